// netmc lab console: the browser side of netmc-server --http (docs/operations/console.md).
// Reads the live feed (/live, WebSocket), the JSON routes (/api/...), and draws with Debian's
// dygraphs (global Dygraph) and, for the x-y contour, a plain canvas.
'use strict';

(function () {
  const MAX_SAMPLES = 20000;      // live samples kept per plot (the oldest dropped first)
  const TRIM_SLACK = 1000;        // trim in chunks, not on every sample
  // At most 4 redraws a second (the contract allows 10). Each redraw makes the browser paint a
  // frame, and a frame of this page costs about 4 % of a core in software rendering: at 10 a second
  // a browser beside a realtime loop on a small machine costs it deadlines.
  const REDRAW_MS = 250;
  const BACKOFF_MIN_MS = 500;
  const BACKOFF_MAX_MS = 10000;
  const TOKEN_KEY = 'netmc-console-token';
  const STATES_ACTIVE = ['queued', 'running'];
  const MICRO = '\u00b5';
  const TAU = '\u03c4';
  const PLUS_MINUS = '\u00b1';

  const $ = (id) => document.getElementById(id);
  const iterationTableBody = () => $('iterations').tBodies[0];

  // ---------------------------------------------------------------- small helpers

  // A number from protobuf's JSON mapping: 64-bit integers and NaN/Infinity come as strings,
  // fields at their default may be absent.
  function num(v, fallback) {
    if (v === undefined || v === null || v === '') return fallback === undefined ? 0 : fallback;
    const n = typeof v === 'number' ? v : Number(v);
    return Number.isNaN(n) && fallback !== undefined ? fallback : n;
  }
  function idOf(v) {
    return v === undefined || v === null ? '' : String(v);
  }
  function fixed(v, digits) {
    return Number.isFinite(v) ? v.toFixed(digits) : String(v);
  }
  function el(tag, cls, text) {
    const e = document.createElement(tag);
    if (cls) e.className = cls;
    if (text !== undefined && text !== null) e.textContent = String(text);
    return e;
  }
  function hex4(v) {
    return '0x' + (num(v) >>> 0).toString(16).padStart(4, '0');
  }
  function setText(e, text) {
    const s = String(text);
    if (e.textContent !== s) e.textContent = s;
  }
  function setAttr(e, name, value) {
    const s = String(value);
    if (e.getAttribute(name) !== s) e.setAttribute(name, s);
  }
  function trimFront(arr) {
    if (arr.length > MAX_SAMPLES + TRIM_SLACK) arr.splice(0, arr.length - MAX_SAMPLES);
  }

  // ---------------------------------------------------------------- token

  const tokenInput = $('token');
  try {
    tokenInput.value = sessionStorage.getItem(TOKEN_KEY) || '';
  } catch (e) {
    tokenInput.value = '';
  }
  function saveToken() {
    try {
      if (tokenInput.value) sessionStorage.setItem(TOKEN_KEY, tokenInput.value);
      else sessionStorage.removeItem(TOKEN_KEY);
    } catch (e) {
      // storage unavailable (private mode): the field still works for this page
    }
  }
  tokenInput.addEventListener('input', saveToken);
  tokenInput.addEventListener('change', saveToken);
  $('token-form').addEventListener('submit', (event) => {
    event.preventDefault();
    saveToken();
  });

  // ---------------------------------------------------------------- HTTP

  async function getJson(path) {
    const response = await fetch(path, { cache: 'no-store', credentials: 'same-origin' });
    let body = null;
    try {
      body = await response.json();
    } catch (e) {
      body = null;
    }
    if (!response.ok) {
      const why = body && body.error ? body.error : response.statusText;
      throw new Error('HTTP ' + response.status + ': ' + why);
    }
    return body;
  }

  // POST with the token (if any); resolves to {status, body}, never rejects on an HTTP error.
  async function postJson(path, payload) {
    const headers = { 'Content-Type': 'application/json' };
    const token = tokenInput.value.trim();
    if (token) headers.Authorization = 'Bearer ' + token;
    const response = await fetch(path, {
      method: 'POST',
      headers: headers,
      body: JSON.stringify(payload === undefined ? {} : payload),
      cache: 'no-store',
      credentials: 'same-origin',
    });
    let body = null;
    try {
      body = await response.json();
    } catch (e) {
      body = null;
    }
    return { status: response.status, body: body };
  }

  const message = $('message');
  function showMessage(text, kind, status, job) {
    setText(message, text);
    message.className = kind;
    setAttr(message, 'data-status', status === undefined ? '' : status);
    setAttr(message, 'data-job', job === undefined ? '' : job);
  }
  function refusal(status, body, what) {
    const why = body && body.error ? body.error : 'no reason given';
    if (status === 401) return what + ' refused (401 unauthorized): ' + why;
    return what + ' failed (HTTP ' + status + '): ' + why;
  }

  // ---------------------------------------------------------------- connection line

  const conn = {
    ws: null,
    connected: false,
    backoffMs: BACKOFF_MIN_MS,
    retryTimer: null,
    version: '',
    tokenRequired: null,
    everConnected: false,
  };

  function showConnection() {
    document.body.classList.toggle('disconnected', !conn.connected);
    const line = $('connection');
    const state = $('connection-state');
    setAttr(line, 'data-state', conn.connected ? 'connected' : 'disconnected');
    setText(state, conn.connected ? 'connected' : conn.everConnected ? 'disconnected (reconnecting)' : 'disconnected');
    state.className = conn.connected ? 'ok' : 'bad';
    setText($('server-version'), conn.version ? 'netmc-server ' + conn.version : '');
    let tokenText = '';
    if (conn.tokenRequired === true) tokenText = 'token required to start and cancel jobs';
    else if (conn.tokenRequired === false) tokenText = 'read-only: the server has no token (--token-file)';
    setText($('token-required'), tokenText);
    setAttr(line, 'data-token-required', conn.tokenRequired === null ? '' : conn.tokenRequired);
  }

  // ---------------------------------------------------------------- WebSocket

  function liveUrl() {
    const scheme = location.protocol === 'https:' ? 'wss:' : 'ws:';
    return scheme + '//' + location.host + '/live';
  }

  function connect() {
    conn.retryTimer = null;
    let ws;
    try {
      ws = new WebSocket(liveUrl());
    } catch (e) {
      scheduleReconnect();
      return;
    }
    conn.ws = ws;
    ws.addEventListener('open', () => {
      if (conn.ws !== ws) return;
      conn.connected = true;
      conn.everConnected = true;
      showConnection();
      if (!presetsLoaded) loadPresets();
      // Catch up on the shown job (iterations that ended while disconnected).
      if (live.job) loadJobDetails(live.job);
    });
    ws.addEventListener('message', (event) => {
      if (conn.ws !== ws || typeof event.data !== 'string') return;
      // A server that answers, not only accepts: the next loss of the feed starts the wait anew.
      conn.backoffMs = BACKOFF_MIN_MS;
      let msg;
      try {
        msg = JSON.parse(event.data);
      } catch (e) {
        return;
      }
      if (!msg || typeof msg !== 'object') return;
      // An exception here is a bug: it shows in the browser's console (the feed goes on).
      handleMessage(msg);
    });
    ws.addEventListener('close', () => {
      if (conn.ws !== ws) return;
      conn.ws = null;
      conn.connected = false;
      showConnection();
      scheduleReconnect();
    });
    // 'error' is always followed by 'close'; nothing to do here.
    ws.addEventListener('error', () => {});
  }

  function scheduleReconnect() {
    if (conn.retryTimer !== null) return;
    const jitter = Math.random() * 0.2 * conn.backoffMs;
    const wait = conn.backoffMs + jitter;
    conn.backoffMs = Math.min(BACKOFF_MAX_MS, conn.backoffMs * 2);
    conn.retryTimer = setTimeout(connect, wait);
  }

  function handleMessage(msg) {
    switch (msg.type) {
      case 'hello':
        conn.version = msg.version ? String(msg.version) : '';
        conn.tokenRequired = !!msg.token_required;
        showConnection();
        break;
      case 'state':
        // Shown with the next redraw: one painted frame for the tables and the plots.
        pendingState = msg;
        scheduleRedraw();
        break;
      case 'cycles':
        onCycles(msg);
        break;
      case 'iteration':
        onIteration(idOf(msg.job), msg.metrics);
        break;
      case 'finished':
        onFinished(idOf(msg.job), msg.finished);
        break;
      default:
        break;  // unknown types are for newer pages
    }
  }

  // ---------------------------------------------------------------- presets and the start form

  let presetsLoaded = false;
  let presetsLoading = false;
  async function loadPresets() {
    if (presetsLoading) return;
    presetsLoading = true;
    try {
      const body = await getJson('/api/presets');
      const select = $('preset');
      const previous = select.value;
      select.textContent = '';
      const presets = body && Array.isArray(body.presets) ? body.presets : [];
      for (const name of presets) {
        const option = el('option', null, name);
        option.value = String(name);
        select.appendChild(option);
      }
      if (previous && presets.includes(previous)) select.value = previous;
      presetsLoaded = presets.length > 0;
    } catch (e) {
      presetsLoaded = false;  // retried when the live feed (re)connects
    } finally {
      presetsLoading = false;
    }
  }

  $('start-form').addEventListener('submit', async (event) => {
    event.preventDefault();
    const preset = $('preset').value;
    if (!preset) {
      showMessage('no preset to start (the preset list is not loaded yet)', 'error', '');
      return;
    }
    const payload = { preset: preset };
    const controller = $('controller').value.trim();
    if (controller) payload.controller = controller;
    const iterationsText = document.getElementById('iteration-count').value.trim();
    if (iterationsText) {
      const iterations = Number(iterationsText);
      if (!Number.isInteger(iterations) || iterations < 1) {
        showMessage('iterations: a whole number of at least 1', 'error', '');
        return;
      }
      payload.iterations = iterations;
    }
    const clock = $('clock').value;
    if (clock) payload.clock = clock;

    const button = $('start');
    button.disabled = true;
    showMessage('starting a job from ' + preset + ' ...', 'muted', 'pending');
    try {
      const { status, body } = await postJson('/api/jobs', payload);
      if (status === 202 && body && body.job !== undefined) {
        const id = idOf(body.job);
        showMessage('job ' + id + ' started', 'ok', status, id);
      } else {
        showMessage(refusal(status, body, 'start'), 'error', status);
      }
    } catch (e) {
      showMessage('start failed: ' + e.message, 'error', 'network');
    } finally {
      button.disabled = false;
    }
  });

  async function cancelJob(id) {
    showMessage('cancelling job ' + id + ' ...', 'muted', 'pending', id);
    try {
      const { status, body } = await postJson('/api/jobs/' + encodeURIComponent(id) + '/cancel', {});
      if (status === 200) {
        cancelRequested.add(id);
        const j = jobStatus.get(id);
        const queued = j && j.state === 'queued';
        // The server ends a cancelled queued job when its turn comes: until then it is listed queued.
        showMessage('job ' + id + ' cancelled' + (queued ? ' (it leaves the queue when its turn comes)' : ''),
          'ok', status, id);
      } else {
        showMessage(refusal(status, body, 'cancel of job ' + id), 'error', status, id);
      }
    } catch (e) {
      showMessage('cancel of job ' + id + ' failed: ' + e.message, 'error', 'network', id);
    }
  }

  // ---------------------------------------------------------------- nodes table

  const nodeRows = new Map();  // node name -> <tr>

  function nodeRow(name) {
    let tr = nodeRows.get(name);
    if (tr) return tr;
    tr = el('tr', 'node');
    tr.setAttribute('data-node', name);
    for (const cls of ['name', 'axes', 'plant', 'health', 'last-seen', 'clock', 'offset', 'drives', 'server']) {
      tr.appendChild(el('td', cls));
    }
    nodeRows.set(name, tr);
    return tr;
  }

  function driveList(drives) {
    const ul = el('ul', 'drives');
    for (const d of drives) {
      const li = el('li', d.fault_latched ? 'drive fault' : 'drive');
      li.setAttribute('data-axis', idOf(d.axis));
      li.appendChild(el('span', 'axis', d.axis));
      li.appendChild(el('span', 'drive-name', d.drive));
      li.appendChild(el('span', 'cia402', d.state));
      li.appendChild(el('span', 'words', 'status ' + hex4(d.statusword) + ', error ' + hex4(d.error_code)));
      if (d.fault_latched) li.appendChild(el('span', 'fault-text', 'FAULT: ' + (d.last_fault || 'latched')));
      else if (d.last_fault) li.appendChild(el('span', 'last-fault', 'last fault: ' + d.last_fault));
      if (d.limits) li.appendChild(el('span', 'limits', 'limits ' + d.limits));
      ul.appendChild(li);
    }
    return ul;
  }

  function updateNodes(nodes) {
    const tbody = $('nodes').tBodies[0];
    const seen = new Set();
    const sorted = nodes.slice().sort((a, b) => idOf(a.node).localeCompare(idOf(b.node)));
    let previous = null;
    for (const n of sorted) {
      const name = idOf(n.node);
      if (!name || seen.has(name)) continue;
      seen.add(name);
      const tr = nodeRow(name);
      const c = tr.cells;
      setText(c[0], name);
      setText(c[1], (n.axes || []).join(', '));
      setText(c[2], n.plant || '');
      const health = n.health || '';
      setText(c[3], health);
      c[3].className = 'health ' + (/^(ok|healthy)\b/i.test(health) ? 'ok' : 'warn');
      setText(c[4], fixed(num(n.last_seen_s), 1) + ' s ago');
      setText(c[5], (n.clock || '') + (n.time_base ? ' (' + n.time_base + ')' : ''));
      if (n.clock_measured) {
        setText(c[6], (num(n.clock_offset_s) * 1e3).toFixed(3) + ' ' + PLUS_MINUS + ' ' +
          (num(n.round_trip_s) * 1e3 / 2).toFixed(3) + ' ms');
      } else {
        setText(c[6], 'not measured');
      }
      const drivesKey = JSON.stringify(n.drives || []);
      if (c[7].getAttribute('data-key') !== drivesKey) {
        c[7].textContent = '';
        c[7].appendChild(driveList(n.drives || []));
        c[7].setAttribute('data-key', drivesKey);
      }
      let server = n.server_name ? 'obeys ' + n.server_name : 'any';
      if (n.held_by) server += '; held by ' + n.held_by;
      setText(c[8], server);
      const anchor = previous ? previous.nextSibling : tbody.firstChild;
      if (tr !== anchor) tbody.insertBefore(tr, anchor);
      previous = tr;
    }
    for (const [name, tr] of nodeRows) {
      if (!seen.has(name)) {
        tr.remove();
        nodeRows.delete(name);
      }
    }
    $('nodes-empty').hidden = seen.size > 0;
  }

  // ---------------------------------------------------------------- axes (commissioning)

  const axisRows = new Map();  // "node/axis" -> <tr>; made once, so a held jog button stays put

  async function commandAxis(node, axis, kind, extra) {
    const payload = Object.assign({ node: node, axis: axis, kind: kind }, extra || {});
    try {
      const { status, body } = await postJson('/api/axis-command', payload);
      if (status === 200) {
        if (kind !== 'jog') showMessage(kind + ' of ' + node + ' ' + axis + ' sent', 'ok', status);
      } else {
        showMessage(refusal(status, body, kind + ' of ' + node + ' ' + axis), 'error', status);
      }
      return status;
    } catch (e) {
      showMessage(kind + ' of ' + node + ' ' + axis + ' failed: ' + e.message, 'error', 'network');
      return 0;
    }
  }

  function axisButton(label, action, onClick) {
    const b = el('button', 'axis-' + action, label);
    b.type = 'button';
    b.setAttribute('data-action', action);
    if (onClick) b.addEventListener('click', onClick);
    return b;
  }

  // Held down: a jog command every 100 ms (the node stops a jog 0.5 s after the last), released: stop.
  function jogButton(node, axis, sign, speedInput) {
    const b = axisButton(sign > 0 ? 'jog +' : 'jog \u2212', sign > 0 ? 'jog-plus' : 'jog-minus');
    let timer = null;
    const speed = () => sign * Math.abs(num(parseFloat(speedInput.value), 5)) / 1e3;
    const start = (event) => {
      event.preventDefault();
      if (timer !== null) return;
      commandAxis(node, axis, 'jog', { speed_m_s: speed() }).then((status) => {
        if (status !== 200) stop();
      });
      timer = setInterval(() => commandAxis(node, axis, 'jog', { speed_m_s: speed() }), 100);
    };
    const stop = () => {
      if (timer === null) return;
      clearInterval(timer);
      timer = null;
      commandAxis(node, axis, 'jog', { speed_m_s: 0 });
    };
    b.addEventListener('pointerdown', start);
    for (const type of ['pointerup', 'pointerleave', 'pointercancel']) b.addEventListener(type, stop);
    return b;
  }

  function axisRow(node, axis) {
    const key = node + '/' + axis;
    let tr = axisRows.get(key);
    if (tr) return tr;
    tr = el('tr', 'axis');
    tr.setAttribute('data-node', node);
    tr.setAttribute('data-axis', axis);
    for (const cls of ['node', 'axis', 'state', 'motion', 'position', 'velocity', 'following-error', 'controls']) {
      tr.appendChild(el('td', cls));
    }
    const controls = tr.cells[7];
    controls.appendChild(axisButton('enable', 'enable', () => commandAxis(node, axis, 'enable')));
    controls.appendChild(axisButton('disable', 'disable', () => commandAxis(node, axis, 'disable')));
    controls.appendChild(axisButton('quick stop', 'quick-stop', () => commandAxis(node, axis, 'quick-stop')));
    const target = el('input', 'move-target');
    target.type = 'number';
    target.step = 'any';
    target.title = 'target position [mm]';
    target.setAttribute('aria-label', 'target position of ' + axis + ' [mm]');
    controls.appendChild(target);
    controls.appendChild(axisButton('move to', 'move', () => {
      const mm = parseFloat(target.value);
      if (!Number.isFinite(mm)) {
        showMessage('move of ' + node + ' ' + axis + ': give the target in mm', 'error', 'input');
        return;
      }
      commandAxis(node, axis, 'move', { target_m: mm / 1e3 });
    }));
    const jogSpeed = el('input', 'jog-speed');
    jogSpeed.type = 'number';
    jogSpeed.min = '0';
    jogSpeed.step = 'any';
    jogSpeed.value = '5';
    jogSpeed.title = 'jog speed [mm/s]';
    jogSpeed.setAttribute('aria-label', 'jog speed of ' + axis + ' [mm/s]');
    controls.appendChild(jogButton(node, axis, -1, jogSpeed));
    controls.appendChild(jogButton(node, axis, +1, jogSpeed));
    controls.appendChild(jogSpeed);
    controls.appendChild(el('span', 'command-note'));
    axisRows.set(key, tr);
    return tr;
  }

  function updateAxes(nodes) {
    const tbody = $('axes').tBodies[0];
    const seen = new Set();
    let previous = null;
    const sorted = nodes.slice().sort((a, b) => idOf(a.node).localeCompare(idOf(b.node)));
    for (const n of sorted) {
      const node = idOf(n.node);
      for (const d of n.drives || []) {
        const axis = idOf(d.axis);
        const key = node + '/' + axis;
        if (!node || !axis || seen.has(key)) continue;
        seen.add(key);
        const tr = axisRow(node, axis);
        const c = tr.cells;
        setText(c[0], node);
        setText(c[1], axis);
        setText(c[2], d.state || '');
        setText(c[3], d.motion || 'off');
        setText(c[4], fixed(num(d.position_m) * 1e3, 3));
        setText(c[5], fixed(num(d.velocity_m_s) * 1e3, 3));
        setText(c[6], fixed(num(d.following_error_m) * 1e6, 1));
        const note = d.command_note ? (d.command_refused ? 'refused: ' : '') + d.command_note : '';
        setText(c[7].lastChild, note);
        setAttr(tr, 'data-motion', d.motion || 'off');
        const anchor = previous ? previous.nextSibling : tbody.firstChild;
        if (tr !== anchor) tbody.insertBefore(tr, anchor);
        previous = tr;
      }
    }
    for (const [key, tr] of axisRows) {
      if (!seen.has(key)) {
        tr.remove();
        axisRows.delete(key);
      }
    }
    $('axes-empty').hidden = seen.size > 0;
  }

  // ---------------------------------------------------------------- jobs table

  const jobRows = new Map();   // job id -> <tr>
  const jobStatus = new Map(); // job id -> JobStatus
  const cancelRequested = new Set();  // ids whose cancel the server accepted (they may still run or wait)

  function compareIds(a, b) {
    const na = Number(a);
    const nb = Number(b);
    if (Number.isFinite(na) && Number.isFinite(nb) && na !== nb) return na - nb;
    return a < b ? -1 : a > b ? 1 : 0;
  }

  function jobRow(id) {
    let tr = jobRows.get(id);
    if (tr) return tr;
    tr = el('tr', 'job');
    tr.setAttribute('data-job', id);
    for (const cls of ['id', 'label', 'state', 'progress', 'detail', 'actions']) tr.appendChild(el('td', cls));
    tr.addEventListener('click', () => selectJob(id, true));
    jobRows.set(id, tr);
    return tr;
  }

  function cancelButton(id) {
    const button = el('button', 'cancel', 'cancel');
    button.type = 'button';
    button.addEventListener('click', (event) => {
      event.stopPropagation();  // not a click on the row (which selects the job)
      cancelJob(id);
    });
    return button;
  }

  function updateJobs(jobs) {
    const tbody = $('jobs').tBodies[0];
    const seen = new Set();
    for (const j of jobs) {
      const id = idOf(j.job_id);
      if (id) {
        jobStatus.set(id, j);
        seen.add(id);
      }
    }
    for (const id of Array.from(jobStatus.keys())) if (!seen.has(id)) jobStatus.delete(id);
    for (const id of Array.from(cancelRequested)) if (!seen.has(id)) cancelRequested.delete(id);
    const ids = Array.from(seen).sort(compareIds).reverse();  // newest first
    let previous = null;
    for (const id of ids) {
      const j = jobStatus.get(id);
      const tr = jobRow(id);
      const state = j.state || '';
      setAttr(tr, 'data-state', state);
      const c = tr.cells;
      setText(c[0], id);
      setText(c[1], j.label || '');
      setText(c[2], state);
      c[2].className = 'state ' + state;
      setText(c[3], num(j.iterations_done) + ' / ' + num(j.iterations_total));
      const active = STATES_ACTIVE.includes(state);
      let detail = state === 'queued' && j.waiting_for ? 'waits for ' + j.waiting_for : (j.error || '');
      if (active && cancelRequested.has(id)) detail = 'cancel requested' + (detail ? '; ' + detail : '');
      setText(c[4], detail);
      tr.classList.toggle('cancelling', active && cancelRequested.has(id));
      // A cancel button while the job is queued or running, none after.
      const button = c[5].querySelector('button.cancel');
      if (active && !button) c[5].appendChild(cancelButton(id));
      else if (!active && button) button.remove();
      tr.classList.toggle('selected', id === live.job);
      const anchor = previous ? previous.nextSibling : tbody.firstChild;
      if (tr !== anchor) tbody.insertBefore(tr, anchor);
      previous = tr;
    }
    for (const [id, tr] of jobRows) {
      if (!seen.has(id)) {
        tr.remove();
        jobRows.delete(id);
      }
    }
    $('jobs-empty').hidden = seen.size > 0;
    autoSelect();
    if (live.job) {
      const j = jobStatus.get(live.job);
      if (j) {
        showLiveHeader();
        // Iterations the feed let go (slow reader, reconnect): fetch them.
        // Once per count the server reports (a history without them would ask forever).
        const done = num(j.iterations_done);
        if (done > live.iterations.size && done !== live.catchUpDone) {
          live.catchUpDone = done;
          loadJobDetails(live.job);
        }
      }
    }
  }

  // ---------------------------------------------------------------- selection of the live job

  const live = {
    job: null,            // id shown in the live section
    userSelected: false,  // picked by a click (else: the newest running job)
    iterations: new Map(),  // iteration number -> IterationMetrics
    finished: null,
    samples: [],          // the contour's points: {x, it, rx, ry, px, py, e}
    errorRows: [],        // [x, e in um]
    commandRows: [],      // [x, u0, u1, ...]
    commandWidth: 0,
    taus: [],             // seconds, lost ones excluded
    lastRawT: null,
    lastX: null,
    lastDx: 0,
    tOffset: 0,
    currentIteration: null,
    peak: null,           // the sample of the current iteration with the largest |e|
    dropped: 0,
    detailsInFlight: false,
    detailsAgain: false,
    catchUpDone: null,
    version: 0,           // counts changes of the live samples (the time plots redraw on a change)
    iterationsVersion: 0, // counts changes of the iteration table (the learning curve)
  };

  function resetLive() {
    live.iterations = new Map();
    live.finished = null;
    live.samples = [];
    live.errorRows = [];
    live.commandRows = [];
    live.commandWidth = 0;
    live.taus = [];
    live.lastRawT = null;
    live.lastX = null;
    live.lastDx = 0;
    live.tOffset = 0;
    live.currentIteration = null;
    live.peak = null;
    live.dropped = 0;
    live.catchUpDone = null;
    plots.error.clear();
    plots.command.clear();
    plots.tau.clear();
    plots.learning.clear();
    iterationTableBody().textContent = '';
    $('estimates').tBodies[0].textContent = '';
    setText($('estimates-info'), '');
    setText($('tau-info'), '');
    setText($('contour-info'), '');
    setText($('live-info'), '');
    scheduleRedraw();
  }

  function selectJob(id, byUser) {
    if (byUser) live.userSelected = true;
    if (id === live.job) return;
    live.job = id;
    resetLive();
    for (const [jid, tr] of jobRows) tr.classList.toggle('selected', jid === id);
    showLiveHeader();
    if (id) loadJobDetails(id);
  }

  function autoSelect() {
    if (live.userSelected) return;
    let newest = null;
    for (const [id, j] of jobStatus) {
      if (j.state === 'running' && (newest === null || compareIds(id, newest) > 0)) newest = id;
    }
    // With no job running, keep showing the last one (its results stay readable).
    if (newest !== null && newest !== live.job) selectJob(newest, false);
  }

  $('auto-select').addEventListener('click', () => {
    live.userSelected = false;
    autoSelect();
    showLiveHeader();
  });

  function showLiveHeader() {
    const header = $('live-job');
    if (!live.job) {
      setText(header, 'no job selected');
      setAttr(header, 'data-job', '');
      setAttr(header, 'data-state', '');
      return;
    }
    const j = jobStatus.get(live.job);
    let text = 'job ' + live.job;
    if (j) {
      if (j.label) text += ' (' + j.label + ')';
      text += ', ' + (j.state || '?') + ', ' + num(j.iterations_done) + ' / ' + num(j.iterations_total) + ' iterations';
      if (j.error) text += ': ' + j.error;
    }
    // Followed automatically: the newest running job, which stays shown once it has ended.
    text += live.userSelected ? ' [selected]' : j && j.state === 'running' ? ' [newest running]' : ' [last run]';
    setText(header, text);
    setAttr(header, 'data-job', live.job);
    setAttr(header, 'data-state', j ? j.state || '' : '');
  }

  // GET /api/jobs/ID: the iterations so far (a job already running when the page opened, or
  // iterations the feed let go). One request at a time; a call meanwhile asks once more after it.
  async function loadJobDetails(id) {
    if (live.detailsInFlight) {
      live.detailsAgain = true;
      return;
    }
    live.detailsInFlight = true;
    try {
      const body = await getJson('/api/jobs/' + encodeURIComponent(id));
      if (live.job !== id || !body) return;
      if (body.status) {
        jobStatus.set(id, body.status);
        showLiveHeader();
      }
      for (const m of body.iterations || []) addIteration(m);
      if (body.finished) {
        live.finished = body.finished;
        const result = body.finished.result;
        if (result && Array.isArray(result.iterations)) for (const m of result.iterations) addIteration(m);
      }
      showIterations();
    } catch (e) {
      // The job may have left the history, or the server is away: the live feed goes on.
    } finally {
      live.detailsInFlight = false;
      if (live.detailsAgain) {
        live.detailsAgain = false;
        if (live.job) loadJobDetails(live.job);
      }
    }
  }

  // ---------------------------------------------------------------- live messages

  function onCycles(msg) {
    const id = idOf(msg.job);
    if (!id || id !== live.job) return;
    const iteration = num(msg.iteration);
    live.dropped += num(msg.dropped);
    const samples = Array.isArray(msg.samples) ? msg.samples : [];
    if (live.currentIteration === null || iteration > live.currentIteration) {
      if (live.currentIteration !== null) {
        // A new iteration: the time plots start again at its t = 0 (time within the iteration,
        // as the feed gives it), so the contour, its peak and the plots are of one iteration.
        live.samples = [];
        live.errorRows = [];
        live.commandRows = [];
        live.lastRawT = null;
        live.lastX = null;
        live.lastDx = 0;
        live.tOffset = 0;
      }
      live.currentIteration = iteration;
      live.peak = null;
    }
    for (const s of samples) {
      const t = num(s.t, NaN);
      if (!Number.isFinite(t)) continue;
      // Time on the plots: the feed's t, shifted where it starts again (a new iteration) so the
      // x axis stays ordered.
      let x = t + live.tOffset;
      if (live.lastX !== null && x <= live.lastX) {
        const dx = live.lastDx > 0 ? live.lastDx : 1e-3;
        live.tOffset = live.lastX + dx - t;
        x = t + live.tOffset;
      } else if (live.lastX !== null) {
        live.lastDx = x - live.lastX;
      }
      live.lastX = x;
      live.lastRawT = t;
      const ref = Array.isArray(s.ref) ? s.ref : [];
      const pos = Array.isArray(s.pos) ? s.pos : [];
      const u = Array.isArray(s.u) ? s.u.map((v) => num(v, NaN)) : [];
      const e = num(s.e, NaN);
      const tau = num(s.tau, -1);
      const sample = {
        x: x,
        it: iteration,
        rx: num(ref[0], NaN),
        ry: num(ref[1], NaN),
        px: num(pos[0], NaN),
        py: num(pos[1], NaN),
        e: e,
      };
      live.samples.push(sample);
      if (Number.isFinite(e)) {
        live.errorRows.push([x, e * 1e6]);
        if (iteration === live.currentIteration &&
            (live.peak === null || Math.abs(e) > Math.abs(live.peak.e)) &&
            Number.isFinite(sample.px) && Number.isFinite(sample.py)) {
          live.peak = sample;
        }
      }
      if (u.length > 0) {
        if (live.commandWidth === 0) live.commandWidth = Math.min(u.length, 8);
        const row = [x];
        for (let i = 0; i < live.commandWidth; ++i) row.push(i < u.length && Number.isFinite(u[i]) ? u[i] : null);
        live.commandRows.push(row);
      }
      if (tau >= 0 && Number.isFinite(tau)) live.taus.push(tau);
    }
    trimFront(live.samples);
    trimFront(live.errorRows);
    trimFront(live.commandRows);
    trimFront(live.taus);
    live.version += 1;
    scheduleRedraw();
  }

  function gapRow(x, width) {
    const row = [x];
    for (let i = 0; i < width; ++i) row.push(null);
    return row;
  }

  function onIteration(id, metrics) {
    if (!id || id !== live.job || !metrics) return;
    addIteration(metrics);
    showIterations();
  }

  function onFinished(id, finished) {
    if (!id || id !== live.job) return;
    live.finished = finished || null;
    if (finished && finished.result && Array.isArray(finished.result.iterations)) {
      for (const m of finished.result.iterations) addIteration(m);
    }
    showIterations();
    // The authoritative list, should the feed have let an iteration go.
    loadJobDetails(id);
  }

  function addIteration(m) {
    if (!m) return;
    const n = num(m.iteration, NaN);
    if (!Number.isFinite(n)) return;
    live.iterations.set(n, m);
    live.iterationsVersion += 1;
  }

  // ---------------------------------------------------------------- iteration table, estimates

  const ITERATION_COLUMNS = [
    // class (the metric's field), its shown value
    ['e_max_m', (v) => fixed(v * 1e6, 3)],
    ['e_rms_m', (v) => fixed(v * 1e6, 3)],
    ['e_sum_m', (v) => fixed(v * 1e3, 4)],
    ['tau_mean_s', (v) => fixed(v * 1e3, 3)],
    ['tau_p99_s', (v) => fixed(v * 1e3, 3)],
    ['tau_max_s', (v) => fixed(v * 1e3, 3)],
    ['deadline_misses', (v) => String(v)],
    ['lost_feedback', (v) => String(v)],
    ['lost_setpoints', (v) => String(v)],
  ];

  // The raw JSON value for data-value: numbers as JavaScript prints them (the same double),
  // strings (NaN, Infinity) as sent, absent fields as 0 (protobuf's default).
  function rawValue(v) {
    if (v === undefined || v === null) return '0';
    return String(v);
  }

  function showIterations() {
    const tbody = iterationTableBody();
    const numbers = Array.from(live.iterations.keys()).sort((a, b) => a - b);
    const existing = new Map();
    for (const tr of Array.from(tbody.rows)) existing.set(Number(tr.getAttribute('data-iteration')), tr);
    let previous = null;
    for (const n of numbers) {
      const m = live.iterations.get(n);
      let tr = existing.get(n);
      if (!tr) {
        tr = el('tr', 'iteration');
        tr.setAttribute('data-iteration', String(n));
        tr.appendChild(el('td', 'iteration-number', n));
        for (const [cls] of ITERATION_COLUMNS) tr.appendChild(el('td', cls + ' num'));
        tr.appendChild(el('td', 'note'));
      }
      existing.delete(n);
      ITERATION_COLUMNS.forEach(([cls, show], i) => {
        const cell = tr.cells[i + 1];
        setAttr(cell, 'data-value', rawValue(m[cls]));
        setText(cell, show(num(m[cls])));
      });
      const notes = [];
      if (m.diverged) notes.push('diverged at ' + fixed(num(m.diverged_at_s), 3) + ' s');
      if (m.did_not_follow) notes.push('did not follow the reference');
      if (num(m.late_feedback) > 0) notes.push(num(m.late_feedback) + ' late feedback');
      setText(tr.cells[ITERATION_COLUMNS.length + 1], notes.join('; '));
      const anchor = previous ? previous.nextSibling : tbody.firstChild;
      if (tr !== anchor) tbody.insertBefore(tr, anchor);
      previous = tr;
    }
    for (const tr of existing.values()) tr.remove();
    showEstimates(numbers);
    scheduleRedraw();
  }

  function showEstimates(numbers) {
    const tbody = $('estimates').tBodies[0];
    let latest = null;
    let latestIteration = null;
    for (let i = numbers.length - 1; i >= 0; --i) {
      const m = live.iterations.get(numbers[i]);
      if (Array.isArray(m.estimates) && m.estimates.length > 0) {
        latest = m.estimates;
        latestIteration = numbers[i];
        break;
      }
    }
    tbody.textContent = '';
    if (!latest) {
      setText($('estimates-info'), numbers.length ? 'the controller reports no estimates' : 'no iteration ended yet');
      return;
    }
    setText($('estimates-info'), 'after iteration ' + latestIteration);
    for (const est of latest) {
      const tr = el('tr', 'estimate');
      tr.setAttribute('data-name', idOf(est.name));
      tr.appendChild(el('td', 'name', est.name));
      const value = el('td', 'value num', Number(num(est.value)).toPrecision(6));
      value.setAttribute('data-value', rawValue(est.value));
      tr.appendChild(value);
      tr.appendChild(el('td', 'unit', est.unit || ''));
      tbody.appendChild(tr);
    }
  }

  // ---------------------------------------------------------------- dygraphs

  // Dygraphs' legend plugin sets inline style attributes, which the server's
  // Content-Security-Policy (style from 'self' only) refuses with a console error on every draw:
  // the page leaves that plugin out and shows its own readout under each plot.
  if (typeof Dygraph !== 'undefined' && Array.isArray(Dygraph.PLUGINS) && Dygraph.Plugins && Dygraph.Plugins.Legend) {
    Dygraph.PLUGINS = Dygraph.PLUGINS.filter((plugin) => plugin !== Dygraph.Plugins.Legend);
  }

  class Plot {
    constructor(id, readoutId, options, placeholder) {
      this.div = $(id);
      this.readout = readoutId ? $(readoutId) : null;
      this.options = options;
      this.placeholder = placeholder;
      this.graph = null;
      this.labelsKey = '';
      this.div.textContent = placeholder;
      this.div.classList.add('empty');
    }
    clear() {
      if (this.graph) {
        this.graph.destroy();
        this.graph = null;
      }
      this.div.textContent = this.placeholder;
      this.div.classList.add('empty');
      this.version = undefined;
      if (this.readout) setText(this.readout, '');
    }
    // Draws when `version` differs from the last draw's (or the plot was cleared): makeRows()
    // gives the rows in dygraphs' native array format (sorted by x); extra: options for this draw.
    update(version, makeRows, labels, extra) {
      if (this.graph && version === this.version) return;
      this.version = version;
      this.draw(makeRows(), labels, extra);
    }
    draw(rows, labels, extra) {
      // One row gives dygraphs an empty x range: wait for a second one.
      if (rows.length < 2 && !(extra && extra.dateWindow)) rows = [];
      if (!rows.length || typeof Dygraph === 'undefined') {
        if (this.graph) this.clear();
        return;
      }
      const key = labels.join('\u0001');
      if (this.graph && key !== this.labelsKey) this.clear();
      if (!this.graph) {
        this.div.textContent = '';
        this.div.classList.remove('empty');
        const options = Object.assign({}, this.options, extra || {}, { labels: labels });
        if (this.readout) {
          const readout = this.readout;
          const format = this.options.readoutFormat;
          delete options.readoutFormat;
          options.highlightCallback = (event, x, points) => setText(readout, format(x, points));
          options.unhighlightCallback = () => setText(readout, '');
        } else {
          delete options.readoutFormat;
        }
        this.graph = new Dygraph(this.div, rows, options);
        this.labelsKey = key;
      } else {
        this.graph.updateOptions(Object.assign({ file: rows }, extra || {}));
      }
    }
  }

  function pointsText(points, digits) {
    return points
      .filter((p) => p.yval !== null && p.yval !== undefined && !Number.isNaN(p.yval))
      .map((p) => p.name + ' = ' + Number(p.yval).toPrecision(digits || 4))
      .join(', ');
  }

  const common = {
    legend: 'never',
    animatedZooms: false,
    connectSeparatedPoints: false,
    axisLabelFontSize: 11,
    strokeWidth: 1,
  };

  const plots = {
    error: new Plot('error-plot', 'error-readout', Object.assign({}, common, {
      xlabel: 't [s]',
      ylabel: 'e [' + MICRO + 'm]',
      colors: ['#c0392b'],
      readoutFormat: (x, points) => 't = ' + x.toFixed(3) + ' s: ' + pointsText(points),
    }), 'no live data'),
    command: new Plot('command-plot', 'command-readout', Object.assign({}, common, {
      xlabel: 't [s]',
      ylabel: 'u',
      colors: ['#1f77b4', '#ff7f0e', '#2ca02c', '#9467bd', '#8c564b', '#e377c2', '#7f7f7f', '#bcbd22'],
      readoutFormat: (x, points) => 't = ' + x.toFixed(3) + ' s: ' + pointsText(points),
    }), 'no live data'),
    tau: new Plot('tau-plot', 'tau-readout', Object.assign({}, common, {
      xlabel: TAU + ' [ms]',
      ylabel: 'cycles',
      colors: ['#2c7fb8'],
      stepPlot: true,
      fillGraph: true,
      includeZero: true,
      readoutFormat: (x, points) => TAU + ' from ' + x.toFixed(3) + ' ms: ' +
        (points.length && points[0].yval !== null ? points[0].yval : 0) + ' cycles',
    }), 'no live data'),
    learning: new Plot('learning-plot', 'learning-readout', Object.assign({}, common, {
      xlabel: 'iteration',
      ylabel: 'e_max [' + MICRO + 'm]',
      y2label: 'e_sum [mm]',
      colors: ['#c0392b', '#2c7fb8'],
      drawPoints: true,
      pointSize: 3,
      strokeWidth: 1.5,
      includeZero: true,
      series: { 'e_sum [mm]': { axis: 'y2' } },
      axes: {
        x: { axisLabelFormatter: (v) => (Number.isInteger(v) ? String(v) : '') },
        y2: { independentTicks: true },
      },
      readoutFormat: (x, points) => 'iteration ' + x + ': ' + pointsText(points, 5),
    }), 'no iteration ended yet'),
  };

  const AXIS_NAMES = ['x', 'y', 'z'];
  function commandLabels(width) {
    const labels = ['t'];
    const status = jobStatus.get(live.job);
    const unit = status && status.command_unit ? ' [' + status.command_unit + ']' : '';
    for (let i = 0; i < width; ++i) labels.push('u ' + (i < AXIS_NAMES.length ? AXIS_NAMES[i] : String(i)) + unit);
    return labels;
  }

  function tauHistogram() {
    const taus = live.taus;
    if (taus.length === 0) return [];
    let max = 0;
    for (const t of taus) if (t > max) max = t;
    const bins = 40;
    const maxMs = max > 0 ? max * 1e3 : 1e-3;
    const width = maxMs / bins;
    const counts = new Array(bins).fill(0);
    for (const t of taus) {
      const b = Math.min(bins - 1, Math.floor((t * 1e3) / width));
      counts[b] += 1;
    }
    const rows = [];
    for (let i = 0; i < bins; ++i) rows.push([i * width, counts[i]]);
    rows.push([bins * width, counts[bins - 1]]);  // closes the last step
    return rows;
  }

  function tauInfo() {
    const numbers = Array.from(live.iterations.keys()).sort((a, b) => a - b);
    let total = 0;
    for (const n of numbers) total += num(live.iterations.get(n).deadline_misses);
    const parts = [];
    parts.push(live.taus.length + ' cycles in the histogram');
    if (numbers.length) {
      const last = live.iterations.get(numbers[numbers.length - 1]);
      parts.push('deadline misses: ' + num(last.deadline_misses) + ' in iteration ' + numbers[numbers.length - 1] +
        ', ' + total + ' in all ' + numbers.length + ' ended');
      parts.push(TAU + ' p99 ' + fixed(num(last.tau_p99_s) * 1e3, 3) + ' ms, max ' +
        fixed(num(last.tau_max_s) * 1e3, 3) + ' ms');
    } else {
      parts.push('deadline misses: no iteration ended yet');
    }
    return parts.join('; ');
  }

  function learningRows() {
    const numbers = Array.from(live.iterations.keys()).sort((a, b) => a - b);
    return numbers.map((n) => {
      const m = live.iterations.get(n);
      return [n, num(m.e_max_m) * 1e6, num(m.e_sum_m) * 1e3];
    });
  }

  // ---------------------------------------------------------------- contour canvas

  const contourBox = $('contour');
  const canvas = $('contour-canvas');
  const followPeak = $('follow-peak');
  followPeak.addEventListener('change', scheduleRedraw);

  function niceStep(span, target) {
    const raw = span / Math.max(1, target);
    const p = Math.pow(10, Math.floor(Math.log10(raw)));
    const f = raw / p;
    return (f < 1.5 ? 1 : f < 3.5 ? 2 : f < 7.5 ? 5 : 10) * p;
  }

  function lengthText(m) {
    const a = Math.abs(m);
    if (a === 0) return '0';
    if (a < 1e-3) return (m * 1e6).toPrecision(3) + ' ' + MICRO + 'm';
    return (m * 1e3).toPrecision(4) + ' mm';
  }

  function drawContour() {
    const samples = live.samples;
    setAttr(contourBox, 'data-points', samples.length);
    const dpr = window.devicePixelRatio || 1;
    const cssW = Math.max(50, canvas.clientWidth);
    const cssH = Math.max(50, canvas.clientHeight);
    if (canvas.width !== Math.round(cssW * dpr) || canvas.height !== Math.round(cssH * dpr)) {
      canvas.width = Math.round(cssW * dpr);
      canvas.height = Math.round(cssH * dpr);
    }
    const ctx = canvas.getContext('2d');
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    ctx.clearRect(0, 0, cssW, cssH);
    ctx.font = '11px sans-serif';
    if (samples.length === 0) {
      ctx.fillStyle = '#888';
      ctx.fillText('no live data', 10, 20);
      setText($('contour-info'), '');
      return;
    }

    // The window: everything, or around the current iteration's error peak.
    let minX = Infinity, maxX = -Infinity, minY = Infinity, maxY = -Infinity;
    const peak = live.peak;
    let zoomed = false;
    if (followPeak.checked && peak) {
      const half = Math.max(8 * Math.abs(peak.e), 20e-6);
      const cx = Number.isFinite(peak.rx) ? (peak.px + peak.rx) / 2 : peak.px;
      const cy = Number.isFinite(peak.ry) ? (peak.py + peak.ry) / 2 : peak.py;
      minX = cx - half; maxX = cx + half; minY = cy - half; maxY = cy + half;
      zoomed = true;
    } else {
      const extend = (x, y) => {
        if (!Number.isFinite(x) || !Number.isFinite(y)) return;
        if (x < minX) minX = x;
        if (x > maxX) maxX = x;
        if (y < minY) minY = y;
        if (y > maxY) maxY = y;
      };
      for (const s of samples) {
        extend(s.rx, s.ry);
        extend(s.px, s.py);
      }
      if (!Number.isFinite(minX)) return;
      const pad = Math.max(maxX - minX, maxY - minY, 1e-6) * 0.05;
      minX -= pad; maxX += pad; minY -= pad; maxY += pad;
    }

    // Equal scales on x and y: a circle stays round.
    const margin = { left: 58, right: 10, top: 10, bottom: 30 };
    const plotW = cssW - margin.left - margin.right;
    const plotH = cssH - margin.top - margin.bottom;
    const scale = Math.min(plotW / Math.max(maxX - minX, 1e-12), plotH / Math.max(maxY - minY, 1e-12));
    const midX = (minX + maxX) / 2;
    const midY = (minY + maxY) / 2;
    const X = (x) => margin.left + plotW / 2 + (x - midX) * scale;
    const Y = (y) => margin.top + plotH / 2 - (y - midY) * scale;
    const viewMinX = midX - plotW / 2 / scale, viewMaxX = midX + plotW / 2 / scale;
    const viewMinY = midY - plotH / 2 / scale, viewMaxY = midY + plotH / 2 / scale;

    // Grid and ticks (mm, or um when zoomed in).
    const step = niceStep(Math.min(viewMaxX - viewMinX, viewMaxY - viewMinY), 6);
    const inMicro = step < 1e-4;
    const unitScale = inMicro ? 1e6 : 1e3;
    const decimals = Math.max(0, -Math.floor(Math.log10(step * unitScale) + 1e-9));
    ctx.strokeStyle = '#e4e4e4';
    ctx.lineWidth = 1;
    ctx.fillStyle = '#555';
    ctx.beginPath();
    for (let gx = Math.ceil(viewMinX / step) * step; gx <= viewMaxX; gx += step) {
      ctx.moveTo(X(gx), margin.top);
      ctx.lineTo(X(gx), margin.top + plotH);
      ctx.fillText((gx * unitScale).toFixed(decimals), X(gx) - 12, margin.top + plotH + 13);
    }
    for (let gy = Math.ceil(viewMinY / step) * step; gy <= viewMaxY; gy += step) {
      ctx.moveTo(margin.left, Y(gy));
      ctx.lineTo(margin.left + plotW, Y(gy));
      ctx.fillText((gy * unitScale).toFixed(decimals), 4, Y(gy) + 4);
    }
    ctx.stroke();
    ctx.fillText('x, y [' + (inMicro ? MICRO + 'm' : 'mm') + ']', margin.left + plotW - 50, margin.top + plotH + 26);

    ctx.save();
    ctx.beginPath();
    ctx.rect(margin.left, margin.top, plotW, plotH);
    ctx.clip();

    function path(getX, getY, filter) {
      ctx.beginPath();
      let open = false;
      let lastIt = null;
      for (const s of samples) {
        const x = getX(s), y = getY(s);
        if (!filter(s) || !Number.isFinite(x) || !Number.isFinite(y)) {
          open = false;
          continue;
        }
        if (!open || s.it !== lastIt) ctx.moveTo(X(x), Y(y));
        else ctx.lineTo(X(x), Y(y));
        open = true;
        lastIt = s.it;
      }
      ctx.stroke();
    }
    const current = live.currentIteration;
    // Reference (the same curve every iteration), earlier iterations faint, the current one bold.
    ctx.lineWidth = 1;
    ctx.strokeStyle = '#999';
    ctx.setLineDash([4, 3]);
    path((s) => s.rx, (s) => s.ry, (s) => s.it === current);
    ctx.setLineDash([]);
    ctx.strokeStyle = 'rgba(31, 119, 180, 0.3)';
    path((s) => s.px, (s) => s.py, (s) => s.it !== current);
    ctx.lineWidth = 1.5;
    ctx.strokeStyle = '#1f77b4';
    path((s) => s.px, (s) => s.py, (s) => s.it === current);
    if (peak) {
      ctx.strokeStyle = '#c0392b';
      ctx.lineWidth = 1.5;
      ctx.beginPath();
      ctx.arc(X(peak.px), Y(peak.py), 5, 0, 2 * Math.PI);
      ctx.stroke();
      if (Number.isFinite(peak.rx)) {
        ctx.beginPath();
        ctx.moveTo(X(peak.rx), Y(peak.ry));
        ctx.lineTo(X(peak.px), Y(peak.py));
        ctx.stroke();
      }
    }
    ctx.restore();
    ctx.strokeStyle = '#888';
    ctx.lineWidth = 1;
    ctx.strokeRect(margin.left, margin.top, plotW, plotH);

    let info = samples.length + ' points; iteration ' + current;
    if (peak) info += '; peak |e| ' + lengthText(Math.abs(peak.e)) + ' at t = ' + peak.x.toFixed(3) + ' s';
    if (zoomed) info += '; view ' + PLUS_MINUS + ' ' + lengthText((viewMaxX - viewMinX) / 2) + ' around the peak';
    info += '; dashed: reference, blue: actual';
    setText($('contour-info'), info);
  }

  if (typeof ResizeObserver !== 'undefined') new ResizeObserver(() => scheduleRedraw()).observe(canvas);

  // ---------------------------------------------------------------- redraw, at most 10 a second

  let pendingState = null;    // the latest "state" message not shown yet
  let redrawTimer = null;
  let redrawDue = Infinity;   // when the pending redraw runs (performance.now() time)
  let lastRedrawMs = -Infinity;
  function scheduleRedraw() {
    scheduleRedrawIn(0);
  }
  // A redraw in `ms` (or sooner if one is already due sooner), never within REDRAW_MS of the last.
  function scheduleRedrawIn(ms) {
    const now = performance.now();
    const wait = Math.max(ms, REDRAW_MS - (now - lastRedrawMs), 0);
    if (redrawTimer !== null) {
      if (redrawDue <= now + wait) return;
      clearTimeout(redrawTimer);
    }
    redrawDue = now + wait;
    redrawTimer = setTimeout(redraw, wait);
  }

  // What the time plots draw: at most about two points per pixel column. Each bucket of rows
  // gives its first row and the rows with the smallest and largest value of the first series
  // (the envelope, so no peak of the error is lost); gaps (null rows) are kept.
  function thinned(rows, div) {
    const buckets = Math.max(100, Math.floor((div.clientWidth || 500) / 2));
    if (rows.length <= 3 * buckets) return rows.slice();
    const size = Math.ceil(rows.length / buckets);
    const out = [];
    for (let start = 0; start < rows.length; start += size) {
      const end = Math.min(rows.length, start + size);
      let lo = -1;
      let hi = -1;
      let gap = -1;
      for (let k = start; k < end; ++k) {
        const v = rows[k][1];
        if (v === null || v === undefined) {
          if (gap < 0) gap = k;
          continue;
        }
        if (lo < 0 || v < rows[lo][1]) lo = k;
        if (hi < 0 || v > rows[hi][1]) hi = k;
      }
      const picked = [start, lo, hi, gap].filter((k) => k >= 0).sort((a, b) => a - b);
      let last = -1;
      for (const k of picked) {
        if (k !== last) out.push(rows[k]);
        last = k;
      }
    }
    return out;
  }

  const TAU_REDRAW_MS = 1000;  // the histogram changes slowly: once a second is enough
  let lastTauMs = -Infinity;

  function redraw() {
    redrawTimer = null;
    redrawDue = Infinity;
    const now = performance.now();
    lastRedrawMs = now;
    if (pendingState) {
      const state = pendingState;
      pendingState = null;
      updateNodes(Array.isArray(state.nodes) ? state.nodes : []);
      updateAxes(Array.isArray(state.nodes) ? state.nodes : []);
      updateJobs(Array.isArray(state.jobs) ? state.jobs : []);
    }
    drawContour();
    plots.error.update(live.version, () => thinned(live.errorRows, plots.error.div), ['t', 'e [' + MICRO + 'm]']);
    if (live.commandWidth > 0) {
      plots.command.update(live.version, () => thinned(live.commandRows, plots.command.div),
        commandLabels(live.commandWidth));
    } else {
      plots.command.draw([], []);
    }
    if (now - lastTauMs >= TAU_REDRAW_MS || !plots.tau.graph) {
      lastTauMs = now;
      plots.tau.update(live.version, tauHistogram, [TAU + ' [ms]', 'cycles']);
    } else if (plots.tau.version !== live.version) {
      scheduleRedrawIn(TAU_REDRAW_MS - (now - lastTauMs));
    }
    setText($('tau-info'), live.job ? tauInfo() : '');
    plots.learning.update(live.iterationsVersion, learningRows,
      ['iteration', 'e_max [' + MICRO + 'm]', 'e_sum [mm]'], learningWindow());
    let info = '';
    if (live.dropped > 0) info = 'the feed let ' + live.dropped + ' samples go (this page fell behind)';
    if (live.finished) {
      info += (info ? '; ' : '') + 'ended: ' + (live.finished.state || '?') +
        (live.finished.error ? ' (' + live.finished.error + ')' : '');
    }
    setText($('live-info'), info);
  }

  function learningWindow() {
    const numbers = Array.from(live.iterations.keys());
    if (!numbers.length) return undefined;
    return { dateWindow: [Math.min(...numbers) - 0.5, Math.max(...numbers) + 0.5] };
  }

  // ---------------------------------------------------------------- start

  showConnection();
  showLiveHeader();
  redraw();
  loadPresets();
  connect();
})();
