// What the browser tests share: Chromium (Debian's, never a downloaded build) through
// playwright-core, a page that records every console error, page error and request, and
// hashes of a canvas's pixels.
'use strict';
const fs = require('node:fs');

function inCi() {
  const ci = process.env.CI;
  return Boolean(ci) && ci !== 'false' && ci !== '0';
}

// Exit 77 (CTest's "skipped") when something the tests need is missing; under CI, fail instead.
function requireOrSkip(present, what) {
  if (present) return;
  if (inCi()) {
    console.error(what + ' is missing, and CI must have it');
    process.exit(1);
  }
  console.log('skipped: ' + what + ' is missing');
  process.exit(77);
}

const chromiumPath = process.env.MASNET_CHROMIUM || '/usr/bin/chromium';

function loadPlaywright() {
  requireOrSkip(fs.existsSync(chromiumPath), chromiumPath + ' (apt-get install chromium)');
  let playwright = null;
  try {
    playwright = require('playwright-core');
  } catch (e) {
    requireOrSkip(false, 'playwright-core (the fixture runs npm ci in tests/browser)');
  }
  return playwright;
}

async function launch(options) {
  const { chromium } = loadPlaywright();
  const browser = await chromium.launch({
    executablePath: chromiumPath,
    args: ['--no-sandbox', '--disable-gpu', '--disable-background-networking',
           '--disable-component-update', '--no-first-run']
  });
  const context = await browser.newContext(Object.assign({ viewport: { width: 1200, height: 1000 } },
                                                          options || {}));
  const page = await context.newPage();
  const problems = [], requests = [];
  page.on('console', (message) => {
    if (message.type() === 'error') problems.push('console error: ' + message.text());
  });
  page.on('pageerror', (error) => problems.push('page error: ' + String(error)));
  page.on('request', (request) => requests.push(request.url()));
  return { browser, page, problems, requests };
}

// FNV-1a over the canvas's RGBA bytes, as a hex string.
function canvasHash(page, selector) {
  return page.$eval(selector, (canvas) => {
    const data = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
    let h = 0x811c9dc5;
    for (let i = 0; i < data.length; ++i) h = Math.imul(h ^ data[i], 0x01000193) >>> 0;
    return h.toString(16);
  });
}

module.exports = { launch, canvasHash, requireOrSkip };
