// hapscene live view: reads the scene (GET /api/scene), plots the tick stream
// (GET /api/stream, Server-Sent Events) at the display's frame rate, and sends parameter
// changes (POST /api/params), saves (POST /api/save) and validates (POST /api/validate).
// Plain JavaScript, no library: the plots are drawn on canvases here.
'use strict';
(() => {
  const token = new URLSearchParams(location.search).get('token') || '';
  const api = (path) => path + '?token=' + encodeURIComponent(token);
  const WINDOW_S = 5;   // the time plots' span
  const TRACE_S = 3;    // the force-position trace's span
  const $ = (id) => document.getElementById(id);

  // What the page has seen and drawn, for people debugging it and for the browser test.
  const view = window.hapsceneView = {
    events: 0, samples: 0, frames: 0, ended: false, scene: null,
    last: null,       // the newest tick received
    plotted: null,    // the newest tick drawn, and when
    changes: 0, refused: 0, lastError: null, droppedEvents: 0,
    faults: [],       // the script faults shown, each once (their messages)
    end: null,        // the "end" event's data: {reason, fault, message}
    links: [],        // the device's links, as the newest event gave them
    ticks: {},        // per plot: the tick values on its axes, {x: [...], y: [...]}
    drawn: {},        // per plot: the names of the lines and marks drawn in the last frame
    handSent: 0,      // POST /api/hand requests answered (the pointer taking the hand, or letting go)
    hand: null,       // the last answer: {"hand": "pointer", "x_m", ...} or {"hand": "released"}
  };

  let scene = null;
  // The ticks of the last WINDOW_S seconds, column by column (2-D: x and y components).
  const ticks = { t: [], x: [], y: [], fx: [], fy: [], ox: [], oy: [] };
  let proxies = [];
  let status = null;

  // ---- units shown on the page (the API is SI) ----
  const DISPLAY = { length: { unit: 'mm', scale: 1e-3 } };
  const shown = (p) => DISPLAY[p.quantity] || { unit: p.unit || '', scale: 1 };
  const fmt = (v, digits = 4) => (v === null || v === undefined || !isFinite(v)) ? '-' : Number(v.toPrecision(digits)).toString();

  // ---- the scene and its parameters ----
  async function loadScene() {
    const response = await fetch(api('/api/scene'));
    if (!response.ok) throw new Error((await response.json()).error);
    const s = await response.json();
    setScene(s);
    buildParams();
    for (const f of s.script_faults || []) addFault(f);
  }

  function setScene(s) {
    scene = s;
    view.scene = s;
    $('scene-name').textContent = s.name;
    $('scene-file').textContent = s.file + ' on ' + s.device.name + ', ' + s.rate_hz + ' Hz, ' + s.axes + '-DOF';
    $('unsaved').textContent = s.unsaved ? '(changed, not saved)' : '';
    // Each plot's title names its lines with their colours (the keys); draw() names what it drew.
    $('position-title').innerHTML = s.axes === 1 ? 'position (mm) against time (s): ' + keys(['x'])
                                                 : 'position (mm) against time (s): ' + keys(['x', 'y']);
    // 1-D: the scene along the workspace under the trace (the walls' solid sides, the
    // textures' fields, the static force curve), and the handle now.
    const marks = (kind) => (s.shapes || []).some((shape) => shape.kind === kind);
    $('trace-title').innerHTML = s.axes === 1
      ? 'the scene, force (N) against position (mm), last 3 s: ' +
        keys(['asked', 'commanded', 'limit'].concat(s.force_curve ? ['static'] : [], marks('wall') ? ['solid'] : [],
                                                  marks('texture') ? ['field'] : [], ['handle']))
      : 'the plane (mm), 1:1: ' + keys(['handle', 'proxy', 'commanded', 'shape', 'workspace']);
  }
  const KEY_NAMES = { x: 'x', y: 'y', asked: 'asked', commanded: 'commanded', limit: 'limit', handle: 'handle',
                      proxy: 'proxies', shape: 'shapes', workspace: 'workspace',
                      static: 'at rest (probe)', solid: 'solid side', field: 'texture fields' };
  const keys = (names) => names.map((n) => '<span class="key ' + n + '" data-key="' + n + '">' + KEY_NAMES[n] + '</span>').join(' ');

  const paramKey = (p) => p.effect + ':' + p.parameter;
  const controls = new Map();  // paramKey -> {row, range, number, p}

  function buildParams() {
    const box = $('params');
    box.textContent = '';
    controls.clear();
    let current = null;
    for (const p of scene.parameters) {
      if (!current || current.effect !== p.effect) {
        const effect = scene.effects[p.effect] || { type: p.type };
        current = { effect: p.effect, node: document.createElement('div') };
        current.node.className = 'effect';
        const title = document.createElement('div');
        title.className = 'effect-title';
        title.textContent = '/effects/' + p.effect + ' ' + p.type + (effect.file ? ' (' + effect.file + ')' : '');
        current.node.appendChild(title);
        box.appendChild(current.node);
      }
      const d = shown(p);
      const row = document.createElement('div');
      row.className = 'param';
      row.title = 'range: ' + p.range_from + (p.written ? '' : ' (not written in the file: the default)');
      const label = document.createElement('label');
      label.textContent = p.label;
      const range = document.createElement('input');
      range.type = 'range';
      range.min = p.min / d.scale;
      range.max = p.max / d.scale;
      range.step = (p.max - p.min) / d.scale / 1000 || 'any';
      range.value = p.value / d.scale;
      range.dataset.param = paramKey(p);
      const number = document.createElement('input');
      number.type = 'number';
      number.step = 'any';
      number.value = fmt(p.value / d.scale, 6);
      number.dataset.param = paramKey(p);
      const unit = document.createElement('span');
      unit.className = 'unit';
      unit.textContent = d.unit;
      row.append(label, range, number, unit);
      current.node.appendChild(row);
      const control = { row, range, number, p };
      controls.set(paramKey(p), control);
      range.addEventListener('input', () => { number.value = fmt(Number(range.value), 6); request(control, Number(range.value) * d.scale, false); });
      range.addEventListener('change', () => request(control, Number(range.value) * d.scale, true));
      number.addEventListener('change', () => request(control, Number(number.value) * d.scale, true));
    }
  }

  // Shows the scene's values in the controls (after a change taken or refused).
  function syncControls() {
    for (const p of scene.parameters) {
      const c = controls.get(paramKey(p));
      if (!c) continue;
      const d = shown(p);
      c.p = p;
      c.range.min = p.min / d.scale;
      c.range.max = p.max / d.scale;
      if (document.activeElement !== c.range) c.range.value = p.value / d.scale;
      if (document.activeElement !== c.number) c.number.value = fmt(p.value / d.scale, 6);
    }
  }

  // One request in flight; while dragging, the newest value waits for it (older ones are skipped).
  let inFlight = false;
  let queued = null;
  async function request(control, value, final) {
    if (inFlight) { queued = { control, value }; return; }
    inFlight = true;
    try {
      const response = await fetch(api('/api/params'), {
        method: 'POST', headers: { 'Content-Type': 'application/json' },
        body: JSON.stringify({ effect: control.p.effect, parameter: control.p.parameter, value }),
      });
      const body = await response.json();
      if (response.ok) {
        view.changes++;
        control.row.classList.remove('refused');
        $('param-error').hidden = true;
        setScene(body);
        syncControls();
      } else {
        view.refused++;
        view.lastError = body.error;
        control.row.classList.add('refused');
        $('param-error').hidden = false;
        $('param-error').textContent = body.error;
        syncControls();  // back to the values running
      }
    } catch (error) {
      view.lastError = String(error);
    } finally {
      inFlight = false;
      if (queued) { const next = queued; queued = null; request(next.control, next.value, final); }
    }
  }

  $('save-button').addEventListener('click', async () => {
    const response = await fetch(api('/api/save'), { method: 'POST' });
    const body = await response.json();
    $('save-result').textContent = response.ok ? 'saved to ' + body.saved + ' (' + body.bytes + ' bytes)' : body.error;
    if (response.ok) { scene.unsaved = false; $('unsaved').textContent = ''; }
  });

  $('validate-button').addEventListener('click', async () => {
    const button = $('validate-button');
    button.disabled = true;
    $('validate-verdict').textContent = 'running the harness on the current values...';
    try {
      const response = await fetch(api('/api/validate'), { method: 'POST' });
      const body = await response.json();
      if (response.ok) {
        $('validate-verdict').innerHTML = body.pass ? '<span class="pass">PASS</span>' : '<span class="fail">FAIL</span>';
        $('validate-table').textContent = body.table;
      } else {
        $('validate-verdict').textContent = body.error;
        $('validate-table').textContent = '';
      }
    } finally {
      button.disabled = false;
    }
  });

  // ---- the stream ----
  function onTicks(message) {
    const d = JSON.parse(message.data);
    view.events++;
    view.droppedEvents = d.dropped_events;
    const n = d.t_s.length;
    const two = scene && scene.axes === 2;
    for (let i = 0; i < n; i++) {
      ticks.t.push(d.t_s[i]);
      ticks.x.push(d.x_m[i]);
      if (two) {
        ticks.y.push(d.y_m[i]);
        ticks.fx.push(d.force_x_N[i]); ticks.fy.push(d.force_y_N[i]);
        ticks.ox.push(d.output_x_N[i]); ticks.oy.push(d.output_y_N[i]);
      } else {
        ticks.fx.push(d.force_N[i]);
        ticks.ox.push(d.output_N[i]);
      }
    }
    view.samples += n;
    if (n > 0) {
      const k = n - 1;
      view.last = two ? { t_s: d.t_s[k], x_m: d.x_m[k], y_m: d.y_m[k], force_x_N: d.force_x_N[k], force_y_N: d.force_y_N[k], output_x_N: d.output_x_N[k], output_y_N: d.output_y_N[k] }
                      : { t_s: d.t_s[k], x_m: d.x_m[k], force_N: d.force_N[k], output_N: d.output_N[k] };
    }
    if (d.proxies_m) proxies = d.proxies_m;
    // Keep WINDOW_S seconds.
    const newest = ticks.t.length ? ticks.t[ticks.t.length - 1] : 0;
    let drop = 0;
    while (drop < ticks.t.length && ticks.t[drop] < newest - WINDOW_S) drop++;
    if (drop > 0) for (const key of Object.keys(ticks)) ticks[key].splice(0, drop);
    status = d.status;
    showStatus(d);
    for (const f of d.script_faults || []) addFault(f);
    for (const line of d.log) addLog(line);
  }

  function showStatus(d) {
    const s = d.status;
    $('st-time').textContent = fmt(s.t_s, 6) + ' s';
    $('st-rate').textContent = fmt(s.loop_rate_hz, 5) + ' Hz';
    $('st-misses').textContent = s.deadline_misses === null ? 'n/a' : s.deadline_misses + (s.overrun_warnings ? ' (' + s.overrun_warnings + ' warnings)' : '');
    $('st-jitter').textContent = s.wake_late_max_us === null ? 'n/a' : fmt(s.wake_late_max_us, 3) + ' us';
    $('st-compute').textContent = s.compute_max_us === null ? 'n/a' : fmt(s.compute_max_us, 3) + ' us';
    $('st-energy').textContent = fmt(s.energy_J * 1e3, 4) + ' mJ';
    $('st-stream').textContent = 'event ' + d.seq + ', every ' + (d.stride === 1 ? 'tick' : d.stride + ' ticks') +
      ', dropped ' + d.dropped_events + ' events / ' + s.dropped_ticks + ' ticks';
    const rows = Object.entries(s.safety).map(([k, v]) => '<tr><th>' + k.replace(/_/g, ' ') + '</th><td>' + v + '</td></tr>');
    $('safety-table').innerHTML = rows.join('');
    $('st-scripts').textContent = 'disabled now: ' + s.scripts_disabled.length + ', faults in the run: ' + s.script_faults;
    showLinks(s.links || []);
  }

  // A script fault, shown once (a reconnected stream or the scene's list may repeat it).
  const faultsShown = new Set();
  function addFault(f) {
    if (faultsShown.has(f.number)) return;
    faultsShown.add(f.number);
    view.faults.push(f.message);
    const div = document.createElement('div');
    div.className = 'error fault';
    div.textContent = 't ' + fmt(f.t_s, 6) + ' s, script ' + f.script + ' disabled (' + f.kind.replace(/_/g, ' ') +
      ', 0 N from then on): ' + f.message;
    $('faults').appendChild(div);
  }

  // The device's links: one column per board.
  const LINK_ROWS = [
    ['state', (l) => l.state], ['commands', (l) => l.commands], ['replies', (l) => l.replies],
    ['round trip mean', (l) => l.round_trip_us.mean === null ? '-' : fmt(l.round_trip_us.mean, 4) + ' us'],
    ['round trip max', (l) => fmt(l.round_trip_us.max, 4) + ' us'],
    ['CRC / length errors', (l) => l.crc_errors + ' / ' + l.length_errors], ['bytes skipped', (l) => l.bytes_skipped],
    ['lost frames', (l) => l.lost_frames], ['unanswered', (l) => l.unanswered], ['not sent whole', (l) => l.frames_not_sent],
    ['stale reads', (l) => l.stale_reads], ['board timeouts', (l) => l.board_timeouts], ['implausible', (l) => l.implausible],
    ['resyncs', (l) => l.resyncs], ['connects', (l) => l.connects], ['board resets', (l) => l.board_resets],
    ['silences / vanished', (l) => l.silences + ' / ' + l.vanished],
    ['board saw CRC errors', (l) => l.board_saw ? l.board_saw.crc_errors : '-'],
    ['board saw lost frames', (l) => l.board_saw ? l.board_saw.lost_frames : '-'],
  ];
  function showLinks(links) {
    view.links = links;
    $('links-panel').hidden = links.length === 0;
    if (links.length === 0) return;
    const esc = (v) => String(v).replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' })[c]);
    const head = '<tr><th></th>' + links.map((l) => '<th>' + esc((l.joint ? 'joint ' + l.joint + ': ' : '') + (l.board || 'link')) + '</th>').join('') + '</tr>';
    const rows = LINK_ROWS.map(([name, value]) => '<tr><th>' + name + '</th>' + links.map((l) => '<td>' + esc(value(l)) + '</td>').join('') + '</tr>');
    $('links-table').innerHTML = head + rows.join('');
  }

  function addLog(line) {
    const li = document.createElement('li');
    li.textContent = line;
    $('log').appendChild(li);
    while ($('log').children.length > 200) $('log').firstChild.remove();
    $('log').scrollTop = $('log').scrollHeight;
  }

  function connect() {
    const source = new EventSource(api('/api/stream'));
    source.onopen = () => { $('connection').textContent = 'live'; $('connection').className = 'badge live'; };
    source.onmessage = onTicks;
    // The log so far, sent first on every (re)connection: it replaces what the list shows.
    source.addEventListener('log', (message) => {
      let history = [];
      try { history = JSON.parse(message.data).log || []; } catch (error) { history = []; }
      $('log').textContent = '';
      for (const line of history) addLog(line);
    });
    // The run's last event: how it ended; a fault that ended it is shown with the script faults.
    source.addEventListener('end', (message) => {
      view.ended = true;
      source.close();
      let end = {};
      try { end = JSON.parse(message.data); } catch (error) { end = {}; }
      view.end = end;
      $('connection').textContent = end.fault ? 'run stopped: fault' : 'run ended';
      $('connection').className = 'badge ended';
      if (end.message) addLog('run ended: ' + end.message);
      if (end.fault) {
        const div = document.createElement('div');
        div.className = 'error run-fault';
        div.textContent = end.message;
        $('faults').appendChild(div);
      }
    });
    source.onerror = () => {
      if (view.ended) return;
      $('connection').textContent = 'connection lost';
      $('connection').className = 'badge lost';
    };
  }

  // ---- plots ----
  // Round tick values: steps of 1, 2 or 5 times a power of ten, about `count` of them.
  function roundTicks(range, count = 5) {
    const span = range[1] - range[0];
    if (!(span > 0) || !isFinite(span)) return { values: [range[0]], step: 1 };
    const raw = span / count;
    const power = Math.pow(10, Math.floor(Math.log10(raw)));
    const m = raw / power;  // in [1, 10): the nearest of 1, 2, 5 and 10
    const step = (m < 1.5 ? 1 : m < 3 ? 2 : m < 7 ? 5 : 10) * power;
    const values = [];
    for (let v = Math.ceil(range[0] / step - 1e-9) * step; v <= range[1] + step * 1e-9; v += step) {
      values.push(Math.abs(v) < step * 1e-9 ? 0 : Number(v.toPrecision(12)));
    }
    return { values, step };
  }
  // The label of a tick: as many decimals as the step needs.
  const tickLabel = (v, step) => v.toFixed(Math.max(0, -Math.floor(Math.log10(step) + 1e-9)));

  const frames = {};  // per canvas: the last frame's mapping from pixels back to data

  // A canvas sized to its box in device pixels, and a mapping from data to pixels.
  function frame(canvas, xRange, yRange) {
    const ratio = window.devicePixelRatio || 1;
    const w = canvas.clientWidth, h = canvas.clientHeight;
    if (canvas.width !== Math.round(w * ratio) || canvas.height !== Math.round(h * ratio)) {
      canvas.width = Math.round(w * ratio);
      canvas.height = Math.round(h * ratio);
    }
    const g = canvas.getContext('2d');
    g.setTransform(ratio, 0, 0, ratio, 0, 0);
    g.clearRect(0, 0, w, h);
    const left = 52, right = 10, top = 6, bottom = 22;
    const sx = (v) => left + (v - xRange[0]) / (xRange[1] - xRange[0]) * (w - left - right);
    const sy = (v) => h - bottom - (v - yRange[0]) / (yRange[1] - yRange[0]) * (h - top - bottom);
    // Axes with round ticks and faint grid lines.
    g.strokeStyle = '#d2d2d7';
    g.fillStyle = '#6e6e73';
    g.font = '11px system-ui, sans-serif';
    g.lineWidth = 1;
    g.strokeRect(left, top, w - left - right, h - top - bottom);
    const xt = roundTicks(xRange), yt = roundTicks(yRange, 4);
    g.strokeStyle = '#f0f0f2';
    for (const yv of yt.values) {
      g.beginPath(); g.moveTo(left, sy(yv)); g.lineTo(w - right, sy(yv)); g.stroke();
      g.fillText(tickLabel(yv, yt.step), 4, sy(yv) + 4);
    }
    for (const xv of xt.values) {
      g.beginPath(); g.moveTo(sx(xv), top); g.lineTo(sx(xv), h - bottom); g.stroke();
      const label = tickLabel(xv, xt.step);
      g.fillText(label, sx(xv) - g.measureText(label).width / 2, h - 6);
    }
    view.ticks[canvas.id] = { x: xt.values, y: yt.values };
    view.drawn[canvas.id] = [];
    // Pixels (CSS, from the canvas's corner) back to data, for the pointer.
    const ix = (px) => xRange[0] + (px - left) / (w - left - right) * (xRange[1] - xRange[0]);
    const iy = (py) => yRange[0] + (h - bottom - py) / (h - top - bottom) * (yRange[1] - yRange[0]);
    frames[canvas.id] = { ix, iy };
    return { g, sx, sy, w, h, id: canvas.id };
  }
  // Notes what a plot drew, by its key's name.
  const drew = (f, name) => { if (!view.drawn[f.id].includes(name)) view.drawn[f.id].push(name); };

  function line(f, name, xs, ys, color, scaleX = 1, scaleY = 1, start = 0, width = 1.5) {
    const { g, sx, sy } = f;
    drew(f, name);
    g.strokeStyle = color;
    g.lineWidth = width;
    g.beginPath();
    for (let i = start; i < xs.length; i++) {
      const px = sx(xs[i] * scaleX), py = sy(ys[i] * scaleY);
      if (i === start) g.moveTo(px, py); else g.lineTo(px, py);
    }
    g.stroke();
  }

  function hline(f, name, y, xRange, color) {
    const { g, sx, sy } = f;
    drew(f, name);
    g.strokeStyle = color;
    g.setLineDash([5, 4]);
    g.beginPath();
    g.moveTo(sx(xRange[0]), sy(y));
    g.lineTo(sx(xRange[1]), sy(y));
    g.stroke();
    g.setLineDash([]);
  }

  const css = (name) => getComputedStyle(document.documentElement).getPropertyValue(name).trim();
  const magnitude = (a, b) => a.map((v, i) => Math.hypot(v, b[i]));

  function draw() {
    requestAnimationFrame(draw);
    if (!scene || ticks.t.length === 0) return;
    const two = scene.axes === 2;
    const newest = ticks.t[ticks.t.length - 1];
    const tRange = [Math.max(0, newest - WINDOW_S), Math.max(WINDOW_S, newest)];
    const limit = scene.device.max_force_N;
    const lo = scene.device.workspace_min_m, hi = scene.device.workspace_max_m;

    // Position against time.
    const posRange = two ? [Math.min(lo[0], lo[1]) * 1e3, Math.max(hi[0], hi[1]) * 1e3] : [lo * 1e3, hi * 1e3];
    const fp = frame($('plot-position'), tRange, posRange);
    line(fp, 'x', ticks.t, ticks.x, css('--x'), 1, 1e3);
    if (two) line(fp, 'y', ticks.t, ticks.y, css('--y'), 1, 1e3);

    // Force against time, with the limit.
    const forceRange = two ? [0, limit * 1.15] : [-limit * 1.15, limit * 1.15];
    const ff = frame($('plot-force'), tRange, forceRange);
    hline(ff, 'limit', limit, tRange, css('--limit'));
    if (!two) hline(ff, 'limit', -limit, tRange, css('--limit'));
    if (two) {
      line(ff, 'commanded', ticks.t, magnitude(ticks.ox, ticks.oy), css('--commanded'), 1, 1, 0, 3);
      line(ff, 'asked', ticks.t, magnitude(ticks.fx, ticks.fy), css('--asked'));
    } else {
      // Commanded first and wider: where it equals the asked force both show.
      line(ff, 'commanded', ticks.t, ticks.ox, css('--commanded'), 1, 1, 0, 3);
      line(ff, 'asked', ticks.t, ticks.fx, css('--asked'));
    }

    // Force against position over the last TRACE_S s (1-D), or the plane (2-D).
    let start = 0;
    while (start < ticks.t.length && ticks.t[start] < newest - TRACE_S) start++;
    if (two) drawPlane(start); else {
      const ft = frame($('plot-trace'), [lo * 1e3, hi * 1e3], [-limit * 1.15, limit * 1.15]);
      drawSceneMarks(ft, lo, hi, limit);
      hline(ft, 'limit', limit, [lo * 1e3, hi * 1e3], css('--limit'));
      hline(ft, 'limit', -limit, [lo * 1e3, hi * 1e3], css('--limit'));
      if (scene.force_curve) {
        ft.g.setLineDash([2, 3]);
        line(ft, 'static', scene.force_curve.x_m, scene.force_curve.output_N, css('--static'), 1e3, 1, 0, 2);
        ft.g.setLineDash([]);
      }
      line(ft, 'commanded', ticks.x, ticks.ox, css('--commanded'), 1e3, 1, start, 3);
      line(ft, 'asked', ticks.x, ticks.fx, css('--asked'), 1e3, 1, start);
      // The handle now: a line at its position, and a dot at the force commanded there.
      const k = ticks.t.length - 1;
      const hx = ft.sx(ticks.x[k] * 1e3);
      drew(ft, 'handle');
      ft.g.strokeStyle = css('--x');
      ft.g.lineWidth = 1;
      ft.g.beginPath(); ft.g.moveTo(hx, ft.sy(-limit * 1.15)); ft.g.lineTo(hx, ft.sy(limit * 1.15)); ft.g.stroke();
      ft.g.fillStyle = css('--x');
      ft.g.beginPath(); ft.g.arc(hx, ft.sy(ticks.ox[k]), 4.5, 0, 2 * Math.PI); ft.g.fill();
    }
    view.frames++;
    view.plotted = Object.assign({ drawn_at_ms: performance.now() }, view.last);
  }

  // The 1-D scene under the trace: each wall's solid side (hatched, from the wall to the
  // workspace's end) and each texture's fields (bands), across the force range.
  function drawSceneMarks(f, lo, hi, limit) {
    const { g, sx, sy } = f;
    const top = sy(limit * 1.15), bottom = sy(-limit * 1.15);
    for (const shape of scene.shapes || []) {
      if (shape.kind === 'wall') {
        drew(f, 'solid');
        const from = shape.solid === 'above' ? shape.position_m : lo, to = shape.solid === 'above' ? hi : shape.position_m;
        g.fillStyle = css('--solid');
        g.fillRect(sx(from * 1e3), top, sx(to * 1e3) - sx(from * 1e3), bottom - top);
        g.strokeStyle = css('--solid-edge');
        g.lineWidth = 2;
        g.beginPath(); g.moveTo(sx(shape.position_m * 1e3), top); g.lineTo(sx(shape.position_m * 1e3), bottom); g.stroke();
      } else if (shape.kind === 'texture') {
        drew(f, 'field');
        g.fillStyle = css('--field');
        for (const [from, to] of shape.fields_m) g.fillRect(sx(from * 1e3), top, Math.max(1, sx(to * 1e3) - sx(from * 1e3)), bottom - top);
      }
    }
  }

  function drawPlane(start) {
    const canvas = $('plot-trace');
    const lo = scene.device.workspace_min_m, hi = scene.device.workspace_max_m;
    // Equal scales in x and y: widen the shorter range to the canvas's aspect.
    const w = canvas.clientWidth - 62, h = canvas.clientHeight - 28;  // the frame's margins
    let xr = [lo[0] * 1e3, hi[0] * 1e3], yr = [lo[1] * 1e3, hi[1] * 1e3];
    const mmPerPx = Math.max((xr[1] - xr[0]) / w, (yr[1] - yr[0]) / h);
    const cx = (xr[0] + xr[1]) / 2, cy = (yr[0] + yr[1]) / 2;
    xr = [cx - mmPerPx * w / 2, cx + mmPerPx * w / 2];
    yr = [cy - mmPerPx * h / 2, cy + mmPerPx * h / 2];
    const f = frame(canvas, xr, yr);
    const { g, sx, sy } = f;
    // The workspace and the shapes.
    drew(f, 'workspace');
    g.strokeStyle = css('--limit');
    g.setLineDash([4, 3]);
    g.strokeRect(sx(lo[0] * 1e3), sy(hi[1] * 1e3), sx(hi[0] * 1e3) - sx(lo[0] * 1e3), sy(lo[1] * 1e3) - sy(hi[1] * 1e3));
    g.setLineDash([]);
    g.fillStyle = 'rgba(31, 119, 180, 0.15)';
    g.strokeStyle = '#1f77b4';
    for (const s of scene.shapes) {
      drew(f, 'shape');
      g.beginPath();
      if (s.kind === 'circle') {
        g.arc(sx(s.center_m[0] * 1e3), sy(s.center_m[1] * 1e3), s.radius_m * 1e3 / mmPerPx, 0, 2 * Math.PI);
      } else if (s.kind === 'wall') {
        // The wall's line across the workspace.
        const p = s.point_m, n = s.normal, d = [-n[1], n[0]], span = 1;
        g.moveTo(sx((p[0] - d[0] * span) * 1e3), sy((p[1] - d[1] * span) * 1e3));
        g.lineTo(sx((p[0] + d[0] * span) * 1e3), sy((p[1] + d[1] * span) * 1e3));
      } else {
        s.points_m.forEach((p, i) => (i ? g.lineTo : g.moveTo).call(g, sx(p[0] * 1e3), sy(p[1] * 1e3)));
        g.closePath();
      }
      if (s.kind !== 'wall' && s.solid_inside) g.fill();
      g.stroke();
    }
    // The handle's path, the handle, the proxies and the commanded force.
    line(f, 'handle', ticks.x, ticks.y, css('--x'), 1e3, 1e3, start);
    const k = ticks.t.length - 1;
    const hx = sx(ticks.x[k] * 1e3), hy = sy(ticks.y[k] * 1e3);
    g.fillStyle = css('--x');
    g.beginPath(); g.arc(hx, hy, 5, 0, 2 * Math.PI); g.fill();
    g.fillStyle = css('--asked');
    for (const p of proxies) {
      drew(f, 'proxy');
      g.beginPath(); g.arc(sx(p[0] * 1e3), sy(p[1] * 1e3), 3.5, 0, 2 * Math.PI); g.fill();
    }
    const pxPerN = 40;
    drew(f, 'commanded');
    g.strokeStyle = css('--commanded');
    g.lineWidth = 2;
    g.beginPath(); g.moveTo(hx, hy); g.lineTo(hx + ticks.ox[k] * pxPerN, hy - ticks.oy[k] * pxPerN); g.stroke();
  }

  // ---- the pointer takes the simulated hand (POST /api/hand) ----
  // On a simulated device, pressing on the scene's plot (1-D: along the position axis;
  // 2-D: in the plane) has the hand pull the handle there, following the pointer while it
  // is held; letting go gives the hand back to its scripted motion. One request at a time,
  // the newest position kept while one is under way.
  let handBusy = false, handNext = null;
  async function sendHand(body) {
    if (handBusy) { handNext = body; return; }
    handBusy = true;
    try {
      const response = await fetch(api('/api/hand'), { method: 'POST', body: JSON.stringify(body) });
      view.hand = await response.json();
      view.handSent++;
    } catch (error) {
      view.hand = { error: String(error) };
    }
    handBusy = false;
    if (handNext) { const next = handNext; handNext = null; sendHand(next); }
  }
  function pointerTarget(event) {
    const f = frames['plot-trace'];
    if (!f) return null;
    const r = event.currentTarget.getBoundingClientRect();
    const lo = scene.device.workspace_min_m, hi = scene.device.workspace_max_m;
    const clamp = (v, a, b) => Math.min(b, Math.max(a, v));
    const x = f.ix(event.clientX - r.left) * 1e-3;
    if (scene.axes === 1) return { x_m: clamp(x, lo, hi) };
    return { x_m: clamp(x, lo[0], hi[0]), y_m: clamp(f.iy(event.clientY - r.top) * 1e-3, lo[1], hi[1]) };
  }
  function bindPointer() {
    if (!scene.device.hand_pointer) return;
    const canvas = $('plot-trace');
    canvas.classList.add('takes-hand');
    canvas.title = 'press and drag: the simulated hand pulls the handle to the pointer';
    let held = false;
    canvas.addEventListener('pointerdown', (event) => {
      const target = pointerTarget(event);
      if (!target) return;
      held = true;
      canvas.setPointerCapture(event.pointerId);
      sendHand(target);
    });
    canvas.addEventListener('pointermove', (event) => {
      if (!held) return;
      const target = pointerTarget(event);
      if (target) sendHand(target);
    });
    const letGo = () => { if (held) { held = false; sendHand({ release: true }); } };
    canvas.addEventListener('pointerup', letGo);
    canvas.addEventListener('pointercancel', letGo);
    canvas.addEventListener('lostpointercapture', letGo);
    window.addEventListener('blur', letGo);
  }

  loadScene().then(() => { bindPointer(); connect(); requestAnimationFrame(draw); }).catch((error) => {
    $('connection').textContent = String(error.message || error);
    $('connection').className = 'badge lost';
  });
})();
