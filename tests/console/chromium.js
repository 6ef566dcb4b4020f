// Debian's chromium, headless, for the console's browser scripts: as root (no sandbox), with a
// fresh profile each time, and with nothing that tries to reach the internet (the machines that
// run the tests have none).
'use strict';

const fs = require('fs');
const os = require('os');
const path = require('path');
const puppeteer = require('puppeteer-core');

// Launches chromium at `executablePath`; `close()` ends it and removes its profile. With
// `netns`, chromium runs inside that network namespace (`ip netns exec`, root), where its pages
// reach that namespace's 127.0.0.1; puppeteer then talks to it over a pipe, not a port.
async function launchChromium(executablePath, netns = '') {
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'pena-chromium-'));
  let executable = executablePath;
  if (netns) {
    executable = path.join(profile, 'chromium-in-netns');
    fs.writeFileSync(executable, `#!/bin/sh\nexec ip netns exec ${netns} ${executablePath} "$@"\n`, { mode: 0o755 });
  }
  const browser = await puppeteer.launch({
    executablePath: executable,
    pipe: Boolean(netns),
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
