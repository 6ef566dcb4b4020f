// The PeNa command post page: one WebSocket to pena-console (a snapshot, then deltas), the
// picture drawn on a canvas in the map frame (x right, y up, metres), and the operator's
// three-point rotation (paper section 4.1). window.penaConsole exposes the state for tests.
'use strict';

const CHI2_95_2DOF = 5.991;  // 95 % of a 2-D Gaussian lies within this Mahalanobis distance^2
const PALETTE = ['#1565c0', '#c62828', '#2e7d32', '#6a1b9a', '#ef6c00', '#00838f', '#ad1457',
                 '#4e342e', '#283593', '#558b2f'];

const state = {
  connected: false,
  entities: new Map(),     // id -> {id, kind, state, lifecycle, pose, heard_ms, trail: [[t, x, y]]}
  segments: new Map(),     // id -> [x0, y0, x1, y1, observed]
  mapVersion: 0,
  annotations: new Map(),  // id -> annotation
  corrections: [],
  operator: '',
  clockOffsetMs: 0,        // server clock - this browser's clock
  messages: [],            // {kind: 'error' | 'ack' | 'info', text}
  snapshots: 0,
  deltas: 0,
  poseAgesMs: [],          // per new pose in a delta: this browser's clock at arrival - writer's
  poseDdsAgesMs: [],       // the same poses: the console's reception - writer's
};
const view = { cx: 0, cy: 0, scale: 20, fitted: false, follow: '' };
const pick = { active: false, mode: 'rotate', entity: '', points: [] };  // the gesture being clicked
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
    for (const a of m.annotations) state.annotations.set(a.id, a);
    state.corrections = m.corrections.slice();
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
    }
    for (const a of m.annotations || []) state.annotations.set(a.id, a);
    for (const c of m.corrections || []) state.corrections.push(c);
    state.deltas++;
    if (!view.fitted && state.entities.size > 0) fit();
  } else if (m.type === 'error') {
    note('error', m.message);
  } else if (m.type === 'ack') {
    note('ack', m.message);
  }
  dirty = true;
  // The side panel follows every 500 ms; at once only for what the operator waits for.
  if (m.type !== 'delta' || m.annotations || m.corrections) renderPanel();
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
  if (!drag) return;
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

// ---- the three-point rotation -----------------------------------------------------------------

const PICK_PROMPTS = ['click the rotation origin on the trail of ', 'click a point in the wrong direction',
                      'click the same point in the correct direction'];

function startRotation(entity) {
  if (!state.entities.has(entity)) { note('error', `rotate: unknown entity '${entity}'`); return; }
  pick.active = true;
  pick.mode = 'rotate';
  pick.entity = entity;
  pick.points = [];
  showPrompt();
}

// The next click on the map places a mark of the chosen kind.
function startMark() {
  pick.active = true;
  pick.mode = 'mark';
  pick.points = [];
  showPrompt();
}

function retract(id) {
  send({ type: 'retract', id });
}

function cancelRotation() {
  pick.active = false;
  pick.points = [];
  showPrompt();
}

// Adds one clicked point (map frame); the third sends the request.
function pickPoint(x, y) {
  if (!pick.active) return;
  pick.points.push([x, y]);
  if (pick.mode === 'mark') {
    const text = document.getElementById('mark-text').value;
    send({ type: 'annotate', kind: document.getElementById('mark-kind').value, position: [x, y], text });
    cancelRotation();
  } else if (pick.points.length === 3) {
    const [origin, wrong, correct] = pick.points;
    send({ type: 'rotate', entity: pick.entity, origin, wrong, correct });
    cancelRotation();
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
window.addEventListener('keydown', (ev) => { if (ev.key === 'Escape') cancelRotation(); });

function showPrompt() {
  const p = document.getElementById('prompt');
  document.getElementById('rotate').classList.toggle('active', pick.active && pick.mode === 'rotate');
  document.getElementById('mark').classList.toggle('active', pick.active && pick.mode === 'mark');
  canvas.classList.toggle('picking', pick.active);
  if (!pick.active) { p.textContent = ''; return; }
  if (pick.mode === 'mark') {
    p.textContent = `Mark ${document.getElementById('mark-kind').value}: click the map (Esc cancels)`;
    return;
  }
  const n = pick.points.length;
  p.textContent = `Rotate ${pick.entity}: ${PICK_PROMPTS[n]}${n === 0 ? pick.entity : ''} (Esc cancels)`;
}

document.getElementById('rotate').addEventListener('click', () => {
  if (pick.active) { cancelRotation(); return; }
  startRotation(document.getElementById('rotate-entity').value);
});
document.getElementById('mark').addEventListener('click', () => {
  if (pick.active) { cancelRotation(); return; }
  startMark();
});
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

function drawMap() {
  ctx.lineCap = 'round';
  for (const observed of [0, 1]) {
    ctx.beginPath();
    for (const s of state.segments.values()) {
      if (s[4] !== observed) continue;
      const [ax, ay] = toScreen(s[0], s[1]);
      const [bx, by] = toScreen(s[2], s[3]);
      ctx.moveTo(ax, ay);
      ctx.lineTo(bx, by);
    }
    ctx.strokeStyle = observed ? '#111111' : '#9e9e9e';
    ctx.lineWidth = observed ? 2.2 : 1.6;
    ctx.setLineDash(observed ? [] : [6, 4]);
    ctx.stroke();
  }
  ctx.setLineDash([]);
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
  const names = ['origin', 'wrong', 'correct'];
  pick.points.forEach((p, i) => {
    const [sx, sy] = toScreen(p[0], p[1]);
    ctx.beginPath();
    ctx.arc(sx, sy, 5, 0, 2 * Math.PI);
    ctx.fillStyle = '#ffb300';
    ctx.fill();
    ctx.fillStyle = '#1d2330';
    ctx.fillText(names[i], sx + 7, sy - 6);
    if (i > 0) {
      const [ox, oy] = toScreen(pick.points[0][0], pick.points[0][1]);
      ctx.beginPath();
      ctx.moveTo(ox, oy);
      ctx.lineTo(sx, sy);
      ctx.strokeStyle = '#ffb300';
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
  const rows = [['line', '#111111', [], 'observed wall'], ['line', '#9e9e9e', [6, 4], 'plan only'],
                ['ellipse', '#1d2330', [3, 3], '95 % position'], ['dot', '#d81b60', [], 'victim'],
                ['dot', '#f9a825', [], 'other mark']];
  const x = canvas.width - 150, y0 = 12;
  ctx.fillStyle = 'rgba(255, 255, 255, 0.85)';
  ctx.fillRect(x - 8, y0 - 4, 150, rows.length * 17 + 6);
  ctx.font = '12px system-ui, sans-serif';
  rows.forEach(([shape, colour, dash, text], i) => {
    const y = y0 + 8 + i * 17;
    ctx.strokeStyle = colour;
    ctx.fillStyle = colour;
    ctx.setLineDash(dash);
    ctx.lineWidth = 2;
    ctx.beginPath();
    if (shape === 'line') { ctx.moveTo(x, y); ctx.lineTo(x + 24, y); ctx.stroke(); }
    if (shape === 'ellipse') { ctx.ellipse(x + 12, y, 11, 5, 0, 0, 2 * Math.PI); ctx.stroke(); }
    if (shape === 'dot') { ctx.arc(x + 12, y, 5, 0, 2 * Math.PI); ctx.fill(); }
    ctx.setLineDash([]);
    ctx.fillStyle = '#1d2330';
    ctx.fillText(text, x + 32, y + 4);
  });
}

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
    return `${c.kind}${angle} of ${c.entity} from ${c.stamp_s.toFixed(1)} s by ${c.operator}`;
  });
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

window.penaConsole = { state, view, pick, send, toScreen, toWorld, startRotation, startMark, retract, pickPoint, fit,
                       ellipseOf, redraw: () => { draw(); dirty = false; } };
resize();
connect();
requestAnimationFrame(frame);
