// The page's frame rate while panning a large map (console_pan_bench.sh): fills the page's map
// with N walls, zooms in 2x from the whole map, then for S seconds pans every animation frame,
// as a drag would, and times the frames. Prints frames per second overall and in the worst second, and
// frame-time percentiles; asserts nothing.
//
//   node console_pan.js --url URL [--segments 10000] [--seconds 10] [--chromium PATH]
'use strict';

const { launchChromium } = require('./chromium');

function args() {
  const out = { segments: 10000, seconds: 10, chromium: '/usr/bin/chromium' };
  const argv = process.argv.slice(2);
  for (let i = 0; i < argv.length; i += 2) out[argv[i].replace(/^--/, '')] = argv[i + 1];
  out.segments = Number(out.segments);
  out.seconds = Number(out.seconds);
  return out;
}

async function main() {
  const o = args();
  const { browser, close } = await launchChromium(o.chromium);
  try {
    const page = await browser.newPage();
    await page.goto(o.url, { waitUntil: 'load' });
    await page.waitForFunction(() => window.penaConsole.state.snapshots > 0, { timeout: 10000 });
    const result = await page.evaluate(async (n, seconds, DASHED) => {
      const c = window.penaConsole;
      // Rooms of 4 m on a square grid, walls 1-4 m long with doorway gaps; seeded, so every run
      // draws the same map. Half observed, half plan-only (dashed), as in a mission.
      let seed = 12345;
      const rand = () => ((seed = (seed * 1103515245 + 12345) % 2147483648) / 2147483648);
      const side = Math.ceil(Math.sqrt(n / 2)) * 4;
      for (let id = 1; id <= n; ++id) {
        const x = Math.floor(rand() * side / 4) * 4, y = Math.floor(rand() * side / 4) * 4;
        const len = 1 + 3 * rand();
        const horizontal = id % 2 === 0;
        const observed = DASHED ? (id % 3 ? 1 : 0) : 1;
        c.state.segments.set(id, horizontal ? [x, y, x + len, y, observed] : [x, y, x, y + len, observed]);
      }
      c.mapChanged();
      c.fit();
      c.view.scale *= 2;  // zoomed in on part of the building, as an operator looks at it
      c.redraw();
      const frames = [];
      const start = performance.now();
      const cx0 = c.view.cx, cy0 = c.view.cy;
      await new Promise((resolve) => {
        const step = (t) => {
          frames.push(t);
          const s = (t - start) / 1000;
          // A drag around the map: every frame moves the view, as the mouse does.
          c.view.cx = cx0 + Math.sin(s * 0.8) * side * 0.3;
          c.view.cy = cy0 + Math.cos(s * 0.6) * side * 0.2;
          c.redraw();
          if (s < seconds) requestAnimationFrame(step); else resolve();
        };
        requestAnimationFrame(step);
      });
      return { frames, segments: c.state.segments.size, width: c.view && document.getElementById('map').width,
               height: document.getElementById('map').height };
    }, o.segments, o.seconds, o.dashed !== "no");
    const f = result.frames;
    const dts = [];
    for (let i = 1; i < f.length; ++i) dts.push(f[i] - f[i - 1]);
    const sorted = dts.slice().sort((a, b) => a - b);
    const pct = (q) => sorted[Math.min(sorted.length - 1, Math.floor(q * sorted.length))];
    let worst = Infinity;
    for (let t = f[0]; t + 1000 <= f[f.length - 1]; t += 250) {
      worst = Math.min(worst, f.filter((x) => x >= t && x < t + 1000).length);
    }
    const fps = (f.length - 1) / ((f[f.length - 1] - f[0]) / 1000);
    console.log(`pan over ${result.segments} segments, canvas ${result.width}x${result.height}, ` +
                `${o.seconds} s in headless chromium:`);
    console.log(`  ${fps.toFixed(1)} frames/s overall, ${worst} frames in the worst 1 s window`);
    console.log(`  frame time p50 ${pct(0.5).toFixed(1)} ms, p99 ${pct(0.99).toFixed(1)} ms, max ${pct(1).toFixed(1)} ms`);
  } finally {
    await close();
  }
}

main().catch((e) => { console.error(e.stack || String(e)); process.exit(1); });
