// The console's picture from the command line: Debian's chromium (headless) opens a running
// pena-console's page, waits for the picture (a snapshot with at least --min-entities entities),
// fits the view and writes FILE: .svg the picture as SVG (the page's "SVG" export), .png a
// screenshot of the whole page, or with --map-only yes the map's canvas alone (the page's "PNG"
// export). Needs no ground truth: it draws what the console holds (fusion's global map, the
// poses and trails, marks and corrections), so it serves real missions as well as simulated
// ones. Used by deploy/demo/run-team.sh for OUT/console.png and OUT/console.svg.
//
//   node console_shot.js --url URL --out FILE.png|FILE.svg [--map-only yes] [--min-entities 1]
//                        [--width 1280] [--height 800] [--chromium /usr/bin/chromium]
'use strict';

const fs = require('fs');
const { launchChromium } = require('./chromium');

const o = { chromium: '/usr/bin/chromium', 'min-entities': '1', 'map-only': 'no', width: '1280', height: '800' };
const argv = process.argv.slice(2);
for (let i = 0; i < argv.length; i += 2) o[argv[i].replace(/^--/, '')] = argv[i + 1];
if (!o.url || !o.out || !/\.(png|svg)$/.test(o.out)) {
  console.error('usage: node console_shot.js --url URL --out FILE.png|FILE.svg [--map-only yes] [--min-entities N]');
  process.exit(1);
}

(async () => {
  const { browser, close } = await launchChromium(o.chromium);
  try {
    const page = await browser.newPage();
    await page.setViewport({ width: Number(o.width), height: Number(o.height) });
    await page.goto(o.url, { waitUntil: 'load' });
    await page.waitForFunction((n) => window.penaConsole.state.snapshots > 0 &&
                               window.penaConsole.state.entities.size >= n,
                               { timeout: 20000, polling: 100 }, Number(o['min-entities']));
    await page.evaluate(() => { window.penaConsole.fit(); window.penaConsole.redraw(); });
    await new Promise((r) => setTimeout(r, 700));  // the side panel refreshes every 500 ms
    if (o.out.endsWith('.svg')) {
      fs.writeFileSync(o.out, await page.evaluate(() => window.penaConsole.exportSvg()));
    } else if (o['map-only'] === 'yes') {
      const url = await page.evaluate(() => window.penaConsole.exportPng());
      fs.writeFileSync(o.out, Buffer.from(url.replace(/^data:image\/png;base64,/, ''), 'base64'));
    } else {
      await page.screenshot({ path: o.out });
    }
  } finally {
    await close();
  }
})().catch((e) => { console.error(e.stack || String(e)); process.exit(1); });
