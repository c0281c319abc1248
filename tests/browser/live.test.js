// The live viewer in Chromium: node live.test.js MASNET SCENARIO OUT_DIR
// `masnet run SCENARIO --serve --port 0` prints its URL; the page opens, the run starts for
// this viewer, at least 50 frames arrive, nothing errs, and a screenshot is not blank (the
// variance of its pixels). Interrupted after the run, masnet exits 0 with its run directory.
'use strict';
const test = require('node:test');
const assert = require('node:assert/strict');
const fs = require('node:fs');
const path = require('node:path');
const { spawn } = require('node:child_process');
const { launch } = require('./browser.js');

const [masnet, scenario, out] = process.argv.slice(2);
if (!masnet || !scenario || !out) {
  console.error('usage: node live.test.js MASNET SCENARIO OUT_DIR');
  process.exit(2);
}

// Resolves with the URL masnet prints; collects everything it prints.
function startServing() {
  const child = spawn(masnet, ['run', scenario, '--serve', '--port', '0', '--out', out,
                               '--force', '--quiet', '--set', 'duration=3',
                               '--set', 'output.snapshots=[0,3]'],
                      { stdio: ['ignore', 'pipe', 'pipe'] });
  let printed = '';
  const url = new Promise((resolve, reject) => {
    child.stdout.on('data', (chunk) => {
      printed += chunk;
      const match = /live view: (http:\/\/\S+)/.exec(printed);
      if (match) resolve(match[1]);
    });
    child.stderr.on('data', (chunk) => { printed += chunk; });
    child.on('exit', (code) => reject(new Error('masnet exited (' + code + '): ' + printed)));
  });
  const exited = new Promise((resolve) => child.on('exit', (code, signal) => resolve({ code, signal })));
  // Printed once the run directory is written.
  const serving = new Promise((resolve) => {
    const check = () => (/still serving/.test(printed) ? resolve() : setTimeout(check, 50));
    check();
  });
  return { child, url, exited, serving, output: () => printed };
}

// Mean and variance of the grey levels of a PNG, decoded by the browser itself.
async function pixelVariance(page, png) {
  return page.evaluate(async (base64) => {
    const image = new Image();
    image.src = 'data:image/png;base64,' + base64;
    await image.decode();
    const canvas = document.createElement('canvas');
    canvas.width = image.width;
    canvas.height = image.height;
    const context = canvas.getContext('2d');
    context.drawImage(image, 0, 0);
    const data = context.getImageData(0, 0, canvas.width, canvas.height).data;
    let sum = 0, squares = 0;
    const n = data.length / 4;
    for (let i = 0; i < data.length; i += 4) {
      const grey = (data[i] + data[i + 1] + data[i + 2]) / 3;
      sum += grey;
      squares += grey * grey;
    }
    const mean = sum / n;
    return squares / n - mean * mean;
  }, png.toString('base64'));
}

test('the live page shows a running scenario', async () => {
  fs.rmSync(out, { recursive: true, force: true });
  const serving = startServing();
  const url = await serving.url;
  assert.match(url, /^http:\/\/127\.0\.0\.1:\d+\/$/);
  const { browser, page, problems } = await launch();
  try {
    await page.goto(url);
    // The run waits, paused, for this first viewer, then goes at real time: 3 s, 150 frames.
    await page.waitForFunction(() => Number(document.body.getAttribute('data-frames') || 0) >= 50,
                               null, { timeout: 60000 });
    const scene = await page.$eval('#scene', (c) => [c.width, c.height]);
    assert.ok(scene[0] > 100 && scene[0] === scene[1], 'scene canvas ' + scene);
    const shot = await page.screenshot({ path: path.join(path.dirname(out), 'live-view.png') });
    const variance = await pixelVariance(page, shot);
    assert.ok(variance > 100, 'the screenshot is nearly uniform (variance ' + variance + ')');
    // The charts have points and the status line follows the run.
    assert.ok(await page.evaluate(() => Chart.getChart('chart-coverage').data.datasets[0].data.length > 5));
    // (On a busy machine the 3 s run may end while the screenshot is taken: then it says so.)
    assert.match(await page.textContent('#status'),
                 /^t = \d+\.\d\d s, (running at 1x|finished)(; viewers: 1)?/);
    // Run to the end: the page says the run has finished. Clicked from the page, so that a run
    // that has just ended (its button disabled) is not waited on for 30 s.
    await page.evaluate(() => document.getElementById('end').click());
    await page.waitForFunction(() => document.getElementById('status').textContent.includes('finished'),
                               null, { timeout: 60000 });
    assert.deepEqual(problems, []);
  } catch (error) {
    serving.child.kill('SIGKILL');
    throw error;
  } finally {
    await browser.close();
  }
  // The server stays up after the run until interrupted; then masnet exits 0.
  await serving.serving;
  assert.ok(fs.existsSync(path.join(out, 'summary.json')), serving.output());
  serving.child.kill('SIGINT');
  const { code } = await serving.exited;
  assert.equal(code, 0, serving.output());
  assert.match(serving.output(), /live view: stopped \(viewers 1, frames sent \d+, coalesced \d+\)/);
});
