// The zenith operator console (docs/operator.md): the status pushed over the
// WebSocket /api/events, or polled from GET /api/status while that is not
// connected; commands with POST /api/command. Plain JavaScript, nothing
// fetched from elsewhere.
'use strict';

const POLL_MS = 500;
const RECONNECT_MS = 5000;  // a lost status push is tried again after this (polling meanwhile)
const PREVIEW_MS = 1000;

/// Parameters that make sense live, shown for an atmosphere when its
/// parameters have them (advanced mode: aerosol; standard mode: mie). The
/// ranges of the sliders are convenient ones; the master checks the real
/// ranges (docs/atmosphere-config.md) and answers with its error.
const LIVE_PARAMETERS = [
  {label: 'turbidity', pointer: '/aerosol/scattering/turbidity', min: 1, max: 10, step: 0.25},
  {label: 'aerosol scale height (m)', pointer: '/aerosol/scale_height_m', min: 100, max: 5000, step: 50},
  {label: 'Mie scale height (m)', pointer: '/mie/scale_height_m', min: 100, max: 5000, step: 50},
  {label: 'gas scale height (m)', pointer: '/gas/scale_height_m', min: 1000, max: 20000, step: 100},
  {label: 'ground albedo', pointer: '/planet/ground_albedo', min: 0, max: 1, step: 0.01},
  {label: 'air mass', pointer: '/air_mass', choices: ['geometric', 'pickering']},
  {label: 'ozone', pointer: '/ozone', toggle: true},
];

let token = sessionStorage.getItem('zenith-operator-token') || '';
let pushed = false;  // the status arrives over the WebSocket: no polling
let pushSocket = null;
let lastStatus = null;
const atmosphereViews = new Map();  // body → its controls
const removedBlocks = new Map();    // "body pointer" → the block a toggle removed (to put it back)

const $ = (id) => document.getElementById(id);

function headers(extra) {
  const h = Object.assign({}, extra);
  if (token) h.Authorization = 'Bearer ' + token;
  return h;
}

function showMessage(text, ok) {
  const m = $('message');
  m.textContent = text;
  m.className = ok ? 'ok' : 'error';
}

/// The value at a JSON pointer of `object`, or undefined.
function at(object, pointer) {
  let v = object;
  for (const token of pointer.split('/').slice(1)) {
    const key = token.replace(/~1/g, '/').replace(/~0/g, '~');
    if (v === null || typeof v !== 'object' || !(key in v)) return undefined;
    v = v[key];
  }
  return v;
}

async function send(command) {
  try {
    const response = await fetch('/api/command', {
      method: 'POST', headers: headers({'Content-Type': 'application/json'}), body: JSON.stringify(command)});
    const reply = await response.json();
    if (response.status === 401) askForToken();
    showMessage(reply.ok ? reply.reply : reply.error, reply.ok);
  } catch (e) {
    showMessage('cannot reach the master: ' + e, false);
  }
  poll();
}

function askForToken() {
  $('token-box').hidden = false;
}

/// The status pushes: while connected the page renders every pushed status and
/// does not poll; when the connection fails or drops it polls and tries again.
function connectPush() {
  let socket;
  try {
    socket = new WebSocket((location.protocol === 'https:' ? 'wss://' : 'ws://') + location.host + '/api/events');
  } catch (e) {
    setTimeout(connectPush, RECONNECT_MS);
    return;
  }
  pushSocket = socket;
  socket.addEventListener('open', () => {
    if (token) socket.send(JSON.stringify({token: token}));
  });
  socket.addEventListener('message', (event) => {
    pushed = true;
    $('transport').textContent = 'push';
    render(JSON.parse(event.data));
  });
  socket.addEventListener('close', () => {
    pushed = false;
    $('transport').textContent = 'polling';
    setTimeout(connectPush, RECONNECT_MS);
  });
}

async function poll() {
  try {
    const response = await fetch('/api/status', {headers: headers({}), cache: 'no-store'});
    if (response.status === 401) {
      askForToken();
      $('state').textContent = 'token needed';
      return;
    }
    render(await response.json());
  } catch (e) {
    $('state').textContent = 'offline';
    $('state').className = 'badge offline';
  }
}

function number(x, digits) {
  return typeof x === 'number' ? x.toFixed(digits) : '–';
}

function editing(element) {
  return document.activeElement === element || element.dataset.dragging === '1';
}

function render(s) {
  lastStatus = s;
  $('state').textContent = s.state;
  $('state').className = 'badge ' + s.state;
  $('frame').textContent = s.frame === null ? '–' : s.frame;
  $('show-time').textContent = number(s.show_time_s, 3) + ' s';
  $('show-name').textContent = s.show ? s.show.name : 'default show';
  // A show chasing the house's timecode: its state, last frame and drift (docs/operator.md, "Status").
  $('timecode').hidden = !s.timecode;
  if (s.timecode) {
    $('timecode-state').textContent = s.timecode.state + (s.timecode.before_start ? ', before the start' : '');
    $('timecode-detail').textContent = (s.timecode.last || '–') + ' at ' + s.timecode.rate + ' fps, drift ' +
        Math.round(s.timecode.drift_ppm) + ' ppm, ' + s.timecode.locates + ' locate' +
        (s.timecode.locates === 1 ? '' : 's');
  }

  // A chasing show takes its start on the timecode, not the clock's commands.
  $('chase-controls').hidden = !s.timecode;
  if (s.timecode) {
    $('timecode-offset-now').textContent = s.timecode.offset;
    if (!editing($('timecode-offset')) && $('timecode-offset').value === '') $('timecode-offset').value = s.timecode.offset;
  }

  $('no-clock').hidden = s.show !== null;
  $('clock-controls').hidden = s.show === null || !!s.timecode;
  if (s.show) {
    const seek = $('seek');
    seek.max = s.show.duration_s;
    if (!editing(seek)) seek.value = s.show_time_s;
    $('time-now').textContent = number(s.show_time_s, 2);
    $('duration').textContent = number(s.show.duration_s, 2);
    if (!editing($('rate'))) $('rate').value = s.show.rate;
    $('loop').checked = s.show.loop;
  }

  // Four significant digits: a show's exposure track interpolates.
  const exposure = s.exposure === null ? null : Number(s.exposure.toPrecision(4));
  $('exposure-now').textContent = exposure === null ? '–' : exposure;
  $('exposure-source').textContent = s.exposure_override === null ? "(the show's)" : '(operator)';
  if (!editing($('exposure')) && $('exposure').value === '' && exposure !== null) $('exposure').value = exposure;

  renderSun(s);
  renderFade(s.fade);
  renderPreview(s.preview);

  $('no-live').hidden = s.live_atmospheres;
  for (const a of s.atmospheres) renderAtmosphere(a, s.live_atmospheres);
  renderNodes(s.nodes);
}

/// The fade of the latest frame, and where the operator's fade is going.
function renderFade(f) {
  if (!f) return;
  $('fade-now').textContent = f.level === 0 ? 'the picture' : Math.round(f.level * 100) + ' %';
  $('fade-state').textContent = f.frames_left > 0
    ? '(to ' + Math.round(f.target_level * 100) + ' % in ' + f.frames_left + ' frames)'
    : f.level === 1 && f.colour.every((c) => c === 0) ? '(black)' : '';
}

/// "#rrggbb" → [r, g, b] in [0, 1] (the colour picker's sRGB, sent as the
/// display-linear values the fade uses).
function fadeColour() {
  const hex = $('fade-colour').value;
  const srgb = [1, 3, 5].map((i) => parseInt(hex.substr(i, 2), 16) / 255);
  return srgb.map((v) => (v <= 0.04045 ? v / 12.92 : Math.pow((v + 0.055) / 1.055, 2.4)));
}

/// The sun's angles now (the latest frame's) and whether they are the operator's.
function renderSun(s) {
  const now = s.sun;
  $('sun-elevation-now').textContent = now ? number(now.elevation_deg, 2) : '–';
  $('sun-azimuth-now').textContent = now ? number(now.azimuth_deg, 2) : '–';
  $('sun-source').textContent = s.sun_override ? '(operator)' : "(the show's)";
  if (!now) return;
  for (const [key, ids] of [['elevation_deg', ['sun-elevation-range', 'sun-elevation']],
                            ['azimuth_deg', ['sun-azimuth-range', 'sun-azimuth']]]) {
    const value = Number(now[key].toFixed(2));
    for (const id of ids)
      if (!editing($(id))) $(id).value = value;
  }
}

/// The dome preview's switch and what it shows.
function renderPreview(p) {
  $('preview-box').hidden = p === null;
  if (p === null) return;
  if (!editing($('preview-on'))) $('preview-on').checked = p.on;
  $('preview-image').hidden = !p.on || p.frame === null;
  $('preview-info').textContent = !p.on ? 'Off: the nodes send no thumbnails.'
      : p.frame === null ? 'Waiting for the first thumbnails…'
      : (p.layout === 'dome' ? 'The dome master' : 'The outputs side by side') + ', ' + p.width_px + '×' + p.height_px +
        ' px, ' + p.tiles + ' of ' + p.outputs + ' outputs, frame ' +
        (p.oldest_frame === p.frame ? p.frame : p.oldest_frame + '–' + p.frame);
}

let previewUrl = null;
/// Fetches the preview (with the token, so not as a plain image URL) while it is on.
async function refreshPreview() {
  if (!lastStatus || !lastStatus.preview || !lastStatus.preview.on || lastStatus.preview.frame === null) return;
  try {
    const response = await fetch('/api/preview', {headers: headers({}), cache: 'no-store'});
    if (!response.ok) return;
    const url = URL.createObjectURL(await response.blob());
    $('preview-image').src = url;
    if (previewUrl) URL.revokeObjectURL(previewUrl);
    previewUrl = url;
  } catch (e) {
    // the status shows that the master is offline
  }
}

/// A slider and its number box for one value: the box follows the slider
/// while it is dragged; `apply` gets the number once the slider is let go or
/// the box is changed (so a drag sends one command, not one per step).
function wireSliderAndBox(range, box, apply) {
  range.addEventListener('pointerdown', () => { range.dataset.dragging = '1'; });
  range.addEventListener('input', () => { box.value = range.value; });
  range.addEventListener('change', () => {
    range.dataset.dragging = '0';
    apply(Number(range.value));
  });
  box.addEventListener('change', () => apply(Number(box.value)));
}

/// A slider and a number box for one of the sun's angles; a change sends it alone.
function wireSunAngle(rangeId, boxId, key) {
  wireSliderAndBox($(rangeId), $(boxId), (value) => send(Object.assign({command: 'sun'}, {[key]: value})));
}

function makeControl(body, p, parameters) {
  const row = document.createElement('div');
  row.className = 'row control';
  const label = document.createElement('label');
  label.textContent = p.label;
  row.appendChild(label);
  const set = (value) => send({command: 'set', body: body, pointer: p.pointer, value: value});
  let update;
  if (p.choices) {
    const select = document.createElement('select');
    select.dataset.pointer = p.pointer;
    for (const c of p.choices) {
      const o = document.createElement('option');
      o.value = o.textContent = c;
      select.appendChild(o);
    }
    select.addEventListener('change', () => set(select.value));
    row.appendChild(select);
    update = (v) => { if (!editing(select) && v !== undefined) select.value = v; };
  } else if (p.toggle) {
    const box = document.createElement('input');
    box.type = 'checkbox';
    box.dataset.pointer = p.pointer;
    const key = body + ' ' + p.pointer;
    box.addEventListener('change', () => {
      if (box.checked) {
        if (removedBlocks.has(key)) set(removedBlocks.get(key));
      } else {
        const now = at(currentParameters(body), p.pointer);
        if (now !== undefined) removedBlocks.set(key, now);
        set(null);
      }
    });
    row.appendChild(box);
    update = (v) => {
      box.checked = v !== undefined;
      box.disabled = v === undefined && !removedBlocks.has(key);
    };
  } else {
    const range = document.createElement('input');
    range.type = 'range';
    const box = document.createElement('input');
    box.type = 'number';
    box.dataset.pointer = p.pointer;
    for (const e of [range, box]) {
      e.min = p.min;
      e.max = p.max;
      e.step = p.step;
    }
    box.step = 'any';
    wireSliderAndBox(range, box, set);
    row.appendChild(range);
    row.appendChild(box);
    update = (v) => {
      if (typeof v !== 'number') return;
      if (!editing(range)) range.value = v;
      if (!editing(box)) box.value = v;
    };
  }
  update(at(parameters, p.pointer));
  return {row, update, pointer: p.pointer};
}

function currentParameters(body) {
  const a = lastStatus && lastStatus.atmospheres.find((x) => x.body === body);
  return a ? a.parameters : null;
}

function makeAtmosphere(a, live) {
  const view = document.createElement('div');
  view.className = 'atmosphere';
  view.dataset.body = a.body;
  const title = document.createElement('h3');
  title.textContent = a.body;
  view.appendChild(title);
  const version = document.createElement('div');
  version.className = 'row';
  view.appendChild(version);
  const controls = [];
  if (live) {
    for (const p of LIVE_PARAMETERS) {
      if (!p.toggle && at(a.parameters, p.pointer) === undefined) continue;
      if (p.min !== undefined && typeof at(a.parameters, p.pointer) !== 'number') continue;
      const c = makeControl(a.body, p, a.parameters);
      controls.push(c);
      view.appendChild(c.row);
    }
    // Any other parameter: a JSON pointer and a JSON value.
    const any = document.createElement('form');
    any.className = 'row';
    const pointer = document.createElement('input');
    pointer.type = 'text';
    pointer.className = 'wide';
    pointer.placeholder = '/aerosol/phase/g1';
    const value = document.createElement('input');
    value.type = 'text';
    value.placeholder = 'JSON value';
    const button = document.createElement('button');
    button.type = 'submit';
    button.textContent = 'Set';
    any.append('parameter ', pointer, ' = ', value, button);
    any.addEventListener('submit', (e) => {
      e.preventDefault();
      let v;
      try {
        v = JSON.parse(value.value);
      } catch (err) {
        showMessage('the value is not JSON: ' + err.message, false);
        return;
      }
      send({command: 'set', body: a.body, pointer: pointer.value, value: v});
    });
    view.appendChild(any);
    // The operator's changes end: a show's track (or the scene's atmosphere) again.
    const own = document.createElement('div');
    own.className = 'row';
    const clear = document.createElement('button');
    clear.type = 'button';
    clear.className = 'clear-atmosphere';
    clear.textContent = lastStatus && lastStatus.show ? "The show's own" : "The scene's own";
    clear.addEventListener('click', () => send({command: 'clear', what: 'atmosphere', body: a.body}));
    const changes = document.createElement('span');
    changes.className = 'muted operator-changes';
    own.append(clear, changes);
    view.appendChild(own);
    view.changes = changes;
  }
  const pending = document.createElement('div');
  pending.className = 'row pending';
  view.appendChild(pending);
  $('atmospheres').appendChild(view);
  return {view, version, pending, controls};
}

function renderAtmosphere(a, live) {
  let v = atmosphereViews.get(a.body);
  if (!v) {
    v = makeAtmosphere(a, live);
    atmosphereViews.set(a.body, v);
  }
  v.version.replaceChildren('table version ', Object.assign(document.createElement('span'), {
    className: 'version', textContent: a.version}), ' since frame ' + a.effective_from_frame);
  v.version.dataset.version = a.version;
  if (v.view.changes) {
    v.view.changes.textContent = a.operator_changes ? "operator's changes on the show's version " + a.show_version + ': ' +
                                                      a.operator_changes
                               : a.show_version ? "the show's track" : '';
    v.view.dataset.overridden = a.operator_changes ? '1' : '0';
  }
  for (const c of v.controls) c.update(at(a.parameters, c.pointer));
  const parts = [];
  if (a.pending) {
    const p = a.pending;
    const bar = document.createElement('progress');
    bar.max = 1;
    bar.value = p.stage === 'loading on the nodes' ? (p.nodes_ready ? p.nodes_holding / p.nodes_ready : 0) : p.fraction;
    const detail = p.stage === 'preparing' ? (p.precompute_stage || '') + ' ' + Math.round(100 * p.fraction) + ' %'
                 : p.stage === 'loading on the nodes' ? p.nodes_holding + ' of ' + p.nodes_ready + ' nodes hold it'
                 : '';
    parts.push('new version ', Object.assign(document.createElement('span'), {className: 'version', textContent: p.version}),
               ' (' + p.change + '): ' + p.stage + ' ', bar, ' ' + detail);
  }
  if (a.waiting) parts.push(' next: ' + a.waiting);
  v.pending.replaceChildren(...parts);
  v.pending.dataset.stage = a.pending ? a.pending.stage : '';
}

/// A node's link (docs/operator.md, "Status"): how its frames reach it.
function linkText(link) {
  if (!link) return '–';
  if (link.state === 'unreachable') return 'UNREACHABLE ' + (link.silent_ms / 1000).toFixed(1) + ' s';
  return link.state;
}

/// How long its tables took at its latest join (docs/operator.md, "Status").
function tablesText(tables) {
  if (!tables) return '–';
  return (tables.bytes / 1e6).toFixed(1) + ' MB in ' + tables.seconds.toFixed(1) + ' s';
}

function renderNodes(nodes) {
  const body = $('nodes').tBodies[0];
  const rows = nodes.map((n) => {
    const tr = document.createElement('tr');
    tr.dataset.node = n.name;
    const cells = [n.name, n.host, n.state, n.last_render_ms === null ? '–' : n.last_render_ms.toFixed(1) + ' ms',
                   n.frames_rendered, n.barrier_waits, n.drops, n.rejoins, n.presents, n.late_presents,
                   n.missed_frames, linkText(n.link), tablesText(n.tables), n.tables_held.join(', ')];
    cells.forEach((c, i) => {
      const td = document.createElement('td');
      td.textContent = c;
      if (i === 2) td.className = 'state-' + String(n.state).split(' ')[0];
      tr.appendChild(td);
    });
    return tr;
  });
  body.replaceChildren(...rows);
}

function wire() {
  $('play').addEventListener('click', () => send({command: 'play'}));
  $('pause').addEventListener('click', () => send({command: 'pause'}));
  $('toggle').addEventListener('click', () => send({command: 'toggle'}));
  $('loop').addEventListener('change', () => send({command: 'loop', loop: $('loop').checked}));
  const seek = $('seek');
  seek.addEventListener('pointerdown', () => { seek.dataset.dragging = '1'; });
  seek.addEventListener('change', () => {
    seek.dataset.dragging = '0';
    send({command: 'seek', seconds: Number(seek.value)});
  });
  $('rate-apply').addEventListener('click', () => send({command: 'rate', rate: Number($('rate').value)}));
  $('timecode-offset-apply').addEventListener('click',
      () => send({command: 'timecode', offset: $('timecode-offset').value.trim()}));
  $('chase-play').addEventListener('click', () => send({command: 'play'}));
  $('exposure-apply').addEventListener('click', () => send({command: 'exposure', exposure: Number($('exposure').value)}));
  $('exposure-reset').addEventListener('click', () => {
    $('exposure').value = '';
    send({command: 'exposure', exposure: null});
  });
  const fadeSeconds = () => Number($('fade-seconds').value) || 0;
  $('fade-out').addEventListener('click', () => send({command: 'fade', level: 1, seconds: fadeSeconds(), colour: fadeColour()}));
  $('fade-in').addEventListener('click', () => send({command: 'fade', level: 0, seconds: fadeSeconds()}));
  $('blackout').addEventListener('click', () => send({command: 'blackout'}));
  wireSunAngle('sun-elevation-range', 'sun-elevation', 'elevation_deg');
  wireSunAngle('sun-azimuth-range', 'sun-azimuth', 'azimuth_deg');
  $('sun-reset').addEventListener('click', () => send({command: 'clear', what: 'sun'}));
  $('preview-on').addEventListener('change', () => send({command: 'preview', preview: $('preview-on').checked}));
  setInterval(refreshPreview, PREVIEW_MS);
  $('token-form').addEventListener('submit', (e) => {
    e.preventDefault();
    token = $('token').value;
    sessionStorage.setItem('zenith-operator-token', token);
    $('token-box').hidden = true;
    poll();
    if (pushSocket && pushSocket.readyState === WebSocket.OPEN) pushSocket.send(JSON.stringify({token: token}));
  });
  poll();
  setInterval(() => { if (!pushed) poll(); }, POLL_MS);
  connectPush();
}

wire();
