// The operator's traffic across the radio link (console_gateway_test.sh starts everything): a
// console at the command post, behind a pena-gateway pair, and one in the building on the
// team's DDS domain. Checks, in order:
//   1. the command post sees the four entities, with their mission time (not the link's wall
//      clock), and the link's health (far end heard, budget);
//   2. a victim marked by clicks at the command post reaches the building's console, a mark
//      placed in the building reaches the command post, and a retraction crosses too;
//   3. a three-point rotation sent from the command post is applied by pena-fusion in the
//      building: its answer ("applied") comes back to the command post, and the building's
//      console lists it with its operator;
//   4. the age of the poses at the command post's page (writer in the building -> page): p50,
//      p99, printed.
// Prints figures; exits 1 with the reason on the first failed check.
//
//   node console_gateway_test.js --post URL --building URL --out DIR [--post-netns NS]
//        [--building-netns NS] [--entities 4] [--chromium PATH]
'use strict';

const fs = require('fs');
const path = require('path');
const { launchChromium } = require('./chromium');

function args() {
  const out = { entities: 4, chromium: '/usr/bin/chromium', 'post-netns': '', 'building-netns': '' };
  const argv = process.argv.slice(2);
  for (let i = 0; i < argv.length; i += 2) out[argv[i].replace(/^--/, '')] = argv[i + 1];
  out.entities = Number(out.entities);
  for (const key of ['post', 'building', 'out']) if (!out[key]) throw new Error(`--${key} is required`);
  return out;
}

function fail(message) {
  console.error(`FAIL: ${message}`);
  process.exit(1);
}
const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

async function until(what, timeoutMs, probe) {
  const end = Date.now() + timeoutMs;
  let value;
  while (Date.now() < end) {
    value = await probe();
    if (value) return value;
    await sleep(200);
  }
  fail(`${what} within ${timeoutMs / 1000} s`);
  return value;
}

const poses = (page) => page.evaluate(() => {
  const out = {};
  for (const [id, e] of window.penaConsole.state.entities) if (e.pose) out[id] = { ...e.pose, state: e.state };
  return out;
});
const acks = (page) => page.evaluate(() => window.penaConsole.state.messages.filter((m) => m.kind === 'ack').length);

// Clicks a map point (metres) on the canvas.
async function click(page, x, y) {
  const [sx, sy] = await page.evaluate((x, y) => window.penaConsole.toScreen(x, y), x, y);
  const box = await (await page.$('#map')).boundingBox();
  await page.mouse.click(box.x + sx, box.y + sy);
}

// Marks `kind` with `text` by clicks at (x, y) on the page; returns when the console answered.
async function mark(page, kind, text, x, y) {
  await page.bringToFront();
  await page.select('#mark-kind', kind);
  await page.$eval('#mark-text', (el) => { el.value = ''; });
  await page.type('#mark-text', text);
  const before = await acks(page);
  await page.click('#mark');
  await click(page, x, y);
  await until(`no answer to the ${kind} mark`, 5000, async () => (await acks(page)) > before);
}

const marksWith = (page, text) => page.evaluate((t) => [...window.penaConsole.state.annotations.values()]
    .filter((a) => a.text === t), text);

function percentile(values, q) {
  const sorted = values.slice().sort((a, b) => a - b);
  return sorted[Math.min(sorted.length - 1, Math.floor(q * sorted.length))];
}

async function main() {
  const o = args();
  fs.mkdirSync(o.out, { recursive: true });
  const postBrowser = await launchChromium(o.chromium, o['post-netns']);
  const buildingBrowser = await launchChromium(o.chromium, o['building-netns']);
  try {
    await run(o, postBrowser.browser, buildingBrowser.browser);
  } finally {
    await postBrowser.close();
    await buildingBrowser.close();
  }
}

async function run(o, postBrowser, buildingBrowser) {
  const post = await postBrowser.newPage();
  const building = await buildingBrowser.newPage();
  const pageErrors = [];
  for (const page of [post, building]) page.on('pageerror', (e) => pageErrors.push(String(e)));
  await post.goto(o.post, { waitUntil: 'load' });
  await building.goto(o.building, { waitUntil: 'load' });

  // ---- 1. the team and the link, seen from the command post ----
  await until(`${o.entities} entities did not appear at the command post`, 120000,
              async () => Object.keys(await poses(post)).length >= o.entities);
  await sleep(3000);
  const far = await poses(post), near = await poses(building);
  for (const [id, p] of Object.entries(far)) {
    const n = near[id];
    if (!n) fail(`${id} is at the command post but not in the building`);
    console.log(`  ${id}: mission time ${p.stamp_s.toFixed(2)} s at the command post, ${n.stamp_s.toFixed(2)} s in the building`);
    if (!(p.stamp_s < 1e6) || Math.abs(p.stamp_s - n.stamp_s) > 10) {
      fail(`${id}'s pose at the command post is stamped ${p.stamp_s} s, not the mission time (${n.stamp_s} s)`);
    }
  }
  const links = await until('no link health at the command post', 15000, async () => {
    const l = await post.evaluate(() => window.penaConsole.state.links);
    return l.length > 0 && l.every((x) => x.peer_alive) ? l : null;
  });
  for (const l of links) {
    console.log(`link health at the command post: ${l.id} far end heard ${l.peer_heard_age_s.toFixed(2)} s ago, ` +
                `sent ${(l.sent_bit_s / 1000).toFixed(2)} of ${(l.budget_bit_s / 1000).toFixed(2)} kbit/s, ` +
                `${l.frames_rejected} frames rejected`);
  }
  const shownLink = await post.$eval('#links', (el) => el.textContent);
  if (!/far end heard/.test(shownLink)) fail(`the page does not show the link's health: '${shownLink}'`);
  const buildingLinks = await building.evaluate(() => window.penaConsole.state.links);
  if (!buildingLinks.some((l) => l.id === 'building')) fail('the building console shows no report of its gateway');

  // ---- 2. marks both ways ----
  const e = Object.values(far)[0];
  const target = [e.x + 0.5, e.y + 0.5];
  const start = Date.now();
  await mark(post, 'victim_found', 'two people, post', target[0], target[1]);
  const [m] = await until('the command post\'s victim did not reach the building', 30000,
                          async () => { const v = await marksWith(building, 'two people, post'); return v.length ? v : null; });
  // The command post's page shows its own mark when its console's delta arrives, which under
  // load can come after the building's.
  const [placed] = await until('the command post does not show its own victim', 10000,
                               async () => { const v = await marksWith(post, 'two people, post'); return v.length ? v : null; });
  const off = Math.hypot(m.x - placed.x, m.y - placed.y);
  const scale = await post.evaluate(() => window.penaConsole.view.scale);
  const clickPx = Math.hypot(placed.x - target[0], placed.y - target[1]) * scale;
  console.log(`victim marked at the command post (${m.id} by ${m.author}, ${clickPx.toFixed(1)} px from the click) in the ` +
              `building after ${((Date.now() - start) / 1000).toFixed(1)} s, ${(off * 100).toFixed(2)} cm from where it was ` +
              `placed, mission time ${m.stamp_s.toFixed(2)} s`);
  if (clickPx > 2) fail(`the mark is ${clickPx.toFixed(1)} px from where it was clicked`);
  if (off > 0.0075) fail(`the mark crossed ${off.toFixed(4)} m off (the link carries 1 cm)`);
  if (m.kind !== 'victim_found' || m.author !== 'post' || m.retracted) fail(`the mark crossed as ${JSON.stringify(m)}`);
  if (!(m.stamp_s < 1e6)) fail(`the mark's stamp ${m.stamp_s} is not mission time`);
  await mark(building, 'exit', 'exit, building', e.x - 0.5, e.y);
  const [b] = await until('the building\'s mark did not reach the command post', 30000,
                          async () => { const v = await marksWith(post, 'exit, building'); return v.length ? v : null; });
  console.log(`exit marked in the building (${b.id}) at the command post`);
  await post.bringToFront();
  const button = `#annotations li[data-annotation="${m.id}"] button.retract`;
  await post.waitForSelector(button, { timeout: 5000 });
  await post.click(button);
  await until('the retraction did not reach the building', 30000, async () => {
    const v = await marksWith(building, 'two people, post');
    return v.length === 1 && v[0].retracted;
  });
  console.log('retracted at the command post: retracted in the building');
  await post.screenshot({ path: path.join(o.out, 'console_post.png') });

  // ---- 3. an operator's correction across the link, and the fusion's answer back ----
  const id = Object.keys(far).sort()[0];
  const p = (await poses(post))[id];
  const angle = 2 * Math.PI / 180;
  const request = { type: 'rotate', entity: id, origin: [p.x, p.y], wrong: [p.x + 1, p.y],
                    correct: [p.x + Math.cos(angle), p.y + Math.sin(angle)] };
  const before = await acks(post);
  const sentAt = Date.now();
  await post.evaluate((r) => window.penaConsole.send(r), request);
  await until('no answer to the rotation', 5000, async () => (await acks(post)) > before);
  const sent = await post.evaluate(() => window.penaConsole.state.messages.filter((x) => x.kind === 'ack').pop().text);
  console.log(`rotation at the command post: ${sent}`);
  const answered = await until('pena-fusion\'s answer did not come back to the command post', 30000, async () => {
    const c = await post.evaluate(() => window.penaConsole.state.corrections.filter((x) => x.operator === 'post'));
    return c.length === 1 && c[0].state !== 'sent' ? c[0] : null;
  });
  console.log(`  pena-fusion's answer at the command post after ${((Date.now() - sentAt) / 1000).toFixed(1)} s: ` +
              `${answered.state}${answered.refusal ? ' (' + answered.refusal + ')' : ''}`);
  if (answered.state !== 'applied') fail(`the rotation was ${answered.state}: ${answered.refusal}`);
  const listed = await until('the building\'s console does not list the rotation', 10000, async () => {
    const c = await building.evaluate((cid) => window.penaConsole.state.corrections.find((x) => x.id === cid), answered.id);
    return c && c.state === 'applied' ? c : null;
  });
  console.log(`  the building's console lists ${listed.id} by ${listed.operator}, ${listed.kind} ` +
              `${(listed.transform[2] * 180 / Math.PI).toFixed(2)} deg of ${listed.entity} from ${listed.stamp_s.toFixed(2)} s: ${listed.state}`);
  if (listed.operator !== 'post' || Math.abs(listed.transform[2] - angle) > 1e-3) fail('the rotation crossed changed');
  fs.writeFileSync(path.join(o.out, 'correction_id'), `${answered.id}\n`);

  // ---- 4. pose age at the command post ----
  await sleep(10000);
  const ages = await post.evaluate(() => window.penaConsole.state.poseAgesMs.slice());
  if (ages.length < 20) fail(`only ${ages.length} poses reached the command post's page`);
  console.log(`pose age at the command post's page (${ages.length} poses, entity -> link -> page): ` +
              `p50 ${(percentile(ages, 0.5) / 1000).toFixed(2)} s, p99 ${(percentile(ages, 0.99) / 1000).toFixed(2)} s, ` +
              `max ${(percentile(ages, 1) / 1000).toFixed(2)} s`);

  // ---- 5. the walls' support crosses the link: at one map version both pages hold the same
  // walls, who saw each and its estimated error included ----
  const picture = (page) => page.evaluate(() => ({
    version: window.penaConsole.state.mapVersion,
    walls: JSON.stringify([...window.penaConsole.state.segments.entries()].sort((a, b) => a[0] - b[0])),
  }));
  // The command post lags behind the link: the building's pictures are kept by version until the
  // post shows one of them.
  const history = new Map();
  let logged = 0;
  const [atPost, inBuilding] = await until('the command post showed no map version the building had shown', 90000,
                                           async () => {
    const b = await picture(building);
    history.set(b.version, b);
    const p = await picture(post);
    if (Date.now() - logged > 10000) {
      console.log(`  map version ${p.version} at the command post, ${b.version} in the building`);
      logged = Date.now();
    }
    return p.version > 0 && history.has(p.version) ? [p, history.get(p.version)] : null;
  });
  if (atPost.walls !== inBuilding.walls) fail(`at map version ${atPost.version} the command post's walls differ from the building's`);
  const walls = JSON.parse(atPost.walls);
  const lone = walls.filter(([, w]) => w[4] && w[5] === 1).length;
  const several = walls.filter(([, w]) => w[5] >= 2).length;
  console.log(`walls at the command post, map version ${atPost.version}: ${walls.length}, ${lone} seen by one entity, ` +
              `${several} by several, the same as in the building`);
  if (!lone || !several) fail(`the command post's walls carry no support (${lone} lone, ${several} by several)`);
  await post.screenshot({ path: path.join(o.out, 'console_post_end.png') });
  await building.screenshot({ path: path.join(o.out, 'console_building_end.png') });
  if (pageErrors.length) fail(`page errors: ${pageErrors.join('; ')}`);
}

main().catch((e) => fail(e.stack || String(e)));
