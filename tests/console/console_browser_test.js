// Drives Debian's chromium (headless, puppeteer-core) against a running pena-console while a team
// mission runs (console_browser_test.sh starts both). Checks, in order:
//   1. the entities appear and move, their markers are drawn where their poses are, and the
//      poses are near the mission's ground truth;
//   2. hostile messages over the WebSocket are refused with an error and change nothing, and the
//      page shows the operator the error;
//   3. a second page, and the same page reloaded, hold the same picture as the first; (--url2) a
//      victim marked on the page reaches a second pena-console over DDS, and so does its
//      retraction;
//   0. (--rotate ENTITY, first, at fixed mission times: the entities run with pena-entity
//      --hold-at T1,T2 and the test releases each hold) the three-point rotation: at T1 the test
//      corrupts the entity's heading by 20 deg through the console; at T2 it clicks the three
//      points on the page (origin, the wrong direction, the correct direction); the entity's
//      published poses over the next 8 s of mission time must be within 0.3 m of the truth and
//      of where its own tracking puts them in its frame before the corruption.
// Prints figures; exits 1 with the reason on the first failed check.
//
//   node console_browser_test.js --url URL --out DIR --mission DIR [--entities 4] [--url2 URL]
//                                [--rotate ff2 --hold-at T1,T2 --logs RUN/logs]
'use strict';

const fs = require('fs');
const net = require('net');
const path = require('path');
const { launchChromium } = require('./chromium');

function args() {
  const out = { entities: 4, chromium: '/usr/bin/chromium', rotate: '' };
  const argv = process.argv.slice(2);
  for (let i = 0; i < argv.length; i += 2) out[argv[i].replace(/^--/, '')] = argv[i + 1];
  out.entities = Number(out.entities);
  for (const key of ['url', 'out', 'mission']) if (!out[key]) throw new Error(`--${key} is required`);
  if (out.rotate) {
    out.holds = String(out['hold-at'] || '').split(',').map(Number);
    if (out.holds.length !== 2 || !out.holds.every(Number.isFinite) || !(out.holds[1] > out.holds[0]) || !out.logs) {
      throw new Error('--rotate needs --hold-at T1,T2 (the entities\' holds, mission s, increasing) and --logs DIR');
    }
  }
  return out;
}

function fail(message) {
  console.error(`FAIL: ${message}`);
  process.exit(1);
}
const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

// TUM trajectory: "stamp x y z qx qy qz qw" per line.
function readTum(file) {
  const rows = [];
  for (const line of fs.readFileSync(file, 'utf8').split('\n')) {
    if (!line || line.startsWith('#')) continue;
    const v = line.trim().split(/\s+/).map(Number);
    rows.push([v[0], v[1], v[2]]);
  }
  return rows;
}
// The truth position at `stamp` (linear between the two nearest rows).
function truthAt(rows, stamp) {
  let lo = 0, hi = rows.length - 1;
  if (stamp <= rows[0][0]) return [rows[0][1], rows[0][2]];
  if (stamp >= rows[hi][0]) return [rows[hi][1], rows[hi][2]];
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (rows[mid][0] <= stamp) lo = mid; else hi = mid;
  }
  const f = (stamp - rows[lo][0]) / (rows[hi][0] - rows[lo][0]);
  return [rows[lo][1] + f * (rows[hi][1] - rows[lo][1]), rows[lo][2] + f * (rows[hi][2] - rows[lo][2])];
}
function truthFile(mission, id) {
  for (const name of ['truth.tum', 'ground_truth.tum']) {
    const file = path.join(mission, id, name);
    if (fs.existsSync(file)) return file;
  }
  const tum = fs.readdirSync(path.join(mission, id)).find((f) => f.includes('truth') && f.endsWith('.tum'));
  if (!tum) throw new Error(`no truth trajectory for ${id} in ${mission}`);
  return path.join(mission, id, tum);
}

async function waitFor(page, predicate, arg, timeoutMs, what) {
  try {
    await page.waitForFunction(predicate, { timeout: timeoutMs, polling: 100 }, arg);
  } catch (e) {
    fail(`${what} within ${timeoutMs / 1000} s`);
  }
}

const poses = (page) => page.evaluate(() => {
  const out = {};
  for (const [id, e] of window.penaConsole.state.entities) if (e.pose) out[id] = { ...e.pose, state: e.state };
  return out;
});

async function main() {
  const o = args();
  fs.mkdirSync(o.out, { recursive: true });
  const { browser, close } = await launchChromium(o.chromium);
  try {
    await run(browser, o);
  } finally {
    await close();
  }
}

async function run(browser, o) {
  const page = await browser.newPage();
  const pageErrors = [];
  page.on('pageerror', (e) => pageErrors.push(String(e)));
  await page.goto(o.url, { waitUntil: 'load' });

  // ---- 1. the entities appear (0. the rotation at its fixed mission times) and move ----
  await waitFor(page, (n) => window.penaConsole.state.connected &&
      [...window.penaConsole.state.entities.values()].filter((e) => e.pose).length >= n,
      o.entities, 120000, `${o.entities} entities with poses did not appear`);
  if (o.rotate) await rotation(page, o, readTum(truthFile(o.mission, o.rotate)));
  // In lockstep an entity ahead of the others waits for them: each must advance within 30 s.
  const first = await poses(page);
  let second = first;
  for (const until = Date.now() + 30000; Date.now() < until;) {
    await sleep(500);
    second = await poses(page);
    if (Object.keys(first).every((id) => second[id].stamp_s > first[id].stamp_s + 2)) break;
  }
  const ids = Object.keys(first).sort();
  console.log(`entities: ${ids.join(' ')}`);
  const truth = {};
  for (const id of ids) {
    truth[id] = readTum(truthFile(o.mission, id));
    const a = first[id], b = second[id];
    const moved = Math.hypot(b.x - a.x, b.y - a.y);
    const t = truthAt(truth[id], b.stamp_s);
    const error = Math.hypot(b.x - t[0], b.y - t[1]);
    console.log(`  ${id}: ${b.state}, stamp ${a.stamp_s.toFixed(1)} -> ${b.stamp_s.toFixed(1)} s, moved ${moved.toFixed(2)} m, ` +
                `${error.toFixed(2)} m from the truth`);
    if (!(b.stamp_s > a.stamp_s)) fail(`${id}'s pose did not advance in 30 s`);
    if (error > 2.0) fail(`${id} is drawn ${error.toFixed(2)} m from its true position (> 2 m)`);
  }
  if (!ids.some((id) => Math.hypot(second[id].x - first[id].x, second[id].y - first[id].y) > 0.3)) {
    fail('no entity moved more than 0.3 m');
  }
  // The markers are drawn where the poses are: the canvas pixel at each marker has its colour.
  const drawn = await page.evaluate(() => {
    const c = window.penaConsole;
    c.redraw();
    const canvas = document.getElementById('map');
    const ctx = canvas.getContext('2d');
    const out = {};
    const palette = ['#1565c0', '#c62828', '#2e7d32', '#6a1b9a', '#ef6c00', '#00838f', '#ad1457', '#4e342e', '#283593', '#558b2f'];
    const ids = [...c.state.entities.keys()].sort();
    for (const [id, e] of c.state.entities) {
      if (!e.pose) continue;
      const [sx, sy] = c.toScreen(e.pose.x, e.pose.y);
      const p = ctx.getImageData(Math.round(sx), Math.round(sy), 1, 1).data;
      const hex = palette[ids.indexOf(id) % palette.length];
      const want = [1, 3, 5].map((i) => parseInt(hex.slice(i, i + 2), 16));
      out[id] = { sx, sy, inside: sx >= 0 && sy >= 0 && sx < canvas.width && sy < canvas.height,
                  match: Math.max(...want.map((w, i) => Math.abs(w - p[i]))) <= 40, pixel: [p[0], p[1], p[2]] };
    }
    return out;
  });
  for (const [id, d] of Object.entries(drawn)) {
    const crowded = Object.entries(drawn).some(([other, e]) => other !== id && Math.hypot(e.sx - d.sx, e.sy - d.sy) < 20);
    if (!d.inside) fail(`${id}'s marker is outside the canvas (${d.sx.toFixed(0)}, ${d.sy.toFixed(0)})`);
    if (!crowded && !d.match) fail(`${id}'s marker pixel is ${d.pixel}, not its colour`);
  }
  await page.screenshot({ path: path.join(o.out, 'console_live.png') });
  console.log(`screenshot ${path.join(o.out, 'console_live.png')}`);

  // ---- 2. hostile input ----
  const hostile = [
    'not json',
    JSON.stringify({ type: 'rotate', entity: 'nobody', origin: [0, 0], wrong: [1, 0], correct: [0, 1] }),
    '{"type":"rotate","entity":"' + ids[0] + '","origin":[0,0],"wrong":[1e999,0],"correct":[0,1]}',
    JSON.stringify({ type: 'rotate', entity: ids[0], origin: [0, 'NaN'], wrong: [1, 0], correct: [0, 1] }),
    JSON.stringify({ type: 'rotate', entity: ids[0], origin: [5000, 5000], wrong: [5001, 5000], correct: [5000, 5001] }),
    JSON.stringify({ type: 'ping', pad: 'x'.repeat(5000) }),
    JSON.stringify({ type: 'shutdown' }),
  ];
  const correctionsBefore = await page.evaluate(() => window.penaConsole.state.corrections.length);
  const replies = await page.evaluate(async (messages) => {
    const ws = new WebSocket(`ws://${location.host}/ws`);
    const got = [];
    await new Promise((resolve) => { ws.onopen = resolve; });
    ws.onmessage = (ev) => { const m = JSON.parse(ev.data); if (m.type === 'error' || m.type === 'ack') got.push(m); };
    for (const m of messages) ws.send(m);
    const until = Date.now() + 5000;
    while (got.length < messages.length && Date.now() < until) await new Promise((r) => setTimeout(r, 50));
    ws.close();
    return got;
  }, hostile);
  if (replies.length !== hostile.length) fail(`${replies.length} answers to ${hostile.length} hostile messages`);
  for (const r of replies) {
    if (r.type !== 'error') fail(`a hostile message was accepted: ${JSON.stringify(r)}`);
    console.log(`  refused: ${r.message}`);
  }
  // Through the page's own connection the operator sees the error.
  await page.evaluate(() => window.penaConsole.send({ type: 'rotate', entity: 'ghost', origin: [0, 0], wrong: [1, 0], correct: [0, 1] }));
  await waitFor(page, () => [...document.querySelectorAll('#messages li.error')].some((li) => li.textContent.includes('ghost')),
                null, 5000, 'the page did not show the error for an unknown entity');
  const corrections = await page.evaluate(() => window.penaConsole.state.corrections.length);
  if (corrections !== correctionsBefore) fail(`${corrections - correctionsBefore} corrections after hostile input (expected none)`);
  console.log(`hostile input: ${hostile.length + 1} messages refused, nothing applied`);

  await stalledBrowsers(page, o);

  // ---- 3. a second page and a reload hold the same picture ----
  const other = await browser.newPage();
  await other.goto(o.url, { waitUntil: 'load' });
  await samePicture(page, other, 'a second page');
  await other.reload({ waitUntil: 'load' });
  await samePicture(page, other, 'the reloaded page');
  await other.close();
  if (o.url2) await annotation(browser, page, o);
  if (o.url2 && !o.rotate) await gestures(browser, page, o);

  await page.screenshot({ path: path.join(o.out, 'console.png') });
  await exports(page, o);
  await confidence(page);
  if (pageErrors.length) fail(`errors in the page: ${pageErrors.join('; ')}`);
  console.log('PASS');
}

// Browsers that stop reading, or vanish without closing, hold nobody back: while three such
// connections are open (one never reads, one vanishes at once, one vanishes mid-stream), the
// page keeps getting its deltas at the tick rate.
async function stalledBrowsers(page, o) {
  const url = new URL(o.url);
  const handshake = `GET /ws HTTP/1.1\r\nHost: ${url.host}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n` +
                    'Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n';
  const open = () => new Promise((resolve, reject) => {
    const socket = net.connect(Number(url.port), url.hostname, () => { socket.write(handshake); resolve(socket); });
    socket.on('error', reject);
  });
  const deltas = () => page.evaluate(() => window.penaConsole.state.deltas);
  const b0 = await deltas(), tb = Date.now();
  await sleep(3000);
  const before = await deltas();
  const t0 = Date.now();
  const baseline = (before - b0) / ((t0 - tb) / 1000);
  const stalled = await open();
  stalled.pause();  // never reads: the console's writes to it back up
  (await open()).destroy();  // gone before the snapshot
  const vanishing = await open();
  await sleep(1000);
  vanishing.resetAndDestroy();  // gone mid-stream, without a close frame (TCP reset)
  await sleep(5000);
  const got = await deltas() - before;
  const seconds = (Date.now() - t0) / 1000;
  stalled.destroy();
  console.log(`stalled and vanished browsers: the page got ${(got / seconds).toFixed(1)} deltas/s meanwhile, ` +
              `${baseline.toFixed(1)} deltas/s just before (tick 50 ms)`);
  if (got / seconds < 0.6 * baseline) fail(`the page got ${got} deltas in ${seconds.toFixed(1)} s beside a stalled browser`);
}

// The page's exports hold the picture: the SVG has every wall and every entity where the canvas
// draws them, the PNG is the canvas.
async function exports(page, o) {
  const shown = await page.evaluate(() => {
    const c = window.penaConsole;
    const out = { svg: c.exportSvg(), png: c.exportPng(), entities: {}, walls: c.state.segments.size };
    for (const [id, e] of c.state.entities) if (e.pose) out.entities[id] = c.toScreen(e.pose.x, e.pose.y);
    return out;
  });
  fs.writeFileSync(path.join(o.out, 'console.svg'), shown.svg);
  fs.writeFileSync(path.join(o.out, 'console_map.png'), Buffer.from(shown.png.split(',')[1], 'base64'));
  const walls = (shown.svg.match(/M[-\d.]+ [-\d.]+L/g) || []).length;
  if (!shown.svg.startsWith('<svg') || walls !== shown.walls) fail(`the SVG holds ${walls} of ${shown.walls} walls`);
  for (const [id, [x, y]] of Object.entries(shown.entities)) {
    // The label sits 11 px right of and 8 px above the marker.
    const label = new RegExp(`<text x="([-\\d.]+)" y="([-\\d.]+)"[^>]*>${id}[<( ]`).exec(shown.svg);
    if (!label || Math.hypot(Number(label[1]) - 11 - x, Number(label[2]) + 8 - y) > 0.2) fail(`${id} is not in the SVG where the canvas draws it`);
  }
  if (!shown.png.startsWith('data:image/png;base64,') || shown.png.length < 10000) fail('the PNG export is empty');
  console.log(`exports: SVG with ${walls} walls and ${Object.keys(shown.entities).length} entities where the canvas has them, ` +
              `PNG of ${Math.round(shown.png.length * 0.75 / 1024)} KiB`);
}

// The support pena-fusion publishes per wall is drawn: a wall one entity alone saw is fainter
// than a wall several entities saw (pixels sampled along each, at the middle of the view), and
// hovering it names who saw it.
async function confidence(page) {
  const pickWalls = () => page.evaluate(() => {
    const walls = [...window.penaConsole.state.segments.entries()]
      .filter(([, s]) => s[4] && Math.hypot(s[2] - s[0], s[3] - s[1]) >= 1.0)
      .sort((a, b) => Math.hypot(b[1][2] - b[1][0], b[1][3] - b[1][1]) - Math.hypot(a[1][2] - a[1][0], a[1][3] - a[1][1]));
    return { lone: walls.find(([, s]) => s[5] === 1), team: walls.find(([, s]) => s[5] >= 2) };
  });
  let walls = await pickWalls();
  for (const until = Date.now() + 30000; (!walls.lone || !walls.team) && Date.now() < until;) {
    await sleep(500);
    walls = await pickWalls();
  }
  if (!walls.lone || !walls.team) fail('no wall of 1 m or more seen by one entity and one seen by several');
  const drawnAt = (wall) => page.evaluate(([id, s]) => {
    const c = window.penaConsole;
    c.view.follow = '';
    c.view.cx = (s[0] + s[2]) / 2;
    c.view.cy = (s[1] + s[3]) / 2;
    c.view.scale = 40;
    c.mapChanged();
    c.redraw();
    const ctx = document.getElementById('map').getContext('2d');
    const grey = [];
    for (const t of [0.3, 0.4, 0.5, 0.6, 0.7]) {
      const [sx, sy] = c.toScreen(s[0] + t * (s[2] - s[0]), s[1] + t * (s[3] - s[1]));
      const p = ctx.getImageData(Math.round(sx), Math.round(sy), 1, 1).data;
      grey.push((p[0] + p[1] + p[2]) / 3);
    }
    grey.sort((a, b) => a - b);
    return { id, grey: grey[2], style: c.wallStyle(s).name, seen: s[5], by: s[7] };
  }, wall);
  const lone = await drawnAt(walls.lone), team = await drawnAt(walls.team);
  console.log(`confidence: wall ${lone.id} (seen by ${lone.by.join(' ')}) drawn ${lone.style}, grey ${lone.grey.toFixed(0)}; ` +
              `wall ${team.id} (seen by ${team.seen}: ${team.by.join(' ')}) drawn ${team.style}, grey ${team.grey.toFixed(0)}`);
  if (lone.style !== 'one' || team.style !== 'team') fail(`walls drawn as ${lone.style} and ${team.style}`);
  if (!(lone.grey > team.grey + 80)) fail(`the lone wall (grey ${lone.grey}) is not drawn fainter than the team's (${team.grey})`);
  // Hovering the lone wall: the tooltip names who saw it.
  await drawnAt(walls.lone);
  const [sx, sy] = await page.evaluate((s) => window.penaConsole.toScreen((s[0] + s[2]) / 2, (s[1] + s[3]) / 2), walls.lone[1]);
  const box = await (await page.$('#map')).boundingBox();
  await page.mouse.move(box.x + sx, box.y + sy);
  const title = await page.evaluate(() => document.getElementById('map').title);
  console.log(`confidence: tooltip "${title}"`);
  if (!title.includes('seen by 1 entity') || !lone.by.every((who) => title.includes(who))) {
    fail(`the tooltip over wall ${lone.id} says "${title}"`);
  }
}

// Both pages at the same map version show the same walls and the same entities.
async function samePicture(a, b, what) {
  const picture = (page) => page.evaluate(() => {
    const s = window.penaConsole.state;
    return { version: s.mapVersion, snapshots: s.snapshots,
             segments: JSON.stringify([...s.segments.entries()].sort((x, y) => x[0] - y[0])),
             entities: [...s.entities.keys()].sort().join(),
             corrections: s.corrections.length, annotations: s.annotations.size };
  });
  const until = Date.now() + 20000;
  for (;;) {
    const [pa, pb] = [await picture(a), await picture(b)];
    if (pb.snapshots >= 1 && pa.version === pb.version && pa.segments === pb.segments &&
        pa.entities === pb.entities && pa.corrections === pb.corrections) {
      console.log(`${what}: same picture at map version ${pa.version} (${JSON.parse(pa.segments).length} segments, entities ${pa.entities})`);
      return;
    }
    if (Date.now() > until) {
      fail(`${what} differs: versions ${pa.version}/${pb.version}, entities ${pa.entities}/${pb.entities}, ` +
           `segments equal ${pa.segments === pb.segments}`);
    }
    await sleep(100);
  }
}

// A victim marked by clicks on the first console's page shows on the second console's page;
// the retraction too.
async function annotation(browser, page, o) {
  const e = Object.values(await poses(page))[0];
  const target = [e.x + 0.5, e.y + 0.5];
  await page.select('#mark-kind', 'victim_found');
  await page.type('#mark-text', 'two people, test');
  const acks = await page.evaluate(() => window.penaConsole.state.messages.filter((m) => m.kind === 'ack').length);
  await page.click('#mark');
  await click(page, target[0], target[1]);
  await waitFor(page, (n) => window.penaConsole.state.messages.filter((m) => m.kind === 'ack').length > n,
                acks, 5000, 'no answer to the mark');
  const second = await browser.newPage();
  await second.goto(o.url2, { waitUntil: 'load' });
  const seen = () => second.evaluate(() => [...window.penaConsole.state.annotations.values()]
      .filter((a) => a.kind === 'victim_found' && a.text === 'two people, test'));
  const until = Date.now() + 15000;
  let marks = [];
  while (Date.now() < until && (marks = await seen()).length === 0) await sleep(100);
  if (marks.length !== 1) fail(`the second console shows ${marks.length} victim marks (expected 1)`);
  const m = marks[0];
  const scale = await page.evaluate(() => window.penaConsole.view.scale);
  const offPx = Math.hypot(m.x - target[0], m.y - target[1]) * scale;
  console.log(`victim marked at (${m.x.toFixed(2)}, ${m.y.toFixed(2)}) by ${m.author}: on the second console, ` +
              `${offPx.toFixed(1)} px from the click`);
  if (offPx > 2) fail(`the mark is ${offPx.toFixed(1)} px from where it was clicked`);
  if (m.retracted) fail('the mark arrived retracted');
  await page.bringToFront();  // a background tab gets no animation frames, which clicks wait for
  const button = `#annotations li[data-annotation="${m.id}"] button.retract`;
  await page.waitForSelector(button, { timeout: 5000 });
  await page.click(button);
  while (Date.now() < until + 10000 && !(await second.evaluate((id) => {
    const a = window.penaConsole.state.annotations.get(id);
    return a && a.retracted;
  }, m.id))) await sleep(100);
  const retracted = await second.evaluate((id) => window.penaConsole.state.annotations.get(id).retracted, m.id);
  if (!retracted) fail('the retraction did not reach the second console');
  console.log('retracted on the first console: retracted on the second');
  await second.close();
  await page.bringToFront();
}

// The other gestures, by clicks on the page: a translation and its undo (each answered
// "applied" by pena-fusion, listed with its operator), a dangerous area drawn as a polygon and a
// mark moved, both seen at the second console.
async function gestures(browser, page, o) {
  await page.bringToFront();
  const ids = Object.keys(await poses(page)).sort();
  const id = ids[ids.length - 1];
  const p = (await poses(page))[id];
  await page.select('#rotate-entity', id);
  let n = await ackCount(page);
  await page.click('#translate');
  await click(page, p.x, p.y);
  await click(page, p.x + 0.4, p.y - 0.3);
  await waitFor(page, (k) => window.penaConsole.state.messages.filter((m) => m.kind === 'ack').length > k, n, 5000,
                'no answer to the clicked translation');
  const applied = async (kind) => {
    const until = Date.now() + 20000;
    let c = null;
    while (Date.now() < until) {
      c = await page.evaluate((k) => window.penaConsole.state.corrections.filter((x) => x.kind === k).pop(), kind);
      if (c && c.state !== 'sent') break;
      await sleep(200);
    }
    if (!c || c.state !== 'applied') fail(`the ${kind} was not applied by pena-fusion: ${JSON.stringify(c)}`);
    return c;
  };
  const shift = await applied('translate');
  console.log(`translation of ${id} by (${shift.transform[0].toFixed(2)}, ${shift.transform[1].toFixed(2)}) m from ` +
              `${shift.stamp_s.toFixed(1)} s by ${shift.operator}: ${shift.state}`);
  // Two clicks, each within a pixel of its point: the shift within 2 px.
  const px = 1 / await page.evaluate(() => window.penaConsole.view.scale);
  if (Math.abs(shift.transform[0] - 0.4) > 2 * px || Math.abs(shift.transform[1] + 0.3) > 2 * px) {
    fail(`the translation is not what was clicked (1 px = ${px.toFixed(3)} m)`);
  }
  n = await ackCount(page);
  await page.click('#undo');
  await waitFor(page, (k) => window.penaConsole.state.messages.filter((m) => m.kind === 'ack').length > k, n, 5000,
                'no answer to undo');
  const undo = await applied('undo');
  const undone = await page.evaluate((cid) => window.penaConsole.state.corrections.find((x) => x.id === cid), shift.id);
  console.log(`undo ${undo.id} of ${undo.undoes}: ${undo.state}; ${shift.id} undone: ${undone.undone}`);
  if (undo.undoes !== shift.id || !undone.undone) fail('the undo did not take the translation back');
  const listed = await page.$eval('#corrections', (el) => el.textContent);
  if (!listed.includes(`undo of ${shift.id}`) || !listed.includes(`by ${shift.operator}`)) {
    fail(`the corrections list does not say it: ${listed}`);
  }
  // A second undo has nothing in force for that entity's last translation: refused, shown.
  const refusedBefore = await page.evaluate(() => window.penaConsole.state.messages.filter((m) => m.kind === 'error').length);
  await page.evaluate((cid) => window.penaConsole.send({ type: 'undo', id: cid }), shift.id);
  await waitFor(page, (k) => window.penaConsole.state.messages.filter((m) => m.kind === 'error').length > k,
                refusedBefore, 5000, 'undoing an undone correction was not refused');

  // A dangerous area: four corners clicked, closed on the first.
  const corners = [[p.x + 1, p.y + 1], [p.x + 3, p.y + 1], [p.x + 3, p.y + 2.5], [p.x + 1, p.y + 2.5]];
  await page.$eval('#mark-text', (el) => { el.value = ''; });
  await page.type('#mark-text', 'gas, test');
  n = await ackCount(page);
  await page.click('#area');
  for (const c of corners) await click(page, c[0], c[1]);
  await click(page, corners[0][0], corners[0][1]);
  await waitFor(page, (k) => window.penaConsole.state.messages.filter((m) => m.kind === 'ack').length > k, n, 5000,
                'no answer to the dangerous area');
  const second = await browser.newPage();
  await second.goto(o.url2, { waitUntil: 'load' });
  const area = async () => second.evaluate(() => [...window.penaConsole.state.annotations.values()]
      .find((a) => a.text === 'gas, test'));
  let a = null;
  for (const until = Date.now() + 15000; Date.now() < until && !(a = await area());) await sleep(100);
  if (!a || a.kind !== 'dangerous_area' || a.outline.length !== 4) fail(`the area reached the second console as ${JSON.stringify(a)}`);
  const worst = Math.max(...a.outline.map((q, i) => Math.hypot(q[0] - corners[i][0], q[1] - corners[i][1])));
  console.log(`dangerous area of ${a.outline.length} corners on the second console, corners within ${(worst * 100).toFixed(1)} cm of the clicks`);
  if (worst > 0.1) fail('the area\'s corners are not where they were clicked');
  // Move it by clicks: its outline moves with it.
  await page.bringToFront();
  const button = `#annotations li[data-annotation="${a.id}"] button.move`;
  await page.waitForSelector(button, { timeout: 5000 });
  n = await ackCount(page);
  await page.click(button);
  await click(page, a.x + 1, a.y - 1);
  await waitFor(page, (k) => window.penaConsole.state.messages.filter((m) => m.kind === 'ack').length > k, n, 5000,
                'no answer to the move');
  let moved = a;
  for (const until = Date.now() + 15000; Date.now() < until && Math.abs(moved.x - a.x - 1) > 0.05;) {
    await sleep(100);
    moved = await area();
  }
  console.log(`moved on the first console: at (${moved.x.toFixed(2)}, ${moved.y.toFixed(2)}) on the second, ` +
              `first corner (${moved.outline[0][0].toFixed(2)}, ${moved.outline[0][1].toFixed(2)})`);
  if (Math.abs(moved.x - a.x - 1) > 0.05 || Math.abs(moved.outline[0][1] - a.outline[0][1] + 1) > 0.05) {
    fail('the move did not reach the second console');
  }
  await page.screenshot({ path: path.join(o.out, 'console_gestures.png') });
  await second.close();
  await page.bringToFront();
}

const ackCount = (page) => page.evaluate(() => window.penaConsole.state.messages.filter((m) => m.kind === 'ack').length);

// Clicks a map point (metres) on the canvas.
async function click(page, x, y) {
  const [sx, sy] = await page.evaluate((x, y) => window.penaConsole.toScreen(x, y), x, y);
  const box = await (await page.$('#map')).boundingBox();
  await page.mouse.click(box.x + sx, box.y + sy);
}

// Rigid 2-D poses [x, y, theta]: a * b, and the inverse.
const compose = (a, b) => [a[0] + Math.cos(a[2]) * b[0] - Math.sin(a[2]) * b[1],
                           a[1] + Math.sin(a[2]) * b[0] + Math.cos(a[2]) * b[1], a[2] + b[2]];
const inverse = (a) => [-Math.cos(a[2]) * a[0] - Math.sin(a[2]) * a[1],
                        Math.sin(a[2]) * a[0] - Math.cos(a[2]) * a[1], -a[2]];

// The three-point rotation (paper section 4.1), at fixed mission times. This run goes without
// the fusion's corrections, so the entity's own tracking drifts from the truth as the mission
// goes (ff2: under 0.07 m up to 45 s of mission time, 0.15-0.25 m at 47-80 s, 0.3-0.6 m later;
// `pena odometry` on its log against its truth.tum). The team's entities hold their clocks
// (pena-entity --hold-at T1,T2) and this test releases them: the corruption is sent at T1, the
// rotation clicked at T2, and the poses checked are those of T2 to T2 + 8 s, whatever the load
// made of the wall time in between. Each hold: every entity's log says it holds (and its pid),
// the page has the entity's last pose, the correction sent is applied by the entity while it
// holds (its log says so), then every entity gets SIGUSR1.
async function rotation(page, o, truth) {
  const id = o.rotate;
  const [t1, t2] = o.holds;
  const windowS = 8;
  const truthError = (p) => { const t = truthAt(truth, p.stamp_s); return Math.hypot(p.x - t[0], p.y - t[1]); };
  const ids = Object.keys(await poses(page)).sort();
  const h1 = await held(page, o, ids, 1);
  const before = (await poses(page))[id];
  if (!before.odom) fail(`the page's pose of ${id} has no odometry frame`);
  // Where the entity's own tracking, in its frame before the corruption, puts a pose.
  const mapFromOdom = compose([before.x, before.y, before.theta], inverse(before.odom));
  const uncorrupted = (p) => compose(mapFromOdom, p.odom);
  const frameError = (p) => { const u = uncorrupted(p); return Math.hypot(p.x - u[0], p.y - u[1]); };
  console.log(`rotation: the team holds at ${t1} s of mission time; ${id} at (${before.x.toFixed(2)}, ${before.y.toFixed(2)}) ` +
              `at ${before.stamp_s.toFixed(2)} s, ${truthError(before).toFixed(2)} m from the truth`);
  // Corrupt: +20 deg about where it is now (a heading error the operator must fix).
  const c = Math.cos(20 * Math.PI / 180), s = Math.sin(20 * Math.PI / 180);
  const corrupt = await ack(page, { type: 'rotate', entity: id, origin: [before.x, before.y],
                                    wrong: [before.x + 1, before.y], correct: [before.x + c, before.y + s] });
  console.log(`  corrupted: ${corrupt}`);
  await appliedWhileHeld(o, id, 1);
  release(h1);
  // It walks in the wrong frame until T2.
  const h2 = await held(page, o, ids, 2);
  const off = (await poses(page))[id];
  console.log(`  held at ${t2} s: ${id} walked in the wrong frame to (${off.x.toFixed(2)}, ${off.y.toFixed(2)}) ` +
              `(${off.stamp_s.toFixed(2)} s), ${frameError(off).toFixed(2)} m from where its own frame puts it`);
  if (frameError(off) < 0.5) fail(`the 20 deg corruption moved ${id} only ${frameError(off).toFixed(2)} m: nothing to fix`);
  await page.screenshot({ path: path.join(o.out, 'console_corrupted.png') });
  // The operator's three clicks: the origin where the heading went wrong, the entity where the
  // wrong frame puts it, and where it belongs (where its own tracking in its frame before the
  // corruption puts it: its new walls line up with those it mapped before). The operator zooms
  // in on the three first: at the whole map's scale a pixel is 5-6 cm, a degree at 3 m.
  const right = uncorrupted(off);
  await page.evaluate((pts) => {
    const c = window.penaConsole;
    const xs = pts.map((p) => p[0]), ys = pts.map((p) => p[1]);
    const canvas = document.getElementById('map');
    c.view.follow = '';
    c.view.cx = (Math.min(...xs) + Math.max(...xs)) / 2;
    c.view.cy = (Math.min(...ys) + Math.max(...ys)) / 2;
    c.view.scale = 0.6 * Math.min(canvas.width / (Math.max(...xs) - Math.min(...xs) + 1),
                                  canvas.height / (Math.max(...ys) - Math.min(...ys) + 1));
    c.redraw();
  }, [[before.x, before.y], [off.x, off.y], right]);
  const scale = await page.evaluate(() => window.penaConsole.view.scale);
  await page.select('#rotate-entity', id);
  await page.click('#rotate');
  const acks = await page.evaluate(() => window.penaConsole.state.messages.filter((m) => m.kind === 'ack').length);
  await click(page, before.x, before.y);
  await click(page, off.x, off.y);
  await click(page, right[0], right[1]);
  await waitFor(page, (n) => window.penaConsole.state.messages.filter((m) => m.kind === 'ack').length > n,
                acks, 5000, 'no answer to the clicked rotation');
  const answer = await page.evaluate(() => window.penaConsole.state.messages.filter((m) => m.kind === 'ack').pop().text);
  console.log(`  clicked rotation at ${scale.toFixed(0)} px/m: ${answer}`);
  await appliedWhileHeld(o, id, 2);
  release(h2);
  // The entity's published poses from T2 to T2 + 8 s of mission time.
  const samples = [];
  for (const until = Date.now() + 60000; Date.now() < until;) {
    const p = (await poses(page))[id];
    if (p.stamp_s > t2 + windowS) break;
    if (p.stamp_s > t2 && (!samples.length || p.stamp_s > samples[samples.length - 1].stamp)) {
      const t = truthAt(truth, p.stamp_s), u = uncorrupted(p);
      samples.push({ stamp: p.stamp_s, frame: frameError(p), truth: truthError(p), drift: Math.hypot(u[0] - t[0], u[1] - t[1]),
                     from_origin: Math.hypot(p.x - before.x, p.y - before.y) });
    }
    await sleep(100);
  }
  if (samples.length < 5) fail(`${samples.length} poses of ${id} seen between ${t2} and ${t2 + windowS} s of mission time (expected >= 5)`);
  const worst = (key) => Math.max(...samples.map((x) => x[key]));
  const line = (key) => samples.map((x) => x[key].toFixed(2)).join(' ');
  const far = samples.map((x) => x.from_origin);
  console.log(`  after the rotation: ${samples.length} poses at ${samples[0].stamp.toFixed(2)}-${samples[samples.length - 1].stamp.toFixed(2)} s, ` +
              `${Math.min(...far).toFixed(1)}-${Math.max(...far).toFixed(1)} m from the origin:`);
  console.log(`    from the truth:     ${line('truth')} m (worst ${worst('truth').toFixed(2)} m, limit 0.3 m)`);
  console.log(`    from its own frame: ${line('frame')} m (worst ${worst('frame').toFixed(2)} m, limit 0.3 m)`);
  console.log(`    its own drift:      ${line('drift')} m`);
  if (worst('truth') > 0.3) fail(`${id} is ${worst('truth').toFixed(2)} m from the truth after the rotation (> 0.3 m)`);
  if (worst('frame') > 0.3) fail(`${id} is ${worst('frame').toFixed(2)} m from its own frame after the rotation (> 0.3 m)`);
  const listed = await page.evaluate(() => window.penaConsole.state.corrections.length);
  if (listed !== 2) fail(`${listed} corrections listed (expected 2)`);
  await page.click('#fit');  // the whole picture again for the later checks and screenshots
}

// pena-entity --hold-at's lines in an entity's log (deploy/demo/run-team.sh writes LOGS/<id>.log).
const heldLine = /held at ([\d.]+) s of mission time \(last pose ([\d.]+) s\); SIGUSR1 to pid (\d+) releases hold (\d+)/g;
const logOf = (o, id) => { try { return fs.readFileSync(path.join(o.logs, `${id}.log`), 'utf8'); } catch (e) { return ''; } };

// Waits until every entity holds at hold number `k` and the page has `o.rotate`'s last pose
// before it; returns the pids to release.
async function held(page, o, ids, k) {
  const found = {};
  for (const until = Date.now() + 180000; Object.keys(found).length < ids.length;) {
    if (Date.now() > until) fail(`not every entity held at ${o.holds[k - 1]} s within 180 s: ${Object.keys(found).join(' ') || 'none'} did`);
    for (const id of ids) {
      for (const m of logOf(o, id).matchAll(heldLine)) {
        if (Number(m[4]) === k) found[id] = { pid: Number(m[3]), last: Number(m[2]) };
      }
    }
    await sleep(100);
  }
  const last = found[o.rotate].last;
  await waitFor(page, ([id, s]) => Math.abs(window.penaConsole.state.entities.get(id).pose.stamp_s - s) < 1e-3,
                [o.rotate, last], 10000, `the page did not get ${o.rotate}'s pose of ${last} s, its last before the hold`);
  return Object.values(found).map((f) => f.pid);
}

// Waits until the entity's log says it applied a correction during hold `k`.
async function appliedWhileHeld(o, id, k) {
  for (const until = Date.now() + 20000; Date.now() < until; await sleep(100)) {
    const text = logOf(o, id);
    const start = text.indexOf(`releases hold ${k}\n`);
    if (start >= 0 && /held: correction \d+ applied/.test(text.slice(start))) return;
  }
  fail(`${o.rotate} did not apply the correction during its hold ${k} (no "held: correction ... applied" in its log)`);
}

const release = (pids) => { for (const pid of pids) process.kill(pid, 'SIGUSR1'); };

// Sends a request through the page's connection and waits for its ack.
async function ack(page, request) {
  const n = await page.evaluate(() => window.penaConsole.state.messages.length);
  await page.evaluate((r) => window.penaConsole.send(r), request);
  await waitFor(page, (n) => window.penaConsole.state.messages.length > n, n, 5000, 'no answer to a rotation');
  const last = await page.evaluate(() => window.penaConsole.state.messages[window.penaConsole.state.messages.length - 1]);
  if (last.kind !== 'ack') fail(`rotation refused: ${last.text}`);
  return last.text;
}

main().catch((e) => fail(e.stack || String(e)));
