// CHASM state view: per manager, its plan's tree (from chasm_structure_t, sent
// once per plan), the active path the manager reported (chasm_status_t), the
// transitions of the active states with the value of every test in them, the
// variables and the transition history. Never draws a state the manager did
// not report: a status of another plan than the structure is shown as such.
'use strict';

const CV = { structs: {}, cols: {}, query: '', open: true };

// the structures the server sends, once per plan (see server.py)
function cvStructures(structs) {
  for (const [key, st] of Object.entries(structs || {})) {
    st.pathIndex = new Map(st.states.map((s, i) => [s.path, i]));
    st.children = st.states.map(() => []);
    st.states.forEach((s, i) => { if (s.parent >= 0) st.children[s.parent].push(i); });
    st.byFrom = st.states.map(() => []);
    st.aborts = [];
    st.transitions.forEach((t, k) => (t.from >= 0 ? st.byFrom[t.from] : st.aborts).push(k));
    CV.structs[key] = st;
    if (CV.cols[key]) CV.cols[key].builtFor = null;   // draw the new tree
  }
}

function cvTreeHtml(st, i) {
  const s = st.states[i], kids = st.children[i];
  const tog = kids.length ? '<span class="tog">▾</span>' : '<span class="tog leaf">·</span>';
  return `<li data-i="${i}">${tog}<span class="nm" title="${esc(s.path)} (${esc(s.loc)})">${esc(s.name)}</span>` +
    '<span class="tis"></span>' + (kids.length ? `<ul>${kids.map(c => cvTreeHtml(st, c)).join('')}</ul>` : '') + '</li>';
}

function cvColumn(key) {
  let col = CV.cols[key];
  if (col) return col;
  const [vid, mgr] = key.split('/');
  const el = document.createElement('div');
  el.className = 'cv-col'; el.dataset.key = key; el.style.setProperty('--c', colorOf(vid));
  el.innerHTML = `<h4>${esc(vid)} · ${esc(mgr)} <span class="cv-plan"></span></h4><div class="cv-status"></div>` +
    '<div class="cv-problem"></div><ul class="cv-tree"></ul><div class="cv-why"></div>' +
    '<details class="cv-vars"><summary>variables</summary><table></table></details>' +
    '<details class="cv-hist" open><summary>transitions</summary><ol></ol></details>';
  el.querySelector('.cv-tree').addEventListener('click', e => {
    e.stopPropagation();
    if (!e.target.classList.contains('tog')) return;
    e.target.parentElement.classList.toggle('collapsed');
    e.target.textContent = e.target.parentElement.classList.contains('collapsed') ? '▸' : '▾';
  });
  $('cv-cols').appendChild(el);
  col = CV.cols[key] = { el, builtFor: null, nodes: [], active: [], seen: null };
  return col;
}

function cvBuildTree(col, st) {
  const roots = st.states.map((s, i) => i).filter(i => st.states[i].parent < 0);
  const tree = col.el.querySelector('.cv-tree');
  tree.innerHTML = roots.map(i => cvTreeHtml(st, i)).join('');
  col.nodes = [];
  for (const li of tree.querySelectorAll('li')) col.nodes[Number(li.dataset.i)] = li;
  col.active = [];
  col.builtFor = st.id;
  col.el.querySelector('.cv-plan').textContent = `${st.plan} · ${st.id}`;
  cvFilter(col, st);
}

// search: the matching states and their ancestors stay, the rest hide
function cvFilter(col, st) {
  const q = CV.query.toLowerCase();
  const keep = new Array(st.states.length).fill(!q);
  if (q) st.states.forEach((s, i) => {
    if (!s.path.toLowerCase().includes(q)) return;
    for (let p = i; p >= 0 && !keep[p]; p = st.states[p].parent) keep[p] = true;
  });
  col.nodes.forEach((li, i) => {
    li.hidden = !keep[i];
    li.querySelector('.nm').classList.toggle('hit', !!q && st.states[i].path.toLowerCase().includes(q));
  });
}

function cvShowActive() {
  for (const col of Object.values(CV.cols)) {
    const leaf = col.active[col.active.length - 1];
    if (leaf === undefined) continue;
    for (let li = col.nodes[leaf]; li && li.tagName === 'LI'; li = li.parentElement.closest('li')) {
      li.classList.remove('collapsed'); li.hidden = false;
      const t = li.querySelector(':scope > .tog'); if (t && !t.classList.contains('leaf')) t.textContent = '▾';
    }
    col.nodes[leaf].scrollIntoView({ block: 'nearest' });
  }
}

// the transitions that can fire now, with each test's value (status order: aborts, then the active path)
function cvWhyHtml(st, active, live) {
  const order = st.aborts.slice();
  for (const i of active) order.push(...st.byFrom[i]);
  const expected = order.reduce((n, k) => n + st.transitions[k].tests.length, 0);
  if (live.length !== expected) return `<div class="bad">test values: ${live.length} reported, ${expected} expected: not shown</div>`;
  let at = 0;
  const rows = order.map(k => {
    const t = st.transitions[k], from = t.from >= 0 ? st.states[t.from].name : 'abort';
    const tests = t.tests.map(name => {
      const val = live[at++];
      return `<span class="cv-test ${val ? 'true' : 'false'}" title="${val ? 'true now' : 'false now: blocks an and'}">${esc(name)}=${val}</span>`;
    });
    const waiting = t.tests.filter((_, j) => !live[at - t.tests.length + j]);
    return `<div class="cv-trans" data-from="${esc(from)}"><b>${esc(from)}</b> → ${esc(st.states[t.to].name)}` +
      ` when <i>${esc(t.cond)}</i> ${tests.join(' ')}` +
      (waiting.length && t.from >= 0 ? ` <span class="cv-waiting">waiting on ${waiting.map(esc).join(', ')}</span>` : '') + '</div>';
  });
  return rows.join('') || '<div>no transition out of the active states</div>';
}

function cvUpdate(now) {
  const box = $('chasmview');
  const keys = [];
  for (const [vid, v] of Object.entries(now.vehicles)) for (const mgr of Object.keys(v.managers)) keys.push(`${vid}/${mgr}`);
  for (const key of Object.keys(now.plans || {})) if (!keys.includes(key)) keys.push(key);
  keys.sort();
  box.hidden = !keys.length && !CV.planFiles;
  for (const key of keys) cvUpdateColumn(key, now);
  for (const [key, col] of Object.entries(CV.cols)) if (!keys.includes(key)) { col.el.remove(); delete CV.cols[key]; }
}

function cvUpdateColumn(key, now) {
  const [vid, mgr] = key.split('/');
  const col = cvColumn(key), st = CV.structs[key], info = (now.plans || {})[key] || {};
  const m = now.vehicles[vid] && now.vehicles[vid].managers[mgr], view = m && m.view;
  if (st && col.builtFor !== st.id) cvBuildTree(col, st);
  const problems = [];
  if (info.refused) problems.push(`${info.refused} structure message(s) refused: ${info.reason}`);
  if (!st) problems.push('no plan structure received yet: tree not drawn');
  const matches = st && view && view.plan_id === st.id;
  if (st && view && !matches) problems.push(`the status is of plan ${view.plan_id || '(none)'}, the structure of ${st.id}: not drawn` +
    (info.mismatched ? ` (${info.mismatched} such statuses)` : ''));
  col.el.querySelector('.cv-problem').innerHTML = problems.map(p => `<div class="bad">${esc(p)}</div>`).join('');
  if (!view) { col.el.querySelector('.cv-status').textContent = 'no status yet'; return; }
  const age = Math.max(0, now.t - view.t);
  col.el.querySelector('.cv-status').innerHTML = `<span class="run run-${esc(m.run)}">${esc(m.run)}</span> ` +
    `<span class="cv-path">${esc(view.active.join('/'))}</span> · report ${fmt(age)} s old`;
  const sig = `${view.t}|${view.plan_id}|${col.builtFor}`;
  if (col.seen === sig) return;
  col.seen = sig;
  // the active path: only what the status names, found by path in this plan
  const active = [];
  if (matches) {
    let path = '';
    for (const name of view.active) { path = path ? `${path}/${name}` : name; const i = st.pathIndex.get(path); if (i === undefined) break; active.push(i); }
  }
  for (const i of col.active) if (col.nodes[i]) { col.nodes[i].classList.remove('active'); col.nodes[i].querySelector('.tis').textContent = ''; }
  active.forEach((i, d) => { col.nodes[i].classList.add('active'); col.nodes[i].querySelector('.tis').textContent = ` ${fmt(view.times[d])} s`; });
  col.active = active;
  // the rest changes less often than the times: rewrite each part only when what it shows changed
  // (a rewrite costs the page a layout of the column)
  const whySig = matches ? `${col.builtFor}|${active.join()}|${view.live.join()}|${view.live_cut}` : '';
  if (col.whySig !== whySig) {
    col.whySig = whySig;
    col.el.querySelector('.cv-why').innerHTML = matches ? cvWhyHtml(st, active, view.live) +
      (view.live_cut ? '<div class="bad">more tests than a status carries: the rest not shown</div>' : '') : '';
  }
  const vars = col.el.querySelector('.cv-vars');
  if (matches && vars.open) {
    vars.querySelector('table').innerHTML = st.vars.map((v, i) => v.kind === 'local' && !v.name.includes('.') ? '' :
      `<tr><td>${esc(v.kind)}</td><td>${esc(v.name)}</td><td>${i < view.values.length && view.values[i] !== null ? view.values[i] : '–'} ${esc(v.unit)}</td></tr>`).join('');
  }
  const last = view.history[view.history.length - 1];
  const histSig = `${view.history.length}|${last ? last.t + last.to : ''}`;
  if (col.histSig !== histSig) {
    col.histSig = histSig;
    col.el.querySelector('.cv-hist ol').innerHTML = view.history.slice().reverse().map(h =>
      `<li>${fmt(h.t)} s: ${esc(h.from || '–')} → ${esc(h.to)}${h.cond ? ` when <i>${esc(h.cond)}</i>` : ''}</li>`).join('');
  }
}

$('cv-search').addEventListener('input', e => {
  CV.query = e.target.value.trim();
  for (const [key, col] of Object.entries(CV.cols)) if (CV.structs[key] && col.builtFor) cvFilter(col, CV.structs[key]);
});
$('cv-active').addEventListener('click', cvShowActive);
$('cv-hide').addEventListener('click', () => { $('cv-cols').hidden = !$('cv-cols').hidden; });

// ------------------------------------------------------------------ plan files (auv-console --plan)
// A plan file for its author, not run: the tree as parsed, each load error and
// check finding beside the state it concerns, and `chasm check`'s summary.
function cvPlanFileHtml(p) {
  const kids = p.states.map(() => []), roots = [];
  p.states.forEach((s, i) => (s.parent >= 0 && s.parent < p.states.length ? kids[s.parent] : roots).push(i));
  const notes = p.states.map(() => []), loose = [];
  for (const [cls, list] of [['cv-error', p.errors], ['cv-finding', p.findings]])
    for (const e of list) (e.state >= 0 && e.state < p.states.length ? notes[e.state] : loose).push(
      `<div class="${cls}"><span class="cv-loc" title="${esc(e.loc)}">${esc(e.loc.split('/').pop())}</span> ${esc(e.text)}</div>`);
  const li = i => `<li data-i="${i}"><span class="tog${kids[i].length ? '' : ' leaf'}">${kids[i].length ? '▾' : '·'}</span>` +
    `<span class="nm" title="${esc(p.states[i].loc)}">${esc(p.states[i].path.split('/').pop())}</span>${notes[i].join('')}` +
    (kids[i].length ? `<ul>${kids[i].map(li).join('')}</ul>` : '') + '</li>';
  const base = p.file.split('/').pop();
  return `<h4 title="${esc(p.file)}">plan ${esc(base)} <span class="cv-plan">not running</span></h4>` +
    `<pre class="cv-summary">${esc((p.summary || '').split(p.file).join(base))}</pre>${loose.join('')}<ul class="cv-tree">${roots.map(li).join('')}</ul>`;
}

function cvLoadPlanFiles() {
  fetch('/api/plans').then(r => r.json()).then(plans => {
    for (const el of document.querySelectorAll('.cv-planfile')) el.remove();
    for (const p of plans) {
      const el = document.createElement('div');
      el.className = 'cv-col cv-planfile'; el.dataset.file = p.file;
      el.innerHTML = cvPlanFileHtml(p);
      $('cv-cols').prepend(el);
    }
    if (plans.length) $('chasmview').hidden = false;
    CV.planFiles = plans.length;
  });
}
$('cv-cols').addEventListener('click', e => {
  if (!e.target.classList.contains('tog') || !e.target.closest('.cv-planfile')) return;
  e.target.parentElement.classList.toggle('collapsed');
});
$('cv-reload').addEventListener('click', cvLoadPlanFiles);
cvLoadPlanFiles();
