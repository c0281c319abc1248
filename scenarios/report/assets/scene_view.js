// MasnetScene: draws scene frames (docs/live-and-replay.md, "Frames") on a canvas. Shared by the
// report's replay and the live viewer, so it is plain browser JavaScript: no modules, no fetches.
//   var view = new MasnetScene.View(canvas, header, {maxWidth: 640, maxHeight: 640});
//   view.options.oracle = false;   // raster, cells, oracle, trails, flashes: all true at first
//   view.draw(frame, history);     // history: earlier frames, oldest first (only .p is read)
(function (global) {
  'use strict';

  // Viridis (matplotlib's map) at 16 evenly spaced stops, interpolated into 256 entries.
  var VIRIDIS_STOPS = [
    [68, 1, 84], [72, 26, 108], [71, 47, 125], [65, 68, 135], [57, 86, 140], [49, 104, 142],
    [42, 120, 142], [35, 136, 142], [31, 152, 139], [34, 168, 132], [53, 183, 121],
    [84, 197, 104], [122, 209, 81], [165, 219, 54], [210, 226, 27], [253, 231, 37]
  ];

  // A byte (0..255, linear in the reading) to a colour on a square-root scale, so that the weak
  // readings far from an acoustic target stay visible next to the peak.
  var COLOUR_TABLE = (function () {
    var table = new Uint8Array(256 * 3);
    for (var v = 0; v < 256; ++v) {
      var x = Math.sqrt(v / 255) * 15;
      var k = Math.min(14, Math.floor(x));
      var f = x - k;
      for (var c = 0; c < 3; ++c)
        table[v * 3 + c] = Math.round(VIRIDIS_STOPS[k][c] * (1 - f) + VIRIDIS_STOPS[k + 1][c] * f);
    }
    return table;
  })();

  // Tableau's ten categorical colours; more robots cycle the hue by the golden angle.
  var PALETTE = ['#1f77b4', '#ff7f0e', '#2ca02c', '#d62728', '#9467bd', '#8c564b', '#e377c2',
                 '#7f7f7f', '#bcbd22', '#17becf'];

  function robotColour(i, count) {
    if (count <= PALETTE.length) return PALETTE[i];
    return 'hsl(' + ((i * 137.508) % 360).toFixed(1) + ', 70%, 42%)';
  }

  function withAlpha(colour, alpha) {
    if (colour.charAt(0) === '#') {
      var n = parseInt(colour.slice(1), 16);
      return 'rgba(' + (n >> 16) + ', ' + ((n >> 8) & 255) + ', ' + (n & 255) + ', ' + alpha + ')';
    }
    return colour.replace('hsl(', 'hsla(').replace(')', ', ' + alpha + ')');
  }

  function decodeBase64(text) {
    var binary = global.atob(text);
    var bytes = new Uint8Array(binary.length);
    for (var i = 0; i < binary.length; ++i) bytes[i] = binary.charCodeAt(i);
    return bytes;
  }

  var PADDING_PX = 10;   // room for robots on the domain's edge
  var ROBOT_PX = 5;      // disc radius
  var FLASH_PX = 10;     // ring radius around a robot that transmitted

  function View(canvas, header, limits) {
    limits = limits || {};
    this.canvas = canvas;
    this.header = header;
    this.options = {raster: true, cells: true, oracle: true, trails: true, flashes: true};
    var bbox = header.bbox || [0, 0, 1, 1];
    var width = Math.max(bbox[2] - bbox[0], 1e-12), height = Math.max(bbox[3] - bbox[1], 1e-12);
    var maxWidth = limits.maxWidth || 640, maxHeight = limits.maxHeight || 640;
    var scale = Math.min((maxWidth - 2 * PADDING_PX) / width, (maxHeight - 2 * PADDING_PX) / height);
    this.innerWidth = width * scale;
    this.innerHeight = height * scale;
    this.cssWidth = Math.round(this.innerWidth + 2 * PADDING_PX);
    this.cssHeight = Math.round(this.innerHeight + 2 * PADDING_PX);
    this.pixelRatio = Math.max(1, Math.min(3, global.devicePixelRatio || 1));
    canvas.width = Math.round(this.cssWidth * this.pixelRatio);
    canvas.height = Math.round(this.cssHeight * this.pixelRatio);
    canvas.style.width = this.cssWidth + 'px';
    canvas.style.height = this.cssHeight + 'px';
    this.context = canvas.getContext('2d');
    this.steps = header.steps || 10000;
    var raster = header.raster || {};
    this.rasterNx = raster.nx || 0;
    this.rasterNy = raster.ny || 0;
    this.rasterCanvas = null;
    if (this.rasterNx > 0 && this.rasterNy > 0 && global.document) {
      this.rasterCanvas = global.document.createElement('canvas');
      this.rasterCanvas.width = this.rasterNx;
      this.rasterCanvas.height = this.rasterNy;
    }
  }

  // Scene coordinates (steps across the bounding box, y up) to CSS pixels (y down).
  View.prototype.px = function (qx) { return PADDING_PX + qx / this.steps * this.innerWidth; };
  View.prototype.py = function (qy) {
    return PADDING_PX + (1 - qy / this.steps) * this.innerHeight;
  };

  View.prototype.colour = function (i) {
    return robotColour(i, this.header.robots || 0);
  };

  // A path through a flat [x0, y0, x1, y1, ...] polygon; false when it has too few vertices.
  View.prototype.polygonPath = function (flat) {
    if (!flat || flat.length < 6) return false;
    var ctx = this.context;
    ctx.beginPath();
    ctx.moveTo(this.px(flat[0]), this.py(flat[1]));
    for (var k = 2; k + 1 < flat.length; k += 2) ctx.lineTo(this.px(flat[k]), this.py(flat[k + 1]));
    ctx.closePath();
    return true;
  };

  View.prototype.domainPath = function () {
    var domain = this.header.domain || [];
    var flat = [];
    for (var k = 0; k < domain.length; ++k) flat.push(domain[k][0], domain[k][1]);
    return this.polygonPath(flat);
  };

  View.prototype.drawRaster = function (frame) {
    if (!this.rasterCanvas || typeof frame.raster !== 'string') return;
    var bytes = decodeBase64(frame.raster);
    var nx = this.rasterNx, ny = this.rasterNy;
    if (bytes.length < nx * ny) return;
    var rasterContext = this.rasterCanvas.getContext('2d');
    var image = rasterContext.createImageData(nx, ny);
    for (var row = 0; row < ny; ++row) {
      var imageRow = ny - 1 - row;  // the raster's rows run from the bottom, the image's from the top
      for (var column = 0; column < nx; ++column) {
        var v = bytes[row * nx + column], at = (imageRow * nx + column) * 4;
        image.data[at] = COLOUR_TABLE[v * 3];
        image.data[at + 1] = COLOUR_TABLE[v * 3 + 1];
        image.data[at + 2] = COLOUR_TABLE[v * 3 + 2];
        image.data[at + 3] = 255;
      }
    }
    rasterContext.putImageData(image, 0, 0);
    var ctx = this.context;
    ctx.save();
    if (this.domainPath()) ctx.clip();
    ctx.imageSmoothingEnabled = false;  // nearest bins: each bin is one sensor area, not a blur
    ctx.globalAlpha = 0.55;  // lighter, so that cells and trails stand out
    ctx.drawImage(this.rasterCanvas, PADDING_PX, PADDING_PX, this.innerWidth, this.innerHeight);
    ctx.restore();
  };

  // A robot that is down keeps the cell it last computed; it no longer covers it, so it is left out.
  View.prototype.drawCells = function (frame, robots, down) {
    var ctx = this.context, cells = frame.cells || [];
    for (var i = 0; i < robots; ++i) {
      if (down[i] || !this.polygonPath(cells[i])) continue;
      ctx.fillStyle = withAlpha(this.colour(i), 0.12);
      ctx.fill();
    }
    ctx.setLineDash([]);
    for (var j = 0; j < robots; ++j) {
      if (down[j] || !this.polygonPath(cells[j])) continue;
      ctx.lineWidth = 3.2;  // a light halo keeps the edge visible on any raster colour
      ctx.strokeStyle = 'rgba(255, 255, 255, 0.6)';
      ctx.stroke();
      ctx.lineWidth = 1.6;
      ctx.strokeStyle = this.colour(j);
      ctx.stroke();
    }
  };

  View.prototype.drawOracle = function (frame, robots) {
    var ctx = this.context, oracle = frame.oracle || [];
    ctx.save();
    ctx.setLineDash([5, 4]);
    ctx.lineWidth = 1.3;
    ctx.strokeStyle = 'rgba(30, 30, 30, 0.9)';
    for (var i = 0; i < robots; ++i)
      if (this.polygonPath(oracle[i])) ctx.stroke();
    ctx.restore();
  };

  View.prototype.drawTrails = function (frame, history, robots) {
    if (!history || !history.length) return;
    var ctx = this.context;
    ctx.save();
    ctx.lineWidth = 1.5;
    ctx.lineJoin = 'round';
    for (var i = 0; i < robots; ++i) {
      ctx.beginPath();
      var started = false;
      for (var k = 0; k <= history.length; ++k) {
        var p = k < history.length ? history[k].p : frame.p;
        if (!p || p.length < 2 * i + 2) continue;
        var x = this.px(p[2 * i]), y = this.py(p[2 * i + 1]);
        if (started) ctx.lineTo(x, y);
        else ctx.moveTo(x, y);
        started = true;
      }
      ctx.strokeStyle = withAlpha(this.colour(i), 0.75);
      ctx.stroke();
    }
    ctx.restore();
  };

  View.prototype.drawTargets = function (frame) {
    var ctx = this.context, targets = frame.targets || [];
    ctx.save();
    ctx.lineWidth = 1.5;
    ctx.strokeStyle = '#ffffff';
    ctx.fillStyle = '#e31a1c';
    for (var k = 0; k + 1 < targets.length; k += 2) {
      var x = this.px(targets[k]), y = this.py(targets[k + 1]), s = 7;
      ctx.beginPath();
      ctx.moveTo(x, y - s);
      ctx.lineTo(x + s, y);
      ctx.lineTo(x, y + s);
      ctx.lineTo(x - s, y);
      ctx.closePath();
      ctx.fill();
      ctx.stroke();
    }
    ctx.restore();
  };

  View.prototype.drawFlashes = function (frame, robots, down) {
    var ctx = this.context, sent = frame.sent || [], p = frame.p || [];
    ctx.save();
    ctx.strokeStyle = 'rgba(255, 140, 0, 0.9)';
    ctx.lineWidth = 2;
    for (var i = 0; i < robots; ++i) {
      if (!(sent[i] > 0) || down[i]) continue;
      // The more frames since the previous frame, the wider the ring.
      var radius = FLASH_PX + Math.min(sent[i] - 1, 4) * 1.5;
      ctx.beginPath();
      ctx.arc(this.px(p[2 * i]), this.py(p[2 * i + 1]), radius, 0, 2 * Math.PI);
      ctx.stroke();
    }
    ctx.restore();
  };

  // Robot groups: each follower (x, y, its leader's index) as a small disc in its leader's
  // colour, joined to the leader by a thin line.
  View.prototype.drawFollowers = function (frame) {
    var ctx = this.context, f = frame.followers || [], p = frame.p || [];
    ctx.save();
    for (var k = 0; k + 2 < f.length; k += 3) {
      var g = f[k + 2], x = this.px(f[k]), y = this.py(f[k + 1]);
      if (2 * g + 1 < p.length) {
        ctx.beginPath();
        ctx.moveTo(this.px(p[2 * g]), this.py(p[2 * g + 1]));
        ctx.lineTo(x, y);
        ctx.lineWidth = 1;
        ctx.strokeStyle = withAlpha(this.colour(g), 0.8);
        ctx.stroke();
      }
      ctx.beginPath();
      ctx.arc(x, y, ROBOT_PX - 2, 0, 2 * Math.PI);
      ctx.fillStyle = '#ffffff';
      ctx.strokeStyle = this.colour(g);
      ctx.lineWidth = 1.5;
      ctx.fill();
      ctx.stroke();
    }
    ctx.restore();
  };

  View.prototype.drawRobots = function (frame, robots, down) {
    var ctx = this.context, p = frame.p || [];
    ctx.save();
    ctx.lineWidth = 1.5;
    for (var i = 0; i < robots; ++i) {
      var x = this.px(p[2 * i]), y = this.py(p[2 * i + 1]);
      ctx.beginPath();
      ctx.arc(x, y, ROBOT_PX, 0, 2 * Math.PI);
      ctx.fillStyle = down[i] ? '#b0b0b0' : this.colour(i);
      ctx.strokeStyle = '#ffffff';
      ctx.fill();
      ctx.stroke();
      if (down[i]) {
        var s = ROBOT_PX + 2;
        ctx.beginPath();
        ctx.moveTo(x - s, y - s);
        ctx.lineTo(x + s, y + s);
        ctx.moveTo(x - s, y + s);
        ctx.lineTo(x + s, y - s);
        ctx.strokeStyle = '#000000';
        ctx.stroke();
      }
    }
    ctx.restore();
  };

  View.prototype.drawTime = function (frame) {
    var ctx = this.context;
    var text = 't = ' + (typeof frame.t === 'number' ? frame.t.toFixed(2) : '?') + ' s';
    ctx.save();
    ctx.font = '12px "DejaVu Sans", Helvetica, Arial, sans-serif';
    var width = ctx.measureText(text).width;
    ctx.fillStyle = 'rgba(255, 255, 255, 0.85)';
    ctx.fillRect(PADDING_PX + 2, PADDING_PX + 2, width + 8, 17);
    ctx.fillStyle = '#111111';
    ctx.textBaseline = 'middle';
    ctx.fillText(text, PADDING_PX + 6, PADDING_PX + 11);
    ctx.restore();
  };

  View.prototype.draw = function (frame, history) {
    var ctx = this.context, o = this.options;
    ctx.setTransform(this.pixelRatio, 0, 0, this.pixelRatio, 0, 0);
    ctx.setLineDash([]);
    ctx.globalAlpha = 1;
    ctx.fillStyle = '#ffffff';
    ctx.fillRect(0, 0, this.cssWidth, this.cssHeight);
    if (!frame) return;
    var robots = Math.floor((frame.p || []).length / 2);
    var down = {};
    (frame.down || []).forEach(function (i) { down[i] = true; });

    if (o.raster) this.drawRaster(frame);
    if (o.cells) this.drawCells(frame, robots, down);
    if (o.oracle) this.drawOracle(frame, robots);
    if (this.domainPath()) {
      ctx.lineWidth = 1.5;
      ctx.strokeStyle = '#222222';
      ctx.stroke();
    }
    if (o.trails) this.drawTrails(frame, history, robots);
    this.drawTargets(frame);
    if (o.flashes) this.drawFlashes(frame, robots, down);
    this.drawFollowers(frame);
    this.drawRobots(frame, robots, down);
    this.drawTime(frame);
  };

  global.MasnetScene = {View: View, robotColour: robotColour};
})(typeof window !== 'undefined' ? window : this);
