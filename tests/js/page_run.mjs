// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Opens a launcher page URL (usually with ?run=pkg/exe) in Debian's Chromium
// with playwright-core, waits until every process the page started has
// ended, and prints one JSON line: {processes: [{label, state, exit, log:
// [{stream, severity, text}]}], pageErrors, console}. Run by
// tests/test_install_view.py:
//
//   node page_run.mjs '<json: {url, chromium, timeoutMs?}>'

import { launchChromium } from './chromium.mjs';

const options = JSON.parse(process.argv[2]);
const browser = await launchChromium(options.chromium);
const pageErrors = [];
const consoleLines = [];
let result = null;
try {
  const page = await browser.newPage();
  page.on('pageerror', (e) => pageErrors.push(String(e && e.stack ? e.stack : e)));
  page.on('console', (m) => consoleLines.push(`${m.type()}: ${m.text()}`));
  await page.goto(options.url);
  await page.waitForFunction(() => {
    const session = window.colconWasm && window.colconWasm.session;
    if (!session || session.processes.size === 0) return false;
    return [...session.processes.values()].every((p) => p.state !== 'starting' && p.state !== 'running');
  }, null, { timeout: options.timeoutMs || 60000 });
  result = await page.evaluate(() => [...window.colconWasm.session.processes.values()].map((p) => ({
    label: p.label, state: p.state, exit: p.exit,
    log: p.log.map((e) => ({ stream: e.stream || null, severity: e.severity, text: e.text })),
  })));
} catch (e) {
  pageErrors.push(`page_run.mjs: ${e && e.stack ? e.stack : e}`);
} finally {
  await browser.close();
}
process.stdout.write(`${JSON.stringify({ processes: result, pageErrors, console: consoleLines })}\n`);
process.exit(result ? 0 : 1);
