// The report's replay (docs/live-and-replay.md, "Replay in the report"): plays the frames of
// replay.json, inlined as JSON in #replay-data, on #replay-canvas with MasnetScene's drawing.
(function () {
  'use strict';
  var dataElement = document.getElementById('replay-data');
  var section = document.getElementById('replay');
  if (!dataElement || !section || typeof MasnetScene === 'undefined') return;
  var replay = JSON.parse(dataElement.textContent);
  var frames = replay.frames || [];
  if (!frames.length) return;

  // Trails show the path over the last TRAIL_FRAMES frames (a quarter of a run at the default
  // frame period): long enough to see where a robot comes from, short enough to stay legible.
  var TRAIL_FRAMES = 60;
  var canvas = document.getElementById('replay-canvas');
  var playButton = document.getElementById('replay-play');
  var speedSelect = document.getElementById('replay-speed');
  var scrubber = document.getElementById('replay-scrubber');
  var timeLabel = document.getElementById('replay-time');
  var metricsLabel = document.getElementById('replay-metrics');
  var view = new MasnetScene.View(canvas, replay.header, {maxWidth: 640, maxHeight: 640});

  var index = 0, playing = false, simTime = frames[0].t, lastWall = null;
  var lastTime = frames[frames.length - 1].t;

  function number(v, digits) {
    return typeof v === 'number' && isFinite(v) ? Number(v.toPrecision(digits)).toString() : '-';
  }

  function describe(metrics) {
    if (!metrics) return '';
    var parts = ['coverage cost H ' + number(metrics.coverage_cost, 4),
                 'messages ' + number(metrics.messages, 8),
                 'radio energy ' + number(metrics.energy_j, 4) + ' J',
                 'cell correctness ' + number(metrics.cell_correctness, 3)];
    if ('tracking_mean' in metrics) parts.push('tracking error ' + number(metrics.tracking_mean, 3));
    if ('pollution_total' in metrics) parts.push('total pollution ' + number(metrics.pollution_total, 4));
    return parts.join(' \u00b7 ');
  }

  function show(i) {
    index = i;
    scrubber.value = String(i);
    var frame = frames[i];
    view.draw(frame, frames.slice(Math.max(0, i - TRAIL_FRAMES), i));
    timeLabel.textContent = 't = ' + frame.t.toFixed(2) + ' s (frame ' + (i + 1) + ' of ' +
                            frames.length + ')';
    if (metricsLabel) metricsLabel.textContent = describe(frame.metrics);
    section.setAttribute('data-frame', String(i));
  }

  // The last frame at or before simulated time t.
  function frameAt(t) {
    var lo = 0, hi = frames.length - 1;
    while (lo < hi) {
      var mid = (lo + hi + 1) >> 1;
      if (frames[mid].t <= t) lo = mid;
      else hi = mid - 1;
    }
    return lo;
  }

  function setPlaying(on) {
    playing = on;
    lastWall = null;
    playButton.textContent = on ? 'Pause' : 'Play';
    playButton.setAttribute('aria-pressed', on ? 'true' : 'false');
    if (on) window.requestAnimationFrame(tick);
  }

  function tick(now) {
    if (!playing) return;
    if (lastWall !== null) simTime += (now - lastWall) / 1000 * Number(speedSelect.value);
    lastWall = now;
    var i = frameAt(simTime);
    if (i !== index) show(i);
    if (simTime >= lastTime) {
      show(frames.length - 1);
      setPlaying(false);
      return;
    }
    window.requestAnimationFrame(tick);
  }

  playButton.addEventListener('click', function () {
    if (!playing && index === frames.length - 1) {  // at the end: play again from the start
      simTime = frames[0].t;
      show(0);
    }
    setPlaying(!playing);
  });
  scrubber.addEventListener('input', function () {
    var i = Number(scrubber.value);
    simTime = frames[i].t;
    show(i);
  });
  ['raster', 'cells', 'oracle', 'trails', 'flashes'].forEach(function (key) {
    var box = document.getElementById('replay-' + key);
    if (!box) return;
    view.options[key] = box.checked;
    box.addEventListener('change', function () {
      view.options[key] = box.checked;
      show(index);
    });
  });

  scrubber.max = String(frames.length - 1);
  show(0);
  section.setAttribute('data-replay-frames', String(frames.length));
})();
