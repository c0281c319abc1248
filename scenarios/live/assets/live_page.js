// The live viewer's page (docs/live-and-replay.md): frames from the run's WebSocket drawn by
// MasnetScene, the metric curves drawn by Chart.js, and the controls sent back as commands.
(function () {
  'use strict';
  var kTrailFrames = 150;      // frames of trail behind each robot
  var kChartRedrawMs = 250;    // charts are redrawn at most this often
  var state = { header: null, view: null, trail: [], latest: null, frames: 0, status: null,
                drawPending: false, chartsDirty: false, lastMetricT: -1, finished: false };
  var charts = {};
  var socket = null;

  function byId(id) { return document.getElementById(id); }

  function send(command) {
    if (socket && socket.readyState === WebSocket.OPEN) socket.send(JSON.stringify(command));
  }

  function makeChart(id, title, unit, color) {
    if (typeof Chart === 'undefined') return null;
    return new Chart(byId(id), {
      type: 'line',
      data: { datasets: [{ label: title, data: [], borderColor: color, pointRadius: 0,
                           borderWidth: 1.5 }] },
      options: { animation: false, maintainAspectRatio: false, parsing: false,
                 plugins: { legend: { display: false }, title: { display: true, text: title } },
                 scales: { x: { type: 'linear', title: { display: true, text: 't (s)' } },
                           y: { title: { display: true, text: unit } } } }
    });
  }

  function setUp(header) {
    state.header = header;
    byId('title').textContent = header.name + ' (live)';
    state.view = new MasnetScene.View(byId('scene'), header, { maxWidth: 720, maxHeight: 720 });
    charts.coverage = makeChart('chart-coverage', 'Coverage cost', 'H', '#1f77b4');
    charts.tracking = header.diffusion
      ? makeChart('chart-tracking', 'Pollution (sum of readings)', 'total', '#8c564b')
      : makeChart('chart-tracking', 'Tracking error (mean)', 'distance', '#2ca02c');
    charts.messages = makeChart('chart-messages', 'Messages sent', 'frames', '#ff7f0e');
    charts.energy = makeChart('chart-energy', 'Radio energy', 'J', '#d62728');
  }

  function addMetrics(m) {
    if (!m || m.t <= state.lastMetricT) return;
    state.lastMetricT = m.t;
    var second = state.header && state.header.diffusion ? m.pollution_total : m.tracking_mean;
    var points = [[charts.coverage, m.coverage_cost], [charts.tracking, second],
                  [charts.messages, m.messages], [charts.energy, m.energy_j]];
    points.forEach(function (pair) {
      if (pair[0] && pair[1] !== undefined) pair[0].data.datasets[0].data.push({ x: m.t, y: pair[1] });
    });
    state.chartsDirty = true;
  }

  function redrawCharts() {
    if (!state.chartsDirty) return;
    state.chartsDirty = false;
    Object.keys(charts).forEach(function (k) { if (charts[k]) charts[k].update('none'); });
  }

  function draw() {
    state.drawPending = false;
    if (state.view && state.latest) state.view.draw(state.latest, state.trail);
  }

  function onFrame(frame) {
    state.frames += 1;
    byId('frames').textContent = String(state.frames);
    document.body.setAttribute('data-frames', String(state.frames));
    addMetrics(frame.metrics);
    if (state.latest) {
      state.trail.push({ t: state.latest.t, p: state.latest.p });
      if (state.trail.length > kTrailFrames) state.trail.shift();
    }
    state.latest = frame;
    renderStatus();
    if (!state.drawPending) {
      state.drawPending = true;
      window.requestAnimationFrame(draw);
    }
  }

  function onStatus(s) {
    state.status = s;
    renderStatus();
    byId('play').textContent = s.paused || s.waiting_for_viewer ? 'Play' : 'Pause';
    ['play', 'step', 'speed', 'end'].forEach(function (id) { byId(id).disabled = !!s.finished; });
  }

  // The state from the last status message, the time from the latest frame.
  function renderStatus() {
    var s = state.status;
    if (!s) return;
    var t = state.latest ? state.latest.t : s.t;
    var text = 't = ' + t.toFixed(2) + ' s';
    if (s.finished) text += ', finished (the run directory is written)';
    else if (s.waiting_for_viewer) text += ', waiting for a viewer';
    else if (s.paused) text += ', paused';
    else if (s.to_end) text += ', running to the end';
    else text += ', running at ' + (s.speed > 0 ? s.speed + 'x' : 'full speed');
    text += '; viewers: ' + s.viewers;
    byId('status').textContent = text;
  }

  function onMessage(message) {
    if (message.type === 'hello') {
      setUp(message.header);
    } else if (message.type === 'history') {
      message.points.forEach(function (point) {
        addMetrics(point.metrics);
        state.trail.push({ t: point.t, p: point.p });
      });
      if (state.trail.length > kTrailFrames) state.trail = state.trail.slice(-kTrailFrames);
    } else if (message.type === 'frame') {
      onFrame(message.frame);
    } else if (message.type === 'end') {
      state.finished = true;
      onFrame(message.frame);
    } else if (message.type === 'status') {
      onStatus(message);
    } else if (message.type === 'error') {
      byId('message').textContent = message.message;
    }
  }

  function connect() {
    var scheme = window.location.protocol === 'https:' ? 'wss://' : 'ws://';
    socket = new WebSocket(scheme + window.location.host + '/ws');
    socket.onopen = function () { byId('connection').textContent = 'connected'; };
    socket.onclose = function () {
      byId('connection').textContent = state.finished
        ? 'run finished; server gone' : 'disconnected';
    };
    socket.onmessage = function (event) { onMessage(JSON.parse(event.data)); };
  }

  function wireControls() {
    byId('play').addEventListener('click', function () {
      var paused = !state.status || state.status.paused || state.status.waiting_for_viewer;
      send({ cmd: paused ? 'play' : 'pause' });
    });
    byId('step').addEventListener('click', function () { send({ cmd: 'step' }); });
    byId('end').addEventListener('click', function () { send({ cmd: 'end' }); });
    byId('speed').addEventListener('change', function (e) {
      send({ cmd: 'speed', value: Number(e.target.value) });
    });
    [['show-oracle', 'oracle'], ['show-raster', 'raster'], ['show-trails', 'trails'],
     ['show-flashes', 'flashes']].forEach(function (pair) {
      byId(pair[0]).addEventListener('change', function (e) {
        if (!state.view) return;
        state.view.options[pair[1]] = e.target.checked;
        draw();
      });
    });
  }

  wireControls();
  window.setInterval(redrawCharts, kChartRedrawMs);
  connect();
})();
