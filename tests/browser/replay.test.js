// The report's replay in Chromium: node replay.test.js RUN_DIR/report.html
// The page opens from disk with no error and no request beyond itself, plays (the canvas
// changes as the frames advance), pauses, scrubs, toggles layers and plays to the end at 8x.
'use strict';
const test = require('node:test');
const assert = require('node:assert/strict');
const fs = require('node:fs');
const path = require('node:path');
const { launch, canvasHash } = require('./browser.js');

const report = path.resolve(process.argv[2] || '');
if (!process.argv[2] || !fs.existsSync(report)) {
  console.error('usage: node replay.test.js RUN_DIR/report.html (no such file: ' + report + ')');
  process.exit(2);
}

const frameOf = (page) => page.$eval('#replay', (s) => Number(s.getAttribute('data-frame')));

test('the replay plays, pauses, scrubs and toggles without errors', async () => {
  const { browser, page, problems, requests } = await launch();
  try {
    await page.goto('file://' + report);
    const frames = await page.$eval('#replay-data', (e) => JSON.parse(e.textContent).frames);
    assert.ok(frames.length > 10, 'replay.json has ' + frames.length + ' frames');
    await page.waitForSelector('#replay[data-replay-frames="' + frames.length + '"]');
    assert.equal(await frameOf(page), 0);
    assert.equal(await page.$eval('#replay-scrubber', (e) => Number(e.max)), frames.length - 1);
    // The canvas keeps the domain's aspect ratio (a square here).
    const size = await page.$eval('#replay-canvas', (c) => [c.clientWidth, c.clientHeight]);
    assert.ok(size[0] > 100 && size[0] === size[1], 'canvas ' + size);

    const atStart = await canvasHash(page, '#replay-canvas');
    await page.click('#replay-play');
    assert.equal(await page.textContent('#replay-play'), 'Pause');
    await page.waitForFunction(() => Number(document.getElementById('replay').getAttribute('data-frame')) >= 5);
    const first = await frameOf(page);
    const early = await canvasHash(page, '#replay-canvas');
    await page.waitForFunction(
        (f) => Number(document.getElementById('replay').getAttribute('data-frame')) >= f + 5, first);
    const later = await canvasHash(page, '#replay-canvas');
    assert.notEqual(early, atStart, 'the canvas changed once playing');
    assert.notEqual(later, early, 'the canvas changed between two instants of the playback');

    // Pause holds the frame; the scrubber follows the playback.
    await page.click('#replay-play');
    assert.equal(await page.textContent('#replay-play'), 'Play');
    const paused = await frameOf(page);
    assert.equal(await page.$eval('#replay-scrubber', (e) => Number(e.value)), paused);
    await page.waitForTimeout(300);
    assert.equal(await frameOf(page), paused);

    // Scrubbing to the last frame shows its time.
    await page.$eval('#replay-scrubber', (e) => {
      e.value = e.max;
      e.dispatchEvent(new Event('input'));
    });
    const last = frames[frames.length - 1];
    assert.equal(await frameOf(page), frames.length - 1);
    assert.ok((await page.textContent('#replay-time')).startsWith('t = ' + last.t.toFixed(2) + ' s'));

    // A layer toggled off changes the picture; toggled on again it is the same picture.
    const withAll = await canvasHash(page, '#replay-canvas');
    for (const layer of ['raster', 'oracle', 'trails', 'cells']) {
      await page.click('#replay-' + layer);
      assert.notEqual(await canvasHash(page, '#replay-canvas'), withAll, layer + ' off');
      await page.click('#replay-' + layer);
      assert.equal(await canvasHash(page, '#replay-canvas'), withAll, layer + ' on again');
    }

    // From the end, play starts again at the beginning and, at 8x, reaches the end and stops.
    await page.selectOption('#replay-speed', '8');
    await page.click('#replay-play');
    await page.waitForFunction(() => document.getElementById('replay-play').textContent === 'Play' &&
                               Number(document.getElementById('replay').getAttribute('data-frame')) > 0,
                               null, { timeout: 60000 });
    assert.equal(await frameOf(page), frames.length - 1);

    assert.deepEqual(problems, []);
    assert.deepEqual(await page.evaluate(() => window.masnetErrors), []);
    assert.deepEqual(requests.filter((url) => !url.startsWith('data:')), ['file://' + report],
                     'the page loads nothing beyond itself');
  } finally {
    await browser.close();
  }
});
