// A screenshot of the console page as a browser shows it: Debian's chromium (headless) opens
// the page, waits for the picture (a snapshot with at least one entity), fits the view and
// writes a PNG. Used by deploy/demo/run-team.sh for OUT/console.png.
//
//   node console_shot.js --url URL --out FILE.png [--chromium /usr/bin/chromium]
'use strict';

const { launchChromium } = require('./chromium');

const o = { chromium: '/usr/bin/chromium' };
const argv = process.argv.slice(2);
for (let i = 0; i < argv.length; i += 2) o[argv[i].replace(/^--/, '')] = argv[i + 1];
if (!o.url || !o.out) {
  console.error('usage: node console_shot.js --url URL --out FILE.png');
  process.exit(1);
}

(async () => {
  const { browser, close } = await launchChromium(o.chromium);
  try {
    const page = await browser.newPage();
    await page.goto(o.url, { waitUntil: 'load' });
    await page.waitForFunction(() => window.penaConsole.state.snapshots > 0 &&
                               window.penaConsole.state.entities.size > 0, { timeout: 20000, polling: 100 });
    await page.evaluate(() => { window.penaConsole.fit(); window.penaConsole.redraw(); });
    await new Promise((r) => setTimeout(r, 700));  // the side panel refreshes every 500 ms
    await page.screenshot({ path: o.out });
  } finally {
    await close();
  }
})().catch((e) => { console.error(e.stack || String(e)); process.exit(1); });
