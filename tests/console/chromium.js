// Debian's chromium, headless, for the console's browser scripts: as root (no sandbox), with a
// fresh profile each time, and with nothing that tries to reach the internet (the machines that
// run the tests have none).
'use strict';

const fs = require('fs');
const os = require('os');
const path = require('path');
const puppeteer = require('puppeteer-core');

// Launches chromium at `executablePath`; `close()` ends it and removes its profile.
async function launchChromium(executablePath) {
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'pena-chromium-'));
  const browser = await puppeteer.launch({
    executablePath,
    headless: true,
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
           '--disable-background-networking', '--disable-component-update', '--disable-sync',
           `--user-data-dir=${profile}`, '--window-size=1280,800'],
    defaultViewport: { width: 1280, height: 800 },
  });
  const close = async () => {
    await browser.close();
    fs.rmSync(profile, { recursive: true, force: true });
  };
  return { browser, close };
}

module.exports = { launchChromium };
