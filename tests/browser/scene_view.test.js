// MasnetScene (scenarios/report/assets/scene_view.js), the drawing that the report's replay and
// the live viewer share, on synthetic frames: node scene_view.test.js SCENE_VIEW_JS
// Checks the API the pages rely on and where things land on the canvas (y up, aspect ratio,
// device pixel ratio), by the colour of single pixels.
'use strict';
const test = require('node:test');
const assert = require('node:assert/strict');
const fs = require('node:fs');
const { launch } = require('./browser.js');

const source = fs.readFileSync(process.argv[2] || '', 'utf8');

const ROBOT_BLUE = [0x1f, 0x77, 0xb4];  // robot 0's colour
const WHITE = [255, 255, 255];

// A page with the script and a canvas, at device pixel ratio 2.
async function open() {
  const opened = await launch({ deviceScaleFactor: 2 });
  await opened.page.setContent('<!DOCTYPE html><html><body><canvas id="c"></canvas><script>' +
                               source + '</script></body></html>');
  return opened;
}

// Draws `frame` (with `history`) on a fresh view of `header` after applying `options`, and
// returns the RGB of each of `points`, given in scene coordinates.
function drawAndSample(page, header, frame, history, options, points) {
  return page.evaluate(({ header, frame, history, options, points }) => {
    const canvas = document.getElementById('c');
    const view = new MasnetScene.View(canvas, header, { maxWidth: 640, maxHeight: 640 });
    Object.assign(view.options, options);
    view.draw(frame, history);
    const ratio = canvas.width / canvas.clientWidth;
    return points.map(([qx, qy]) => {
      const x = Math.round(view.px(qx) * ratio), y = Math.round(view.py(qy) * ratio);
      return Array.from(canvas.getContext('2d').getImageData(x, y, 1, 1).data.slice(0, 3));
    });
  }, { header, frame, history, options, points });
}

const header = {
  format: 'masnet-scene-1', bbox: [0, 0, 2, 1], steps: 10000, robots: 2, sensors: 2, targets: 1,
  domain: [[0, 0], [10000, 0], [10000, 10000], [0, 10000]], raster: { nx: 2, ny: 1 }
};
// Robot 0 high up on the left, robot 1 (down, its last cell the right half) low on the right,
// a target at the bottom left; the raster's left bin is 0, its right bin 255 (base64 of the
// bytes 0x00 0xff).
const frame = {
  t: 1.25, p: [2000, 9000, 8000, 1500], r: [500, 500], sent: [0, 0], down: [1],
  cells: [[0, 0, 5000, 0, 5000, 10000, 0, 10000], [5000, 0, 10000, 0, 10000, 10000, 5000, 10000]],
  oracle: [[], []],
  targets: [2000, 2000], raster: 'AP8=', raster_max: 3.5
};

const close = (a, b, tolerance) => a.every((v, k) => Math.abs(v - b[k]) <= (tolerance || 12));

// How many orange pixels lie 7 to 16 px to the right of robot 0 once `frame` is drawn.
function orangeBeside(page, frame, flashes) {
  return page.evaluate(({ header, frame, flashes }) => {
    const canvas = document.getElementById('c');
    const view = new MasnetScene.View(canvas, header, { maxWidth: 640, maxHeight: 640 });
    view.options.flashes = flashes;
    view.draw(frame, []);
    const ratio = canvas.width / canvas.clientWidth, ctx = canvas.getContext('2d');
    const x = view.px(frame.p[0]), y = view.py(frame.p[1]);
    let orange = 0;
    for (let d = 7; d <= 16; d += 0.5) {
      const c = ctx.getImageData(Math.round((x + d) * ratio), Math.round(y * ratio), 1, 1).data;
      if (c[0] > 200 && c[1] > 100 && c[1] < 200 && c[2] < 100) ++orange;
    }
    return orange;
  }, { header, frame, flashes });
}

test('the API: View, draw and five layer options, all on', async () => {
  const { browser, page, problems } = await open();
  try {
    const api = await page.evaluate((header) => {
      const view = new MasnetScene.View(document.getElementById('c'), header, {});
      return { draw: typeof view.draw, options: view.options };
    }, header);
    assert.equal(api.draw, 'function');
    assert.deepEqual(api.options, { raster: true, cells: true, oracle: true, trails: true, flashes: true });
    assert.deepEqual(problems, []);
  } finally {
    await browser.close();
  }
});

test('the canvas takes the domain aspect ratio within the maximum size at the device pixel ratio', async () => {
  const { browser, page } = await open();
  try {
    const size = await page.evaluate((header) => {
      const canvas = document.getElementById('c');
      const view = new MasnetScene.View(canvas, header, { maxWidth: 640, maxHeight: 640 });
      return { css: [canvas.clientWidth, canvas.clientHeight], pixels: [canvas.width, canvas.height],
               inner: [view.px(10000) - view.px(0), view.py(0) - view.py(10000)] };
    }, header);
    assert.equal(size.css[0], 640);
    assert.ok(size.css[1] < 400, 'a 2:1 domain gives a wide canvas: ' + size.css);
    assert.ok(Math.abs(size.inner[0] / size.inner[1] - 2) < 1e-9, 'inner ' + size.inner);
    assert.deepEqual(size.pixels, [size.css[0] * 2, size.css[1] * 2]);
  } finally {
    await browser.close();
  }
});

test('robots, targets, raster and y up land where the frame says', async () => {
  const { browser, page, problems } = await open();
  try {
    const [robot, downRobot, target, rightBin, mirror] = await drawAndSample(
        page, header, frame, [], {},
        [[2000, 9000], [8000, 1500], [2000, 2000], [9000, 5000], [2000, 1000]]);
    assert.ok(close(robot, ROBOT_BLUE), 'robot 0 at the top left: ' + robot);
    assert.ok(close(downRobot, [0xb0, 0xb0, 0xb0], 40) || close(downRobot, [0, 0, 0], 60),
              'a down robot is grey and crossed: ' + downRobot);
    assert.ok(target[0] > 180 && target[1] < 80 && target[2] < 80, 'the target is red: ' + target);
    // The raster's bright bin (viridis' yellow end, lightened) is yellow: red and green over blue.
    assert.ok(rightBin[0] > 150 && rightBin[1] > 150 && rightBin[2] < 140, 'bright bin: ' + rightBin);
    // y up: nothing of robot 0 at the mirrored height, and its disc in the canvas's top left.
    assert.ok(!close(mirror, ROBOT_BLUE, 40), 'mirror point: ' + mirror);
    const disc = await page.evaluate(({ header, frame }) => {
      const canvas = document.getElementById('c');
      const view = new MasnetScene.View(canvas, header, { maxWidth: 640, maxHeight: 640 });
      view.options.cells = false;  // robot 0's cell edge has its colour too
      view.draw(frame, []);
      const data = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
      let n = 0, x = 0, y = 0;
      for (let i = 0; i < data.length; i += 4)
        if (data[i] === 0x1f && data[i + 1] === 0x77 && data[i + 2] === 0xb4) {
          ++n;
          x += (i / 4) % canvas.width;
          y += Math.floor(i / 4 / canvas.width);
        }
      return { n, x: x / n / canvas.width, y: y / n / canvas.height };
    }, { header, frame });
    assert.ok(disc.n > 20 && disc.x < 0.3 && disc.y < 0.3, 'robot 0 disc: ' + JSON.stringify(disc));

    const [bareBin] = await drawAndSample(page, header, frame, [], { raster: false }, [[9000, 5000]]);
    // Without the raster the right half is white: nothing of the down robot's stale cell either.
    assert.deepEqual(bareBin, WHITE);
    assert.deepEqual(problems, []);
  } finally {
    await browser.close();
  }
});

test('trails follow the history and flashes ring the robots that sent', async () => {
  const { browser, page } = await open();
  try {
    // Robot 0 came from (2000, 3000) straight up to (2000, 9000); it sent 2 frames.
    const history = [{ p: [2000, 3000, 8000, 1500] }, { p: [2000, 6000, 8000, 1500] }];
    const moving = Object.assign({}, frame, { sent: [2, 0], raster: undefined, cells: [[], []] });
    const trailPoint = [2000, 4500];
    const [trail] = await drawAndSample(page, header, moving, history, {}, [trailPoint]);
    assert.ok(!close(trail, WHITE, 30) && trail[2] > trail[0], 'trail pixel: ' + trail);
    const [noTrail] = await drawAndSample(page, header, moving, history, { trails: false }, [trailPoint]);
    assert.deepEqual(noTrail, WHITE);

    // The ring: orange pixels on the horizontal line through robot 0, 7 to 16 px out.
    assert.ok(await orangeBeside(page, moving, true) > 0, 'an orange ring around the robot that sent');
    assert.equal(await orangeBeside(page, moving, false), 0, 'no ring with flashes off');
    const noRing = await orangeBeside(page, Object.assign({}, moving, { sent: [0, 0] }), true);
    assert.equal(noRing, 0, 'no ring when the robot sent nothing');
  } finally {
    await browser.close();
  }
});
