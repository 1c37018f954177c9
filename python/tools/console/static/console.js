// CHASM-AUV console page: draws the model the server streams (GET /api/events)
// on a canvas in local north/east metres, and sends commands (POST /api/command).
// No library, no network beyond the console's own server.
'use strict';

const COLORS = ['#4fc3f7', '#ffb74d', '#81c784', '#f06292', '#ba68c8', '#fff176', '#4db6ac', '#e57373'];
const CLASS_COLORS = { mine_like: '#ff5252', clutter: '#9e9e9e', unknown: '#ffd54f' };
const IDENTIFY_M = 5;   // a true target is drawn identified once a contact lies this close (the report's radius)
const S = { info: null, now: null, world: null, series: {}, epoch: null, dirty: true,
            view: { cn: 0, ce: 0, scale: 1, fitted: false }, pending: {}, colors: {}, built: {} };
const $ = id => document.getElementById(id);
const canvas = $('map'), ctx = canvas.getContext('2d');

function colorOf(vid) {
  if (!(vid in S.colors)) {
    // stable between runs: from the name, not the order of arrival
    let h = 0; for (const ch of vid) h = (h * 31 + ch.charCodeAt(0)) >>> 0;
    const used = new Set(Object.values(S.colors));
    let i = h % COLORS.length; for (let k = 0; k < COLORS.length && used.has(COLORS[i]); k++) i = (i + 1) % COLORS.length;
    S.colors[vid] = COLORS[i];
  }
  return S.colors[vid];
}
const esc = s => String(s).replace(/[&<>"]/g, c => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' }[c]));
const fmt = (x, d = 1) => (x === null || x === undefined || Number.isNaN(x)) ? '–' : Number(x).toFixed(d);

// ------------------------------------------------------------------ stream
// the mode (live or log) decides how the panels are built: know it before the first update
fetch('/api/info').then(r => r.json()).then(info => { S.info = info; setupMode(); openStream(); });
function openStream() {
const stream = new EventSource('/api/events');
stream.onmessage = ev => {
  const d = JSON.parse(ev.data);
  if (d.world) S.world = d.world;
  if (d.now.epoch !== S.epoch && typeof CV !== 'undefined') { CV.structs = {}; }
  if (d.structures && typeof cvStructures === 'function') cvStructures(d.structures);
  if (d.now.epoch !== S.epoch) { S.series = {}; S.epoch = d.now.epoch; }
  for (const [name, part] of Object.entries(d.series)) {
    if (part.reset || !S.series[name]) S.series[name] = [];
    const arr = S.series[name];
    for (const p of part.add) arr.push(p);
    if (arr.length > 30000) arr.splice(0, arr.length - 30000);
  }
  S.now = d.now; S.dirty = true;
  updatePanel();
};
// A lost stream is the console process gone (a log's end keeps it open: see modeText)
stream.onerror = () => { S.streamLost = true; $('mode').textContent = 'console unreachable: retrying…'; };
stream.onopen = () => { S.streamLost = false; $('mode').textContent = modeText(); };
}

// What the page shows: live, or a log and whether its end is reached (nothing is
// broken there: the run ended, the view holds its last state)
function modeText() {
  if (S.info.mode !== 'log') return 'live';
  const atEnd = S.now && S.now.t >= S.info.end - 1e-6;
  return `log ${S.info.log}` + (atEnd ? ' · end of the log' : '');
}

function setupMode() {
  $('mode').textContent = modeText();
  if (S.info.mode !== 'log') return;
  const sl = $('slider'), player = $('player');
  player.hidden = false;
  sl.min = S.info.start; sl.max = S.info.end; sl.value = S.info.end;
  let timer = null, inflight = false, want = null;
  const seek = t => {
    want = t;
    if (inflight) return;
    inflight = true;
    const t0 = want; want = null;
    fetch('/api/seek', { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify({ t: t0 }) })
      .finally(() => { inflight = false; if (want !== null) seek(want); });
  };
  sl.addEventListener('input', () => seek(Number(sl.value)));
  $('play').addEventListener('click', () => {
    if (timer) { clearInterval(timer); timer = null; $('play').textContent = '▶'; return; }
    if (Number(sl.value) >= S.info.end) sl.value = S.info.start;
    $('play').textContent = '❚❚';
    timer = setInterval(() => {
      const t = Math.min(S.info.end, Number(sl.value) + 0.2 * Number($('speed').value));
      sl.value = t; seek(t);
      if (t >= S.info.end) $('play').click();
    }, 200);
  });
}

// ------------------------------------------------------------------ panel
function vehicleIds() { return S.now ? Object.keys(S.now.vehicles).sort() : []; }

function buildVehicle(vid) {
  const div = document.createElement('div');
  div.className = 'vehicle'; div.dataset.id = vid; div.style.setProperty('--c', colorOf(vid));
  const live = S.info && S.info.mode === 'live';
  div.innerHTML = `<h3>${esc(vid)}</h3><div class="info"></div>` + (live ? `
    <div class="cmds"><select class="mgr-select"><option value="">every manager</option></select>
    <button data-cmd="pause">Pause</button><button data-cmd="resume">Resume</button>
    <button data-cmd="abort">Abort</button><button data-cmd="load">Load plan…</button></div>
    <div class="ack"></div>` : '');
  div.querySelectorAll('button[data-cmd]').forEach(b => b.addEventListener('click', () => askCommand(vid, b.dataset.cmd)));
  $('vehicles').appendChild(div);
  return div;
}

function updatePanel() {
  const now = S.now;
  $('clock').textContent = `t = ${fmt(now.t, 1)} s` + (now.clock.mode ? ` · ${now.clock.mode}` : '') +
    (now.clock.mode === 'scaled' ? ` ×${fmt(now.clock.warp, 0)}` : '');
  if (S.info && S.info.mode === 'log') {
    $('slider-time').textContent = `${fmt(now.t, 1)} / ${fmt(S.info.end, 1)} s`;
    if (!S.streamLost) $('mode').textContent = modeText();
  }
  const ids = vehicleIds();
  for (const el of document.querySelectorAll('.vehicle')) if (!ids.includes(el.dataset.id)) { el.remove(); delete S.built[el.dataset.id]; }
  for (const vid of ids) {
    const el = S.built[vid] || (S.built[vid] = buildVehicle(vid));
    const v = now.vehicles[vid];
    el.querySelector('.info').innerHTML = vehicleHtml(v);
    const sel = el.querySelector('.mgr-select');
    if (sel) {
      const names = Object.keys(v.managers).sort();
      const have = [...sel.options].map(o => o.value).slice(1);
      if (names.join() !== have.join()) {
        const keep = sel.value;
        sel.innerHTML = '<option value="">every manager</option>' + names.map(n => `<option>${esc(n)}</option>`).join('');
        sel.value = names.includes(keep) ? keep : '';
      }
    }
    showAck(vid);
  }
  if (typeof cvUpdate === 'function') cvUpdate(now);
  $('agents').innerHTML = agentsHtml(now.agents || {});
  const w = S.world;
  $('world-info').textContent = w ? `${w.name || ''} ${w.bathymetry_ref ? '· seabed ' + w.bathymetry_ref : ''}` +
    ` · ${now.counts.messages} messages` : '';
}

function vehicleHtml(v) {
  const out = [];
  const pos = v.truth || v.nav;
  if (pos) out.push(`<div>N ${fmt(pos.n)} E ${fmt(pos.e)} · depth ${fmt(pos.depth)} m · alt ${fmt(pos.altitude)} m · hdg ${(Math.round(deg(pos.heading)) % 360 + 360) % 360}°</div>`);
  if (v.nav) {
    const flags = v.nav.flags.map(f => f === f.toUpperCase() ? `<span class="bad">${f}</span>` : f).join(' ');
    let q = `nav: ${flags || 'no aids'} · σ ${fmt(v.nav.sigma)} m`;
    if (v.nav_status) q += ` · ${v.nav_status.trusted ? 'trusted' : '<span class="bad">NOT TRUSTED</span>'}`;
    if (v.truth) q += ` · error ${fmt(Math.hypot(v.truth.n - v.nav.n, v.truth.e - v.nav.e))} m`;
    out.push(`<div class="navq">${q}</div>`);
  }
  for (const name of Object.keys(v.managers).sort()) {
    const m = v.managers[name];
    out.push(`<div class="mgr" data-manager="${esc(name)}"><b>${esc(name)}</b> <span class="run run-${esc(m.run)}">${esc(m.run)}</span> ` +
      `<span class="path">${esc(m.path)}</span> (${fmt(m.time_in_state)} s)</div>`);
    if (m.last.to) {
      const tests = Object.entries(m.last.tests).map(([k, x]) => `${esc(k)}=${x}`).join(' ');
      out.push(`<div class="last">at ${fmt(m.last.t)} s: ${esc(m.last.from || '–')} → ${esc(m.last.to)}` +
        (m.last.condition ? ` when <i>${esc(m.last.condition)}</i>` : '') + (tests ? ` [${tests}]` : '') + '</div>');
    }
  }
  if (v.modem) {
    const m = v.modem, refused = m.refused_size + m.refused_rate + m.refused_invalid;
    out.push(`<div class="modem">modem: sent ${m.sent} · received ${m.received} · lost ${m.lost} · out of range ${m.out_of_range}` +
      (m.collided ? ` · <span class="bad">collided ${m.collided}</span>` : '') +
      (m.deaf ? ` · missed while sending ${m.deaf}` : '') +
      (refused ? ` · <span class="bad">refused ${refused}</span> (${esc(m.last_refusal)})` : '') + '</div>');
  }
  if (v.radio) out.push(radioHtml(v.radio));
  if (v.frontseat) {   // a commercial vehicle: who flies it now (docs/frontseat.md)
    const f = v.frontseat;
    const who = f.control === 'payload' ? 'payload (our plan) has control'
      : f.control === 'operator' ? '<span class="bad">an operator has control</span>'
      : `frontseat has control${f.requesting ? ' (asked)' : ''}`;
    const state = ['silent', 'error', 'not connected'].includes(f.state) ? `<span class="bad">${esc(f.state)}</span>` : esc(f.state);
    out.push(`<div class="frontseat fs-${esc(f.control)}">frontseat ${esc(f.protocol)}: <b>${who}</b> · ${state}` +
      (f.mode ? ` · mode ${esc(f.mode)}` : '') + (f.error ? ` · <span class="bad">error ${esc(f.error)}</span>` : '') +
      ` · heard ${f.age_s < 0 ? 'never' : fmt(f.age_s) + ' s ago'} · granted ${f.granted} · lost ${f.lost}` +
      (f.refused ? ` · refused ${f.refused} (${esc(f.last_refusal)})` : '') + '</div>');
  }
  return out.join('');
}

// The surface radio (docs/radio.md): the link, the last status home and its
// age, each command sent through the shore gateway with its progress.
function radioHtml(r) {
  const out = [];
  if (r.link) {
    const l = r.link;
    out.push(`<div class="radio">radio: ${l.up ? '<b>up</b>' : '<span class="bad">down</span>'}` +
      ` (${l.clear ? 'antenna clear' : 'under water'}, ${fmt(l.range_m)} m) · delivered ${l.delivered}` +
      ` · lost ${l.lost} · dropped ${l.dropped}</div>`);
  }
  if (r.report) {
    const p = r.report;
    out.push(`<div class="radio">last report ${fmt(S.now.t - p.t)} s ago: N ${fmt(p.n)} E ${fmt(p.e)} depth ${fmt(p.depth)} m` +
      ` · ${esc(p.mission)} · contacts ${p.contacts}` + (p.refused ? ` · <span class="bad">refused ${p.refused}</span>` : '') + '</div>');
  }
  for (const c of r.commands) {
    const pct = c.total ? Math.round(100 * c.held / c.total) : 0;
    const bad = ['expired', 'refused'].includes(c.state);
    out.push(`<div class="radio">${esc(c.what)} (${esc(c.route)}): ` +
      `${bad ? `<span class="bad">${esc(c.state)}</span>` : esc(c.state)}` +
      (c.route === 'radio' && (c.state === 'in flight' || c.state === 'queued') ? ` ${pct}% of ${c.total} bytes` : '') +
      (c.message ? ` · ${esc(c.message)}` : '') + '</div>');
  }
  return out.join('');
}

// The host agents' process tables (AGENT.<HOST>.PROCS): one block per host.
function agentsHtml(agents) {
  const hosts = Object.keys(agents).sort();
  if (!hosts.length) return '';
  return '<h3>Host agents</h3>' + hosts.map(h => {
    const a = agents[h];
    const rows = a.procs.map(p => `<tr class="proc proc-${esc(p.state)}"><td>${esc(p.name)}</td><td>${p.pid}</td>` +
      `<td>${esc(p.state)}${p.state === 'running' ? '' : ' (' + p.exit_code + ')'}</td><td>${fmt(100 * p.cpu, 0)} %</td>` +
      `<td>${fmt(p.rss_mb, 0)} MB</td><td>${p.restarts}</td><td>${fmt(p.uptime_s, 0)} s</td></tr>`).join('');
    return `<div class="agent" data-host="${esc(h)}"><b>${esc(h)}</b> ${esc(a.status)}` +
      (a.run ? ` · run ${esc(a.run)} · launcher heard ${fmt(a.launcher_silent_s, 0)} s ago` : '') +
      `<table><tr><th>process</th><th>pid</th><th>state</th><th>cpu</th><th>mem</th><th>restarts</th><th>up</th></tr>${rows}</table></div>`;
  }).join('');
}

// ------------------------------------------------------------------ commands
let confirmAction = null;
function askCommand(vid, cmd) {
  const el = S.built[vid], manager = el.querySelector('.mgr-select').value;
  const who = `${vid} ${manager || '(every manager)'}`;
  if (cmd === 'load') {
    const input = $('plan-file');
    input.value = '';
    input.onchange = () => {
      const file = input.files[0]; if (!file) return;
      file.text().then(text => confirmBox(`Load plan ${file.name} onto ${who}? The running plan is replaced.`,
        () => sendCommand(vid, manager, 'load', file.name, text)));
    };
    input.click();
    return;
  }
  confirmBox(`${cmd[0].toUpperCase() + cmd.slice(1)} ${who}?`, () => sendCommand(vid, manager, cmd));
}

function confirmBox(text, action) {
  $('confirm-text').textContent = text; confirmAction = action; $('confirm').hidden = false;
}
$('confirm-yes').addEventListener('click', () => { $('confirm').hidden = true; const a = confirmAction; confirmAction = null; if (a) a(); });
$('confirm-no').addEventListener('click', () => { $('confirm').hidden = true; confirmAction = null; });

function sendCommand(vid, manager, cmd, plan_name = '', plan_text = '') {
  S.pending[vid] = { cmd, seq: null, error: null };
  showAck(vid);
  fetch('/api/command', { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify({ vehicle: vid, manager, command: cmd, plan_name, plan_text }) })
    .then(r => r.json().then(j => { if (!r.ok) throw new Error(j.error || r.statusText); return j; }))
    .then(j => { S.pending[vid].seq = j.seq; showAck(vid); })
    .catch(e => { S.pending[vid].error = String(e.message || e); showAck(vid); });
}

function showAck(vid) {
  const p = S.pending[vid], el = S.built[vid] && S.built[vid].querySelector('.ack');
  if (!p || !el) return;
  if (p.error) { el.innerHTML = `${esc(p.cmd)}: <span class="failed">not sent: ${esc(p.error)}</span>`; return; }
  if (p.seq === null) { el.textContent = `${p.cmd}: sending…`; return; }
  const acks = (S.now.vehicles[vid] ? S.now.vehicles[vid].acks : []).filter(a => a.seq === p.seq);
  el.innerHTML = `${esc(p.cmd)} (seq ${p.seq}): ` + (acks.length ? acks.map(a =>
    `<span class="${esc(a.result)}">${esc(a.manager)} ${esc(a.result)}</span>: ${esc(a.message)}`).join('; ') : 'waiting for the ack…');
}

// ------------------------------------------------------------------ map
const deg = r => r * 180 / Math.PI;
function toScreen(n, e) {
  const v = S.view;
  return [canvas.width / 2 + (e - v.ce) * v.scale, canvas.height / 2 - (n - v.cn) * v.scale];
}
function toWorld(x, y) {
  const v = S.view;
  return [v.cn - (y - canvas.height / 2) / v.scale, v.ce + (x - canvas.width / 2) / v.scale];
}

function fit() {
  const pts = [];
  const w = S.world || {};
  for (const p of (w.operating_area || []).concat(w.survey_area || [])) pts.push(p);
  if (S.now) for (const v of Object.values(S.now.vehicles)) { const p = v.truth || v.nav; if (p) pts.push([p.n, p.e]); }
  if (!pts.length) return false;
  let n0 = Infinity, n1 = -Infinity, e0 = Infinity, e1 = -Infinity;
  for (const [n, e] of pts) { n0 = Math.min(n0, n); n1 = Math.max(n1, n); e0 = Math.min(e0, e); e1 = Math.max(e1, e); }
  const span = Math.max(n1 - n0, e1 - e0, 40) * 1.15;
  S.view.cn = (n0 + n1) / 2; S.view.ce = (e0 + e1) / 2;
  S.view.scale = Math.min(canvas.width, canvas.height) / span;
  S.view.fitted = true; S.dirty = true;
  return true;
}
$('fit').addEventListener('click', fit);
for (const id of ['show-nav', 'show-true', 'show-seabed', 'show-water']) $(id).addEventListener('change', () => { S.dirty = true; });

let drag = null;
canvas.addEventListener('mousedown', e => { drag = [e.offsetX, e.offsetY]; canvas.style.cursor = 'grabbing'; });
window.addEventListener('mouseup', () => { drag = null; canvas.style.cursor = 'grab'; });
canvas.addEventListener('mousemove', e => {
  const r = devicePixelRatio, [n, ee] = toWorld(e.offsetX * r, e.offsetY * r);
  $('cursor').textContent = `N ${fmt(n)} E ${fmt(ee)}`;
  if (!drag) return;
  S.view.ce -= (e.offsetX - drag[0]) * r / S.view.scale; S.view.cn += (e.offsetY - drag[1]) * r / S.view.scale;
  drag = [e.offsetX, e.offsetY]; S.dirty = true;
});
canvas.addEventListener('wheel', e => {
  e.preventDefault();
  const r = devicePixelRatio, [n, ee] = toWorld(e.offsetX * r, e.offsetY * r);
  const k = Math.exp(-e.deltaY * 0.0015);
  S.view.scale *= k;
  S.view.cn = n + (S.view.cn - n) / k; S.view.ce = ee + (S.view.ce - ee) / k; S.dirty = true;
}, { passive: false });

function resize() {
  const r = devicePixelRatio, box = canvas.getBoundingClientRect();
  canvas.width = Math.max(1, Math.round(box.width * r)); canvas.height = Math.max(1, Math.round(box.height * r));
  S.dirty = true;
}
window.addEventListener('resize', resize);
resize();

function poly(pts, close) {
  ctx.beginPath();
  pts.forEach(([n, e], i) => { const [x, y] = toScreen(n, e); i ? ctx.lineTo(x, y) : ctx.moveTo(x, y); });
  if (close) ctx.closePath();
}

function drawSeabed(sb) {
  if (!sb || sb.error || !$('show-seabed').checked) return;
  let lo = Infinity, hi = -Infinity;
  for (const row of sb.depth) for (const d of row) { lo = Math.min(lo, d); hi = Math.max(hi, d); }
  const span = Math.max(hi - lo, 1);   // a flat seabed gets one calm colour, not noise
  for (let i = 0; i < sb.depth.length; i++) {
    for (let j = 0; j < sb.depth[i].length; j++) {
      const f = (sb.depth[i][j] - lo) / span;
      ctx.fillStyle = `rgb(${Math.round(30 - 20 * f)},${Math.round(70 - 45 * f)},${Math.round(110 - 50 * f)})`;
      const [x0, y0] = toScreen(sb.north0 + (i + 1) * sb.dn, sb.east0 + j * sb.de);
      const [x1, y1] = toScreen(sb.north0 + i * sb.dn, sb.east0 + (j + 1) * sb.de);
      ctx.fillRect(x0, y0, x1 - x0 + 1, y1 - y0 + 1);
    }
  }
  $('legend').innerHTML = `seabed ${fmt(lo)}–${fmt(hi)} m · <span style="color:#ff5252">●</span> mine-like ` +
    `<span style="color:#9e9e9e">●</span> clutter <span style="color:#ffd54f">●</span> unknown · ◇ true target (◆ identified) · △ LBL`;
}

// The water's temperature (a world with an ocean, docs/sampling.md), over the seabed:
// cold blue to warm red across the layer's own range, and its legend.
function drawWater(wt) {
  if (!wt || wt.error || !$('show-water').checked) return false;
  let lo = Infinity, hi = -Infinity;
  for (const row of wt.temp) for (const v of row) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
  const span = Math.max(hi - lo, 0.01);
  for (let i = 0; i < wt.temp.length; i++) {
    for (let j = 0; j < wt.temp[i].length; j++) {
      const f = (wt.temp[i][j] - lo) / span;
      ctx.fillStyle = `rgb(${Math.round(40 + 160 * f)},${Math.round(60 + 30 * (1 - Math.abs(2 * f - 1)))},${Math.round(200 - 160 * f)})`;
      const [x0, y0] = toScreen(wt.north0 + (i + 1) * wt.dn, wt.east0 + j * wt.de);
      const [x1, y1] = toScreen(wt.north0 + i * wt.dn, wt.east0 + (j + 1) * wt.de);
      ctx.fillRect(x0, y0, x1 - x0 + 1, y1 - y0 + 1);
    }
  }
  $('legend').innerHTML = `water at ${fmt(wt.depth_m)} m: <span style="color:#2850c8">${fmt(lo)}</span>–` +
    `<span style="color:#c85a28">${fmt(hi)}</span> °C (at the start)`;
  return true;
}

function drawGrid() {
  const r = devicePixelRatio, targetPx = 90 * r;
  const raw = targetPx / S.view.scale, p = Math.pow(10, Math.floor(Math.log10(raw)));
  const step = [1, 2, 5, 10].map(k => k * p).find(s => s >= raw) || raw;
  const [nTop, eLeft] = toWorld(0, 0), [nBot, eRight] = toWorld(canvas.width, canvas.height);
  ctx.strokeStyle = '#ffffff22'; ctx.fillStyle = '#ffffff77'; ctx.lineWidth = 1; ctx.font = `${10 * r}px sans-serif`;
  for (let e = Math.ceil(eLeft / step) * step; e <= eRight; e += step) {
    const [x] = toScreen(0, e); ctx.beginPath(); ctx.moveTo(x, 0); ctx.lineTo(x, canvas.height); ctx.stroke();
    ctx.fillText(`E ${Math.round(e)}`, x + 2, canvas.height - 4 * r);
  }
  for (let n = Math.ceil(nBot / step) * step; n <= nTop; n += step) {
    const [, y] = toScreen(n, 0); ctx.beginPath(); ctx.moveTo(0, y); ctx.lineTo(canvas.width, y); ctx.stroke();
    ctx.fillText(`N ${Math.round(n)}`, 2, y - 2);
  }
}

function drawWorld(w) {
  const r = devicePixelRatio;
  if (w.operating_area && w.operating_area.length) {
    ctx.setLineDash([8 * r, 6 * r]); ctx.strokeStyle = '#ff9800'; ctx.lineWidth = 1.5 * r;
    poly(w.operating_area, true); ctx.stroke(); ctx.setLineDash([]);
  }
  if (w.survey_area && w.survey_area.length) {
    ctx.strokeStyle = '#ffeb3b'; ctx.lineWidth = 2 * r; poly(w.survey_area, true); ctx.stroke();
  }
  for (const [vid, lines] of Object.entries(w.lines || {})) {
    ctx.strokeStyle = colorOf(vid) + '66'; ctx.lineWidth = 1 * r;
    for (const seg of lines) { poly(seg, false); ctx.stroke(); }
  }
  ctx.fillStyle = '#e0e0e0';
  for (const t of w.transponders || []) {
    if (t.n === null || t.n === undefined) continue;
    const [x, y] = toScreen(t.n, t.e), s = 6 * r;
    ctx.beginPath(); ctx.moveTo(x, y - s); ctx.lineTo(x + s, y + s); ctx.lineTo(x - s, y + s); ctx.closePath(); ctx.fill();
  }
}

function drawVehicle(vid, v) {
  const r = devicePixelRatio, c = colorOf(vid), pos = v.truth || v.nav;
  if (!pos) return;
  if (v.truth && v.nav) {   // where the vehicle believes it is
    const [x, y] = toScreen(v.nav.n, v.nav.e);
    ctx.strokeStyle = c; ctx.lineWidth = 1.5 * r; ctx.beginPath(); ctx.arc(x, y, 5 * r, 0, 2 * Math.PI); ctx.stroke();
  }
  const [x, y] = toScreen(pos.n, pos.e), h = pos.heading, s = 11 * r;
  const f = [Math.sin(h), -Math.cos(h)], side = [Math.cos(h), Math.sin(h)];
  ctx.fillStyle = c; ctx.strokeStyle = '#000'; ctx.lineWidth = 1 * r;
  ctx.beginPath();
  ctx.moveTo(x + f[0] * s, y + f[1] * s);
  ctx.lineTo(x - f[0] * s * 0.6 + side[0] * s * 0.5, y - f[1] * s * 0.6 + side[1] * s * 0.5);
  ctx.lineTo(x - f[0] * s * 0.6 - side[0] * s * 0.5, y - f[1] * s * 0.6 - side[1] * s * 0.5);
  ctx.closePath(); ctx.fill(); ctx.stroke();
  ctx.fillStyle = '#fff'; ctx.font = `${11 * r}px sans-serif`; ctx.fillText(vid, x + 10 * r, y - 8 * r);
}

function draw() {
  requestAnimationFrame(draw);
  if (!S.dirty || !S.now) return;
  if (!S.view.fitted && !fit()) return;
  S.dirty = false;
  const r = devicePixelRatio, now = S.now, w = S.world || {};
  ctx.fillStyle = '#0b1622'; ctx.fillRect(0, 0, canvas.width, canvas.height);
  drawSeabed(w.seabed);
  drawWater(w.water);
  drawGrid();
  drawWorld(w);
  const contactsNow = S.series.contacts || [];
  for (const t of now.targets) {   // the true field (simulation only); filled once a contact is within 5 m
    const [x, y] = toScreen(t.n, t.e), s = 6 * r;
    const identified = contactsNow.some(c => Math.hypot(c.n - t.n, c.e - t.e) <= IDENTIFY_M);
    ctx.strokeStyle = ctx.fillStyle = CLASS_COLORS[t.kind] || '#fff'; ctx.lineWidth = 1.5 * r;
    ctx.beginPath(); ctx.moveTo(x, y - s); ctx.lineTo(x + s, y); ctx.lineTo(x, y + s); ctx.lineTo(x - s, y); ctx.closePath();
    if (identified) ctx.fill(); else ctx.stroke();
  }
  for (const c of S.series.contacts || []) {
    const [x, y] = toScreen(c.n, c.e);
    ctx.fillStyle = CLASS_COLORS[c.class] || CLASS_COLORS.unknown;
    ctx.beginPath(); ctx.arc(x, y, 3 * r, 0, 2 * Math.PI); ctx.fill();
  }
  for (const vid of vehicleIds()) {
    for (const [kind, dash, show] of [['true', [], 'show-true'], ['nav', [4 * r, 4 * r], 'show-nav']]) {
      const trail = S.series[`${vid}.${kind}`];
      if (!trail || trail.length < 2 || !$(show).checked) continue;
      ctx.strokeStyle = colorOf(vid) + (kind === 'true' ? 'dd' : '99'); ctx.lineWidth = 1.5 * r; ctx.setLineDash(dash);
      poly(trail, false); ctx.stroke(); ctx.setLineDash([]);
    }
  }
  for (const ln of now.links) {     // a modem frame heard: sender -> receiver
    const a = now.vehicles[ln.src], b = now.vehicles[ln.dst];
    const pa = a && (a.truth || a.nav), pb = b && (b.truth || b.nav);
    if (!pa || !pb) continue;
    const age = Math.max(0, now.t - ln.t);
    ctx.strokeStyle = `rgba(0,229,255,${Math.max(0.15, 1 - age / 8)})`; ctx.lineWidth = 1.5 * r;
    const [x0, y0] = toScreen(pa.n, pa.e), [x1, y1] = toScreen(pb.n, pb.e);
    ctx.beginPath(); ctx.moveTo(x0, y0); ctx.lineTo(x1, y1); ctx.stroke();
  }
  for (const vid of vehicleIds()) drawVehicle(vid, now.vehicles[vid]);
}
requestAnimationFrame(draw);
