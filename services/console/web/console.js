// The PeNa command post page: one WebSocket to pena-console (a snapshot, then deltas), the
// picture drawn on a canvas in the map frame (x right, y up, metres), and the operator's
// gestures (paper section 4.1): three-point rotation, translation, undo, marks, areas.
// window.penaConsole exposes the state for tests.
'use strict';

const CHI2_95_2DOF = 5.991;  // 95 % of a 2-D Gaussian lies within this Mahalanobis distance^2
const PALETTE = ['#1565c0', '#c62828', '#2e7d32', '#6a1b9a', '#ef6c00', '#00838f', '#ad1457',
                 '#4e342e', '#283593', '#558b2f'];

const state = {
  connected: false,
  entities: new Map(),     // id -> {id, kind, state, lifecycle, pose, heard_ms, trail: [[t, x, y]]}
  segments: new Map(),     // id -> [x0, y0, x1, y1, observed, seen_by_entities, error_sd_m, [mapped by]]
  mapVersion: 0,
  annotations: new Map(),  // id -> annotation
  corrections: [],
  links: [],               // the radio link's health, one per pena-gateway endpoint reporting here
  operator: '',
  clockOffsetMs: 0,        // server clock - this browser's clock
  messages: [],            // {kind: 'error' | 'ack' | 'info', text}
  snapshots: 0,
  deltas: 0,
  poseAgesMs: [],          // per new pose in a delta: this browser's clock at arrival - writer's
  poseDdsAgesMs: [],       // the same poses: the console's reception - writer's
};
const view = { cx: 0, cy: 0, scale: 20, fitted: false, follow: '' };
const pick = { active: false, mode: 'rotate', entity: '', mark: '', points: [] };  // the gesture being clicked
let socket = null;
let nextReq = 1;
let dirty = true;

const canvas = document.getElementById('map');
const ctx = canvas.getContext('2d');

// ---- connection ------------------------------------------------------------------------------

function connect() {
  socket = new WebSocket(`ws://${location.host}/ws`);
  socket.onopen = () => { state.connected = true; showLink(); };
  socket.onclose = () => {
    state.connected = false;
    showLink();
    setTimeout(connect, 1000);  // the server sends the whole picture again on reconnect
  };
  socket.onmessage = (event) => {
    let message;
    try { message = JSON.parse(event.data); } catch (e) { note('error', 'bad message from server'); return; }
    receive(message);
  };
}

function send(request) {
  if (!socket || socket.readyState !== WebSocket.OPEN) {
    note('error', 'not connected: nothing sent');
    return 0;
  }
  request.req = nextReq++;
  socket.send(JSON.stringify(request));
  return request.req;
}

function receive(m) {
  if (typeof m.now_ms === 'number') state.clockOffsetMs = m.now_ms - Date.now();
  if (m.type === 'snapshot') {
    state.entities.clear();
    state.segments.clear();
    state.annotations.clear();
    state.corrections = [];
    state.operator = m.operator || '';
    for (const e of m.entities) upsertEntity(e);
    state.mapVersion = m.map.version;
    for (const s of m.map.segments) state.segments.set(s[0], s.slice(1));
    mapChanged = true;
    for (const a of m.annotations) state.annotations.set(a.id, a);
    state.corrections = m.corrections.slice();
    state.links = (m.links || []).slice();
    state.snapshots++;
    if (!view.fitted) fit();
  } else if (m.type === 'delta') {
    const arrivedMs = performance.timeOrigin + performance.now();
    for (const e of m.entities || []) {
      const known = state.entities.get(e.id);
      if (e.pose && e.pose.src_ms > 0 && (!known || !known.pose || known.pose.seq !== e.pose.seq)) {
        state.poseAgesMs.push(arrivedMs - e.pose.src_ms);
        state.poseDdsAgesMs.push(e.pose.rx_ms - e.pose.src_ms);
        if (state.poseAgesMs.length > 200000) { state.poseAgesMs.shift(); state.poseDdsAgesMs.shift(); }
      }
      upsertEntity(e);
    }
    if (m.map) {
      state.mapVersion = m.map.version;
      for (const s of m.map.upsert) state.segments.set(s[0], s.slice(1));
      for (const id of m.map.remove) state.segments.delete(id);
      mapChanged = true;
    }
    for (const a of m.annotations || []) state.annotations.set(a.id, a);
    for (const c of m.corrections || []) {
      const at = state.corrections.findIndex((k) => k.id === c.id);
      if (at >= 0) state.corrections[at] = c; else state.corrections.push(c);
    }
    if (m.links) state.links = m.links;
    state.deltas++;
    if (!view.fitted && state.entities.size > 0) fit();
  } else if (m.type === 'error') {
    note('error', m.message);
  } else if (m.type === 'ack') {
    note('ack', m.message);
  }
  dirty = true;
  // The side panel follows every 500 ms; at once only for what the operator waits for.
  if (m.type !== 'delta' || m.annotations || m.corrections || m.links) renderPanel();
}

function upsertEntity(e) {
  const known = state.entities.get(e.id) || { id: e.id, trail: [] };
  for (const key of ['kind', 'state', 'lifecycle', 'message', 'pose', 'heard_ms', 'corrections_applied']) {
    if (e[key] !== undefined) known[key] = e[key];
  }
  if (e.trail) known.trail = e.trail;
  if (e.trail_add) known.trail.push(...e.trail_add);
  state.entities.set(e.id, known);
}

function note(kind, text) {
  state.messages.push({ kind, text });
  if (state.messages.length > 50) state.messages.shift();
  renderPanel();
}

// ---- view ------------------------------------------------------------------------------------

function toScreen(x, y) {
  return [canvas.width / 2 + (x - view.cx) * view.scale, canvas.height / 2 - (y - view.cy) * view.scale];
}
function toWorld(sx, sy) {
  return [view.cx + (sx - canvas.width / 2) / view.scale, view.cy - (sy - canvas.height / 2) / view.scale];
}

function fit() {
  let lo = [Infinity, Infinity], hi = [-Infinity, -Infinity];
  const take = (x, y) => { lo = [Math.min(lo[0], x), Math.min(lo[1], y)]; hi = [Math.max(hi[0], x), Math.max(hi[1], y)]; };
  for (const s of state.segments.values()) { take(s[0], s[1]); take(s[2], s[3]); }
  for (const e of state.entities.values()) if (e.pose) take(e.pose.x, e.pose.y);
  if (!isFinite(lo[0])) return;
  view.cx = (lo[0] + hi[0]) / 2;
  view.cy = (lo[1] + hi[1]) / 2;
  const w = Math.max(hi[0] - lo[0], 5), h = Math.max(hi[1] - lo[1], 5);
  view.scale = 0.9 * Math.min(canvas.width / w, canvas.height / h);
  view.fitted = true;
  dirty = true;
}

function resize() {
  const r = canvas.getBoundingClientRect();
  canvas.width = Math.max(100, Math.floor(r.width));
  canvas.height = Math.max(100, Math.floor(r.height));
  dirty = true;
}

let drag = null;
canvas.addEventListener('mousedown', (ev) => {
  if (pick.active) return;
  drag = { x: ev.offsetX, y: ev.offsetY, cx: view.cx, cy: view.cy };
});
window.addEventListener('mouseup', () => { drag = null; });
canvas.addEventListener('mousemove', (ev) => {
  if (!drag) {
    const near = wallNear(ev.offsetX, ev.offsetY, 6);
    canvas.title = near ? describeWall(near[0], near[1]) : '';
    return;
  }
  view.cx = drag.cx - (ev.offsetX - drag.x) / view.scale;
  view.cy = drag.cy + (ev.offsetY - drag.y) / view.scale;
  view.follow = '';
  document.getElementById('follow').value = '';
  dirty = true;
});
canvas.addEventListener('wheel', (ev) => {
  ev.preventDefault();
  const [wx, wy] = toWorld(ev.offsetX, ev.offsetY);
  view.scale = Math.min(2000, Math.max(0.2, view.scale * Math.exp(-ev.deltaY * 0.0015)));
  // Zoom about the cursor: the world point under it stays there.
  view.cx = wx - (ev.offsetX - canvas.width / 2) / view.scale;
  view.cy = wy + (ev.offsetY - canvas.height / 2) / view.scale;
  dirty = true;
}, { passive: false });

// ---- the operator's gestures (paper section 4.1) ----------------------------------------------

// What each gesture asks for, click by click.
const PICK_PROMPTS = {
  rotate: ['click the rotation origin on the trail of ', 'click a point in the wrong direction',
           'click the same point in the correct direction'],
  translate: ['click the point to move on the trail of ', 'click where it belongs'],
};
const PICK_NAMES = { rotate: ['origin', 'wrong', 'correct'], translate: ['point', 'belongs'] };

function startPick(mode, entity) {
  if ((mode === 'rotate' || mode === 'translate') && !state.entities.has(entity)) {
    note('error', `${mode}: unknown entity '${entity}'`);
    return;
  }
  pick.active = true;
  pick.mode = mode;
  pick.entity = entity || '';
  pick.mark = '';
  pick.points = [];
  showPrompt();
  dirty = true;
}
function startRotation(entity) { startPick('rotate', entity); }
function startTranslation(entity) { startPick('translate', entity); }
// The next click on the map places a mark of the chosen kind.
function startMark() { startPick('mark', ''); }
// Clicks place the corners of a dangerous area; a click on the first corner (or Enter) closes it.
function startArea() { startPick('area', ''); }
// The next click moves the mark `id` there.
function startMove(id) { startPick('move_mark', ''); pick.mark = id; showPrompt(); }

function retract(id) {
  send({ type: 'retract', id });
}

// The last rotation or translation in force (not undone, not refused): what Undo takes back.
function lastInForce() {
  for (let i = state.corrections.length - 1; i >= 0; --i) {
    const c = state.corrections[i];
    if ((c.kind === 'rotate' || c.kind === 'translate') && !c.undone && c.state !== 'refused') return c;
  }
  return null;
}
function undo() {
  const c = lastInForce();
  if (!c) { note('error', 'undo: no correction in force'); return 0; }
  return send({ type: 'undo', id: c.id });
}

function cancelRotation() {
  pick.active = false;
  pick.points = [];
  showPrompt();
  dirty = true;
}

const mm = (v) => Math.round(v * 1000) / 1000;

function closeArea() {
  if (pick.points.length < 3) { note('error', 'a dangerous area needs at least 3 corners'); return; }
  const text = document.getElementById('mark-text').value;
  send({ type: 'annotate', kind: 'dangerous_area', outline: pick.points.map((p) => [mm(p[0]), mm(p[1])]), text });
  cancelRotation();
}

// Adds one clicked point (map frame); the last one a gesture needs sends its request.
function pickPoint(x, y) {
  if (!pick.active) return;
  if (pick.mode === 'area' && pick.points.length >= 3) {
    const [fx, fy] = toScreen(pick.points[0][0], pick.points[0][1]);
    const [cx, cy] = toScreen(x, y);
    if (Math.hypot(fx - cx, fy - cy) < 10) { closeArea(); return; }
  }
  pick.points.push([x, y]);
  const text = document.getElementById('mark-text').value;
  if (pick.mode === 'mark') {
    send({ type: 'annotate', kind: document.getElementById('mark-kind').value, position: [x, y], text });
    cancelRotation();
  } else if (pick.mode === 'move_mark') {
    send({ type: 'move_mark', id: pick.mark, position: [x, y] });
    cancelRotation();
  } else if (pick.mode === 'rotate' && pick.points.length === 3) {
    const [origin, wrong, correct] = pick.points;
    send({ type: 'rotate', entity: pick.entity, origin, wrong, correct });
    cancelRotation();
  } else if (pick.mode === 'translate' && pick.points.length === 2) {
    const [point, correct] = pick.points;
    send({ type: 'translate', entity: pick.entity, point, correct });
    cancelRotation();
  } else if (pick.mode === 'area' && pick.points.length === 64) {
    closeArea();
  } else {
    showPrompt();
  }
  dirty = true;
}

canvas.addEventListener('click', (ev) => {
  if (!pick.active) return;
  const [x, y] = toWorld(ev.offsetX, ev.offsetY);
  pickPoint(x, y);
});
window.addEventListener('keydown', (ev) => {
  if (ev.key === 'Escape') cancelRotation();
  if (ev.key === 'Enter' && pick.active && pick.mode === 'area') closeArea();
});

function showPrompt() {
  const p = document.getElementById('prompt');
  for (const mode of ['rotate', 'translate', 'mark', 'area']) {
    document.getElementById(mode).classList.toggle('active', pick.active && pick.mode === mode);
  }
  canvas.classList.toggle('picking', pick.active);
  if (!pick.active) { p.textContent = ''; return; }
  const n = pick.points.length;
  if (pick.mode === 'mark') {
    p.textContent = `Mark ${document.getElementById('mark-kind').value}: click the map (Esc cancels)`;
  } else if (pick.mode === 'move_mark') {
    p.textContent = `Move ${pick.mark}: click where it belongs (Esc cancels)`;
  } else if (pick.mode === 'area') {
    p.textContent = `Dangerous area: click its corners (${n} so far); click the first corner or press Enter to close (Esc cancels)`;
  } else {
    const name = pick.mode === 'rotate' ? 'Rotate' : 'Move';
    p.textContent = `${name} ${pick.entity}: ${PICK_PROMPTS[pick.mode][n]}${n === 0 ? pick.entity : ''} (Esc cancels)`;
  }
}

for (const [button, mode] of [['rotate', 'rotate'], ['translate', 'translate']]) {
  document.getElementById(button).addEventListener('click', () => {
    if (pick.active) { cancelRotation(); return; }
    startPick(mode, document.getElementById('rotate-entity').value);
  });
}
document.getElementById('mark').addEventListener('click', () => {
  if (pick.active) { cancelRotation(); return; }
  startMark();
});
document.getElementById('area').addEventListener('click', () => {
  if (pick.active) { cancelRotation(); return; }
  startArea();
});
document.getElementById('undo').addEventListener('click', undo);
document.getElementById('fit').addEventListener('click', fit);
document.getElementById('follow').addEventListener('change', (ev) => { view.follow = ev.target.value; dirty = true; });

// ---- drawing ---------------------------------------------------------------------------------

function colourOf(id) {
  const ids = [...state.entities.keys()].sort();
  return PALETTE[Math.max(0, ids.indexOf(id)) % PALETTE.length];
}

function draw() {
  if (view.follow) {
    const e = state.entities.get(view.follow);
    if (e && e.pose) { view.cx = e.pose.x; view.cy = e.pose.y; }
  }
  ctx.setTransform(1, 0, 0, 1, 0, 0);
  ctx.fillStyle = '#ffffff';
  ctx.fillRect(0, 0, canvas.width, canvas.height);
  drawMap();
  for (const e of state.entities.values()) drawTrail(e);
  for (const a of state.annotations.values()) drawAnnotation(a);
  for (const e of state.entities.values()) drawEntity(e);
  drawPick();
  drawScaleBar();
  drawLegend();
}

// The walls are drawn into a layer three views wide and high around the view, at the view's
// scale; panning blits it, and it is drawn again only when the view leaves it, the scale
// changes or the map changes (a map of 10,000 walls then pans at the display's frame rate).
const wallLayer = { canvas: document.createElement('canvas'), scale: 0, x0: 0, y0: 0, key: '' };
let mapChanged = true;

// How a wall is drawn by the support pena-fusion published for it: walls several entities saw
// (or with no support figure) solid black, walls one entity alone saw faint, plan-only walls
// dashed grey. The confidence the console shows is who saw a wall, not a threshold on its sd.
const WALL_STYLES = [
  { name: 'plan', colour: '#9e9e9e', opacity: 1, width: 1.6, dash: [6, 4], legend: 'plan only' },
  { name: 'one', colour: '#111111', opacity: 0.35, width: 2.2, dash: [], legend: 'seen by one entity' },
  { name: 'team', colour: '#111111', opacity: 1, width: 2.2, dash: [], legend: 'seen by 2+ entities' },
];

function wallStyle(s) {
  if (!s[4]) return WALL_STYLES[0];
  return s[5] === 1 ? WALL_STYLES[1] : WALL_STYLES[2];
}

function drawWalls(c, originX, originY) {
  c.lineCap = 'round';
  for (const style of WALL_STYLES) {
    c.beginPath();
    for (const s of state.segments.values()) {
      if (wallStyle(s) !== style) continue;
      c.moveTo((s[0] - originX) * view.scale, (originY - s[1]) * view.scale);
      c.lineTo((s[2] - originX) * view.scale, (originY - s[3]) * view.scale);
    }
    c.globalAlpha = style.opacity;
    c.strokeStyle = style.colour;
    c.lineWidth = style.width;
    c.setLineDash(style.dash);
    c.stroke();
  }
  c.globalAlpha = 1;
  c.setLineDash([]);
}

// The wall nearest screen point (x, y) within `px` pixels: [id, wall], or null.
function wallNear(x, y, px) {
  const [wx, wy] = toWorld(x, y);
  let best = null, bestD = px / view.scale;
  for (const [id, s] of state.segments) {
    const dx = s[2] - s[0], dy = s[3] - s[1], l2 = dx * dx + dy * dy;
    const t = l2 > 0 ? Math.max(0, Math.min(1, ((wx - s[0]) * dx + (wy - s[1]) * dy) / l2)) : 0;
    const d = Math.hypot(wx - s[0] - t * dx, wy - s[1] - t * dy);
    if (d <= bestD) { best = [id, s]; bestD = d; }
  }
  return best;
}

// A wall's tooltip: who saw it and its estimated error, as pena-fusion published them.
function describeWall(id, s) {
  const length = Math.hypot(s[2] - s[0], s[3] - s[1]).toFixed(2);
  if (!s[4]) return `wall ${id}, ${length} m: plan only`;
  const n = s[5] || 0, names = s[7] || [];
  if (n === 0) return `wall ${id}, ${length} m: observed by ${names.join(', ') || 'an entity'} (no support figure)`;
  let who = `seen by ${n === 1 ? '1 entity' : n + ' entities'}`;
  if (names.length) who += `: ${names.join(', ')}`;
  if (names.length < n) who += ` and ${n - names.length} whose copy the fusion merged away`;
  return `wall ${id}, ${length} m: ${who}; estimated error sd ${s[6].toFixed(2)} m`;
}

function drawMap() {
  const w = canvas.width, h = canvas.height;
  // World coordinates of the view's top-left corner.
  const left = view.cx - w / 2 / view.scale, top = view.cy + h / 2 / view.scale;
  const layer = wallLayer;
  const inside = layer.scale === view.scale && left >= layer.x0 && top <= layer.y0 &&
                 left + w / view.scale <= layer.x0 + layer.canvas.width / view.scale &&
                 top - h / view.scale >= layer.y0 - layer.canvas.height / view.scale;
  if (mapChanged || !inside) {
    layer.canvas.width = 3 * w;
    layer.canvas.height = 3 * h;
    layer.scale = view.scale;
    layer.x0 = left - w / view.scale;
    layer.y0 = top + h / view.scale;
    drawWalls(layer.canvas.getContext('2d'), layer.x0, layer.y0);
    mapChanged = false;
  }
  const dx = Math.round((layer.x0 - left) * view.scale), dy = Math.round((top - layer.y0) * view.scale);
  ctx.drawImage(layer.canvas, dx, dy);
}

function drawTrail(e) {
  if (e.trail.length < 2) return;
  ctx.beginPath();
  e.trail.forEach((p, i) => {
    const [sx, sy] = toScreen(p[1], p[2]);
    if (i === 0) ctx.moveTo(sx, sy); else ctx.lineTo(sx, sy);
  });
  ctx.strokeStyle = colourOf(e.id);
  ctx.globalAlpha = 0.55;
  ctx.lineWidth = 1.5;
  ctx.stroke();
  ctx.globalAlpha = 1;
}

// The 95 % ellipse of the position covariance [xx, xy, yy] (m^2).
function ellipseOf(cov) {
  const [xx, xy, yy] = cov;
  const mean = (xx + yy) / 2, diff = Math.sqrt(((xx - yy) / 2) ** 2 + xy * xy);
  const l1 = Math.max(mean + diff, 0), l2 = Math.max(mean - diff, 0);
  return { a: Math.sqrt(CHI2_95_2DOF * l1), b: Math.sqrt(CHI2_95_2DOF * l2), angle: 0.5 * Math.atan2(2 * xy, xx - yy) };
}

function drawEntity(e) {
  if (!e.pose) return;
  const colour = colourOf(e.id);
  const [sx, sy] = toScreen(e.pose.x, e.pose.y);
  const el = ellipseOf(e.pose.cov);
  if (isFinite(el.a) && isFinite(el.b)) {
    ctx.beginPath();
    ctx.ellipse(sx, sy, Math.max(el.a * view.scale, 0.5), Math.max(el.b * view.scale, 0.5), -el.angle, 0, 2 * Math.PI);
    ctx.strokeStyle = colour;
    ctx.setLineDash([3, 3]);
    ctx.lineWidth = 1.2;
    ctx.stroke();
    ctx.setLineDash([]);
  }
  // The marker: a triangle pointing along the heading (screen y is down).
  const h = e.pose.theta, r = 9;
  ctx.beginPath();
  ctx.moveTo(sx + r * Math.cos(h), sy - r * Math.sin(h));
  ctx.lineTo(sx + r * Math.cos(h + 2.5), sy - r * Math.sin(h + 2.5));
  ctx.lineTo(sx + r * Math.cos(h - 2.5), sy - r * Math.sin(h - 2.5));
  ctx.closePath();
  const live = e.state === 'tracking' || e.state === 'degraded';
  ctx.fillStyle = live ? colour : '#ffffff';
  ctx.strokeStyle = colour;
  ctx.lineWidth = 2;
  ctx.fill();
  ctx.stroke();
  ctx.font = '12px system-ui, sans-serif';
  ctx.fillStyle = '#1d2330';
  const label = e.state === 'tracking' ? e.id : `${e.id} (${e.state}, ${ageText(e)})`;
  ctx.fillText(label, sx + 11, sy - 8);
}

function drawAnnotation(a) {
  if (a.retracted) return;
  const [sx, sy] = toScreen(a.x, a.y);
  if (a.outline && a.outline.length >= 3) {
    ctx.beginPath();
    a.outline.forEach((p, i) => { const [px, py] = toScreen(p[0], p[1]); if (i === 0) ctx.moveTo(px, py); else ctx.lineTo(px, py); });
    ctx.closePath();
    ctx.fillStyle = 'rgba(229, 57, 53, 0.18)';
    ctx.fill();
  } else if (a.radius_m > 0) {
    ctx.beginPath();
    ctx.arc(sx, sy, a.radius_m * view.scale, 0, 2 * Math.PI);
    ctx.fillStyle = 'rgba(229, 57, 53, 0.18)';
    ctx.fill();
  }
  ctx.beginPath();
  ctx.arc(sx, sy, 6, 0, 2 * Math.PI);
  ctx.fillStyle = a.kind === 'victim_found' ? '#d81b60' : '#f9a825';
  ctx.fill();
  ctx.font = '11px system-ui, sans-serif';
  ctx.fillStyle = '#1d2330';
  ctx.fillText(a.text || a.kind, sx + 8, sy + 4);
}

function drawPick() {
  if (!pick.active) return;
  const names = PICK_NAMES[pick.mode] || [];
  ctx.font = '11px system-ui, sans-serif';
  pick.points.forEach((p, i) => {
    const [sx, sy] = toScreen(p[0], p[1]);
    ctx.beginPath();
    ctx.arc(sx, sy, 5, 0, 2 * Math.PI);
    ctx.fillStyle = '#ffb300';
    ctx.fill();
    ctx.fillStyle = '#1d2330';
    if (names[i]) ctx.fillText(names[i], sx + 7, sy - 6);
    if (i > 0) {
      // A rotation's rays from the origin; a translation's arrow; an area's edges.
      const from = pick.mode === 'area' ? pick.points[i - 1] : pick.points[0];
      const [ox, oy] = toScreen(from[0], from[1]);
      ctx.beginPath();
      ctx.moveTo(ox, oy);
      ctx.lineTo(sx, sy);
      ctx.strokeStyle = '#ffb300';
      ctx.lineWidth = 1.5;
      ctx.stroke();
    }
  });
}

function drawScaleBar() {
  // The largest 1-2-5 length that fits in 160 px.
  const target = 160 / view.scale;
  const p = Math.pow(10, Math.floor(Math.log10(target)));
  const length = [5, 2, 1].map((k) => k * p).find((l) => l <= target) || p;
  const px = length * view.scale, x = 16, y = canvas.height - 18;
  ctx.strokeStyle = '#1d2330';
  ctx.lineWidth = 2;
  ctx.beginPath();
  ctx.moveTo(x, y - 5); ctx.lineTo(x, y); ctx.lineTo(x + px, y); ctx.lineTo(x + px, y - 5);
  ctx.stroke();
  ctx.fillStyle = '#1d2330';
  ctx.font = '12px system-ui, sans-serif';
  ctx.fillText(length >= 1 ? `${length} m` : `${Math.round(length * 100)} cm`, x + px + 6, y);
}

function drawLegend() {
  const rows = [...[2, 1, 0].map((i) => ['line', WALL_STYLES[i].colour, WALL_STYLES[i].dash,
                                        WALL_STYLES[i].legend, WALL_STYLES[i].opacity]),
                ['ellipse', '#1d2330', [3, 3], '95 % position', 1], ['dot', '#d81b60', [], 'victim', 1],
                ['dot', '#f9a825', [], 'other mark', 1]];
  const x = canvas.width - 160, y0 = 12;
  ctx.fillStyle = 'rgba(255, 255, 255, 0.85)';
  ctx.fillRect(x - 8, y0 - 4, 160, rows.length * 17 + 6);
  ctx.font = '12px system-ui, sans-serif';
  rows.forEach(([shape, colour, dash, text, opacity], i) => {
    const y = y0 + 8 + i * 17;
    ctx.strokeStyle = colour;
    ctx.fillStyle = colour;
    ctx.setLineDash(dash);
    ctx.lineWidth = 2;
    ctx.globalAlpha = opacity;
    ctx.beginPath();
    if (shape === 'line') { ctx.moveTo(x, y); ctx.lineTo(x + 24, y); ctx.stroke(); }
    if (shape === 'ellipse') { ctx.ellipse(x + 12, y, 11, 5, 0, 0, 2 * Math.PI); ctx.stroke(); }
    if (shape === 'dot') { ctx.arc(x + 12, y, 5, 0, 2 * Math.PI); ctx.fill(); }
    ctx.globalAlpha = 1;
    ctx.setLineDash([]);
    ctx.fillStyle = '#1d2330';
    ctx.fillText(text, x + 32, y + 4);
  });
}

// ---- export --------------------------------------------------------------------------------

const esc = (text) => String(text).replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' }[c]));
const f1 = (v) => v.toFixed(1);

// The picture as the canvas shows it (same view, same symbols), as an SVG document: walls,
// trails, marks and areas, entities with their 95 % ellipses, the scale bar and a caption.
function exportSvg() {
  const w = canvas.width, h = canvas.height, out = [];
  out.push(`<svg xmlns="http://www.w3.org/2000/svg" width="${w}" height="${h}" viewBox="0 0 ${w} ${h}" font-family="sans-serif">`);
  out.push(`<rect width="${w}" height="${h}" fill="#ffffff"/>`);
  for (const style of WALL_STYLES) {
    const d = [];
    for (const seg of state.segments.values()) {
      if (wallStyle(seg) !== style) continue;
      const [ax, ay] = toScreen(seg[0], seg[1]), [bx, by] = toScreen(seg[2], seg[3]);
      d.push(`M${f1(ax)} ${f1(ay)}L${f1(bx)} ${f1(by)}`);
    }
    if (d.length) {
      out.push(`<path class="walls-${style.name}" d="${d.join('')}" fill="none" stroke-linecap="round" stroke="${style.colour}" ` +
               `stroke-width="${style.width}"${style.opacity < 1 ? ` stroke-opacity="${style.opacity}"` : ''}` +
               `${style.dash.length ? ` stroke-dasharray="${style.dash.join(' ')}"` : ''}/>`);
    }
  }
  for (const e of state.entities.values()) {
    if (e.trail.length < 2) continue;
    const pts = e.trail.map((p) => toScreen(p[1], p[2]).map(f1).join(',')).join(' ');
    out.push(`<polyline points="${pts}" fill="none" stroke="${colourOf(e.id)}" stroke-opacity="0.55" stroke-width="1.5"/>`);
  }
  for (const a of state.annotations.values()) {
    if (a.retracted) continue;
    const [sx, sy] = toScreen(a.x, a.y);
    if (a.outline && a.outline.length >= 3) {
      const pts = a.outline.map((p) => toScreen(p[0], p[1]).map(f1).join(',')).join(' ');
      out.push(`<polygon points="${pts}" fill="rgba(229,57,53,0.18)"/>`);
    } else if (a.radius_m > 0) {
      out.push(`<circle cx="${f1(sx)}" cy="${f1(sy)}" r="${f1(a.radius_m * view.scale)}" fill="rgba(229,57,53,0.18)"/>`);
    }
    out.push(`<circle cx="${f1(sx)}" cy="${f1(sy)}" r="6" fill="${a.kind === 'victim_found' ? '#d81b60' : '#f9a825'}"/>`);
    out.push(`<text x="${f1(sx + 8)}" y="${f1(sy + 4)}" font-size="11" fill="#1d2330">${esc(a.text || a.kind)}</text>`);
  }
  for (const e of state.entities.values()) {
    if (!e.pose) continue;
    const colour = colourOf(e.id), [sx, sy] = toScreen(e.pose.x, e.pose.y), el = ellipseOf(e.pose.cov);
    if (isFinite(el.a) && isFinite(el.b)) {
      out.push(`<ellipse cx="${f1(sx)}" cy="${f1(sy)}" rx="${f1(Math.max(el.a * view.scale, 0.5))}" ry="${f1(Math.max(el.b * view.scale, 0.5))}" ` +
               `transform="rotate(${f1(-el.angle * 180 / Math.PI)} ${f1(sx)} ${f1(sy)})" fill="none" stroke="${colour}" stroke-dasharray="3 3" stroke-width="1.2"/>`);
    }
    const hd = e.pose.theta, r = 9;
    const tri = [0, 2.5, -2.5].map((d) => `${f1(sx + r * Math.cos(hd + d))},${f1(sy - r * Math.sin(hd + d))}`).join(' ');
    const live = e.state === 'tracking' || e.state === 'degraded';
    out.push(`<polygon points="${tri}" fill="${live ? colour : '#ffffff'}" stroke="${colour}" stroke-width="2"/>`);
    out.push(`<text x="${f1(sx + 11)}" y="${f1(sy - 8)}" font-size="12" fill="#1d2330">${esc(e.id)}${e.state === 'tracking' ? '' : ' (' + esc(e.state) + ')'}</text>`);
  }
  const target = 160 / view.scale, p10 = Math.pow(10, Math.floor(Math.log10(target)));
  const length = [5, 2, 1].map((k) => k * p10).find((l) => l <= target) || p10;
  const px = length * view.scale, y = h - 18;
  out.push(`<path d="M16 ${y - 5}V${y}H${f1(16 + px)}V${y - 5}" fill="none" stroke="#1d2330" stroke-width="2"/>`);
  out.push(`<text x="${f1(22 + px)}" y="${y}" font-size="12" fill="#1d2330">${length >= 1 ? length + ' m' : Math.round(length * 100) + ' cm'}</text>`);
  const when = new Date(Date.now() + state.clockOffsetMs).toISOString();
  out.push(`<text x="16" y="20" font-size="12" fill="#1d2330">PeNa, ${esc(when)}: ${state.entities.size} entities, ` +
           `map version ${state.mapVersion}, ${state.segments.size} walls</text>`);
  out.push('</svg>');
  return out.join('\n');
}

// The canvas as PNG (a data URL).
function exportPng() {
  draw();
  return canvas.toDataURL('image/png');
}

function download(name, href) {
  const a = document.createElement('a');
  a.href = href;
  a.download = name;
  document.body.appendChild(a);
  a.click();
  a.remove();
}

const stampName = () => new Date(Date.now() + state.clockOffsetMs).toISOString().replace(/[:.]/g, '-');
document.getElementById('export-png').addEventListener('click', () => download(`pena-${stampName()}.png`, exportPng()));
document.getElementById('export-svg').addEventListener('click', () => {
  const url = URL.createObjectURL(new Blob([exportSvg()], { type: 'image/svg+xml' }));
  download(`pena-${stampName()}.svg`, url);
  setTimeout(() => URL.revokeObjectURL(url), 10000);
});

// ---- side panel ------------------------------------------------------------------------------

function ageText(e) {
  if (!e.heard_ms) return 'never';
  const s = (Date.now() + state.clockOffsetMs - e.heard_ms) / 1000;
  return `${Math.max(0, s).toFixed(1)} s`;
}

function renderPanel() {
  const body = document.querySelector('#entities tbody');
  const ids = [...state.entities.keys()].sort();
  body.innerHTML = '';
  for (const id of ids) {
    const e = state.entities.get(id);
    const row = document.createElement('tr');
    const cells = [id, e.state || '', ageText(e), e.pose ? `${e.pose.x.toFixed(2)}, ${e.pose.y.toFixed(2)}` : ''];
    cells.forEach((text, i) => {
      const td = document.createElement('td');
      if (i === 0) {
        const swatch = document.createElement('span');
        swatch.className = 'swatch';
        swatch.style.background = colourOf(id);
        td.appendChild(swatch);
      }
      if (i === 1) td.className = `state-${text}`;
      td.appendChild(document.createTextNode(text));
      row.appendChild(td);
    });
    row.dataset.entity = id;
    body.appendChild(row);
  }
  for (const selectId of ['follow', 'rotate-entity']) {
    const select = document.getElementById(selectId);
    const keep = select.value;
    const have = [...select.options].map((o) => o.value).filter((v) => v);
    if (have.join() !== ids.join()) {
      select.querySelectorAll('option').forEach((o) => { if (o.value) o.remove(); });
      for (const id of ids) select.add(new Option(id, id));
      select.value = keep || (selectId === 'rotate-entity' && ids.length ? ids[0] : '');
    }
  }
  const list = (elementId, items, text, cls) => {
    const el = document.getElementById(elementId);
    el.innerHTML = '';
    for (const item of items) {
      const li = document.createElement('li');
      li.textContent = text(item);
      if (cls) li.className = cls(item);
      el.appendChild(li);
    }
  };
  list('corrections', state.corrections, (c) => {
    const angle = c.transform ? ` ${(c.transform[2] * 180 / Math.PI).toFixed(1)} deg` : '';
    const shift = c.kind === 'translate' && c.transform ? ` (${c.transform[0].toFixed(2)}, ${c.transform[1].toFixed(2)}) m` : '';
    const what = c.kind === 'undo' ? `undo of ${c.undoes}` : `${c.kind}${c.kind === 'rotate' ? angle : shift}`;
    const answer = c.state === 'refused' ? `refused: ${c.refusal}` : c.state;
    return `${c.id}: ${what} of ${c.entity} from ${c.stamp_s.toFixed(1)} s by ${c.operator}: ${answer}${c.undone ? ', undone' : ''}`;
  }, (c) => `correction-${c.state}${c.undone ? ' correction-undone' : ''}`);
  list('links', state.links, linkText, (l) => (l.peer_alive && l.report_age_s < 5 ? 'link-up' : 'link-down'));
  if (!state.links.length) document.getElementById('links').innerHTML = '<li>no pena-gateway reports on this DDS domain</li>';
  // Rebuilt only when the marks change: a button must stay put while the operator clicks it.
  const marks = document.getElementById('annotations');
  const shown = [...state.annotations.values()].filter((m) => !m.retracted);
  const key = JSON.stringify(shown.map((a) => [a.id, a.kind, a.text, a.x, a.y]));
  if (marks.dataset.key !== key) {
    marks.dataset.key = key;
    marks.innerHTML = '';
    for (const a of shown) marks.appendChild(markItem(a));
  }
  list('messages', state.messages.slice().reverse(), (m) => m.text, (m) => m.kind);
}

// One gateway endpoint's report: is the far end heard, how much of the budget is used, what waits.
function linkText(l) {
  const heard = l.peer_heard_age_s < 0 ? 'never heard' : `heard ${l.peer_heard_age_s.toFixed(1)} s ago`;
  const up = l.report_age_s >= 5 ? `no report for ${l.report_age_s.toFixed(0)} s` : l.peer_alive ? 'up' : 'DOWN';
  return `${l.id}: ${up}, far end ${heard}, sent ${(l.sent_bit_s / 1000).toFixed(1)} of ` +
    `${(l.budget_bit_s / 1000).toFixed(1)} kbit/s, ${l.pending_reliable} marks/corrections and ` +
    `${l.pending_map_updates} map updates waiting, ${l.frames_rejected} frames rejected`;
}

// One mark in the side list, with its retract button.
function markItem(a) {
  const li = document.createElement('li');
  li.dataset.annotation = a.id;
  li.textContent = `${a.kind}${a.text ? ': ' + a.text : ''} at ${a.x.toFixed(1)}, ${a.y.toFixed(1)} (${a.author}) `;
  const button = document.createElement('button');
  button.textContent = 'retract';
  button.className = 'retract';
  button.addEventListener('click', () => retract(a.id));
  li.appendChild(button);
  const move = document.createElement('button');
  move.textContent = 'move';
  move.className = 'move';
  move.addEventListener('click', () => startMove(a.id));
  li.appendChild(move);
  return li;
}

function showLink() {
  const el = document.getElementById('link');
  el.textContent = state.connected ? 'live' : 'disconnected';
  el.className = `link ${state.connected ? 'up' : 'down'}`;
}

function frame() {
  if (dirty) { draw(); dirty = false; }
  requestAnimationFrame(frame);
}

// Ages and "stale" move with time alone: the panel refreshes every half second.
setInterval(() => { renderPanel(); dirty = true; }, 500);
window.addEventListener('resize', resize);

window.penaConsole = { state, view, pick, send, toScreen, toWorld, startRotation, startTranslation, startMark, startArea,
                       startMove, retract, undo, lastInForce, pickPoint, closeArea, fit, exportSvg, exportPng,
                       ellipseOf, wallStyle, wallNear, describeWall, redraw: () => { draw(); dirty = false; }, mapChanged: () => { mapChanged = true; } };
resize();
connect();
requestAnimationFrame(frame);
