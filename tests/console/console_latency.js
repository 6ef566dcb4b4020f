// The pose age a browser sees: opens the console page in Debian's chromium (headless) and, for
// `--seconds`, collects the page's poseAgesMs (arrival in the page's WebSocket handler minus the
// DDS writer's source timestamp, same machine clock) of every new pose in a delta. Prints the
// count and p50 / p90 / p99 / max in ms, and the same for the DDS part alone (writer to
// pena-console's reception). Run by console_latency_bench.sh.
//
//   node console_latency.js --url URL --seconds 40 [--chromium /usr/bin/chromium]
'use strict';

const { launchChromium } = require('./chromium');

const o = { seconds: 40, chromium: '/usr/bin/chromium', warmup: 5 };
const argv = process.argv.slice(2);
for (let i = 0; i < argv.length; i += 2) o[argv[i].replace(/^--/, '')] = argv[i + 1];

function quantile(sorted, q) {
  return sorted[Math.min(sorted.length - 1, Math.floor(q * sorted.length))];
}

(async () => {
  const { browser, close } = await launchChromium(o.chromium);
  try {
    const page = await browser.newPage();
    await page.goto(o.url, { waitUntil: 'load' });
    await page.waitForFunction(() => window.penaConsole.state.poseAgesMs.length > 0,
                               { timeout: 120000, polling: 200 });
    // The first seconds (discovery, the snapshot) are not the steady state.
    await new Promise((r) => setTimeout(r, Number(o.warmup) * 1000));
    await page.evaluate(() => {
      window.penaConsole.state.poseAgesMs.length = 0;
      window.penaConsole.state.poseDdsAgesMs.length = 0;
    });
    await new Promise((r) => setTimeout(r, Number(o.seconds) * 1000));
    const result = await page.evaluate(() => ({
      ages: window.penaConsole.state.poseAgesMs.slice(),
      ddsAges: window.penaConsole.state.poseDdsAgesMs.slice(),
      entities: window.penaConsole.state.entities.size,
    }));
    const ages = result.ages.sort((a, b) => a - b);
    const ddsAges = result.ddsAges.sort((a, b) => a - b);
    if (!ages.length) throw new Error('no pose arrived');
    const f = (v) => v.toFixed(1);
    console.log(`of which writer -> pena-console (DDS): p50 ${f(quantile(ddsAges, 0.5))} ms, ` +
                `p90 ${f(quantile(ddsAges, 0.9))} ms, p99 ${f(quantile(ddsAges, 0.99))} ms, ` +
                `max ${f(ddsAges[ddsAges.length - 1])} ms`);
    console.log(`${result.entities} entities, ${ages.length} poses in ${o.seconds} s ` +
                `(${(ages.length / Number(o.seconds)).toFixed(1)} per s): pose age at the browser ` +
                `p50 ${f(quantile(ages, 0.5))} ms, p90 ${f(quantile(ages, 0.9))} ms, ` +
                `p99 ${f(quantile(ages, 0.99))} ms, max ${f(ages[ages.length - 1])} ms`);
  } finally {
    await close();
  }
})().catch((e) => { console.error(e.stack || String(e)); process.exit(1); });
