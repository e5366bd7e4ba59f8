// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Drives the launcher page served by `colcon-wasm serve` the way a user does:
// starts executables with arguments through the page's session, waits for
// log lines, stops them. Debian's Chromium through playwright-core (never a
// downloaded browser). Prints one JSON line:
// {ok, error, logs: {name: [text]}, states: {name: state}, snapshots: {name: bool|null}, pageErrors}.
//
//   node page_session.mjs '<json: {url, chromium, steps, timeoutMs?}>'
//
// steps: {start: NAME, pkg, exe, args?} | {wait: NAME, text | regex, count?}
//        | {python: NAME, file: PATH, args?: TEXT}: picks the file with "Run Python file…"
//        | {pythonConsole: NAME}: presses "Python console"
//        | {type: NAME, line: TEXT}: types a line into the log dock's stdin field (NAME's tab shown)
//        | {sleep: MS} | {stop: NAME}
//        | {until: JS expression (true when done), timeoutMs?, save?: NAME}: waits until the
//          expression, evaluated in the page, is truthy; with `save` its value is in `saved`
//        | {screenshot: PATH, width?, height?}: the page at that window size
//        | {goto: URL}: a second visit in the same tab (the profile's caches and service
//          workers stay), then waits for the page's session as at the start

import { launchChromium } from './chromium.mjs';

const options = JSON.parse(process.argv[2]);
const timeoutMs = options.timeoutMs || 60000;
const browser = await launchChromium(options.chromium);
const pageErrors = [];
const ids = {};
const saved = {};
let error = null;
let page = null;

function pageLogs() {
  return page.evaluate((names) => {
    const session = window.colconWasm.session;
    const logs = {};
    const states = {};
    const snapshots = {};
    for (const [name, id] of Object.entries(names)) {
      const proc = session.processes.get(id);
      logs[name] = proc ? proc.log.map((e) => e.text) : [];
      states[name] = proc ? proc.state : 'unknown';
      // a Python node: started from the page's Pyodide snapshot (python/pyodide_snapshot.mjs)
      snapshots[name] = proc && proc.handle ? !!proc.handle.pyodideSnapshot : null;
    }
    return { logs, states, snapshots };
  }, ids);
}

try {
  page = await browser.newPage();
  page.on('pageerror', (e) => pageErrors.push(String(e && e.stack ? e.stack : e)));
  await page.goto(options.url);
  await page.waitForFunction(() => window.colconWasm && window.colconWasm.session
    && window.colconWasm.session.runtime, null, { timeout: timeoutMs });
  for (const step of options.steps) {
    if (step.start) {
      ids[step.start] = await page.evaluate(({ pkg, exe, args }) => window.colconWasm.session
        .startProcess(pkg, exe, args).id, { pkg: step.pkg, exe: step.exe, args: step.args || [] });
    } else if (step.python) {
      const before = await page.evaluate(() => window.colconWasm.session.nextId);
      await page.fill('#python-args', step.args || '');
      await page.setInputFiles('#python-file', step.file);
      await page.waitForFunction((n) => window.colconWasm.session.nextId > n, before, { timeout: 10000 });
      ids[step.python] = before;
    } else if (step.pythonConsole) {
      const before = await page.evaluate(() => window.colconWasm.session.nextId);
      await page.click('#python-console');
      await page.waitForFunction((n) => window.colconWasm.session.nextId > n, before, { timeout: 10000 });
      ids[step.pythonConsole] = before;
    } else if (step.type) {
      await page.waitForFunction((id) => window.colconWasm.session.processes.get(id).state === 'running',
        ids[step.type], { timeout: step.timeoutMs || timeoutMs });
      const input = 'form.stdin:not([hidden]) input';
      await page.waitForSelector(input, { timeout: 10000 });
      await page.fill(input, step.line);
      await page.press(input, 'Enter');
    } else if (step.wait) {
      const deadline = Date.now() + (step.timeoutMs || timeoutMs);
      const pattern = step.regex ? new RegExp(step.regex) : null;
      for (;;) {
        const { logs, states } = await pageLogs();
        const lines = logs[step.wait] || [];
        const hits = lines.filter((t) => (pattern ? pattern.test(t) : t.includes(step.text))).length;
        if (hits >= (step.count || 1)) break;
        if (states[step.wait] !== 'starting' && states[step.wait] !== 'running') {
          throw new Error(`${step.wait} ended (${states[step.wait]}) before printing `
            + `${JSON.stringify(step.text || step.regex)}`);
        }
        if (Date.now() > deadline) {
          throw new Error(`timed out waiting for ${step.wait} to print ${JSON.stringify(step.text || step.regex)}`);
        }
        await new Promise((resolve) => setTimeout(resolve, 100));
      }
    } else if (step.until) {
      const deadline = Date.now() + (step.timeoutMs || timeoutMs);
      for (;;) {
        const value = await page.evaluate((expr) => { try { return (0, eval)(expr); } catch { return null; } }, step.until);
        if (value) {
          if (step.save) saved[step.save] = value;
          break;
        }
        if (Date.now() > deadline) throw new Error(`timed out waiting until ${step.until}`);
        await new Promise((resolve) => setTimeout(resolve, 100));
      }
    } else if (step.screenshot) {
      // {screenshot: PATH, width, height}: what a user sees at that window size
      if (step.width) await page.setViewportSize({ width: step.width, height: step.height || 900 });
      await new Promise((resolve) => setTimeout(resolve, 300));
      await page.screenshot({ path: step.screenshot });
    } else if (step.goto) {
      await page.goto(step.goto);
      await page.waitForFunction(() => window.colconWasm && window.colconWasm.session
        && window.colconWasm.session.runtime, null, { timeout: timeoutMs });
    } else if (step.sleep) {
      await new Promise((resolve) => setTimeout(resolve, step.sleep));
    } else if (step.stop) {
      await page.evaluate((id) => window.colconWasm.session.stopProcess(id), ids[step.stop]);
    } else {
      throw new Error(`unknown step ${JSON.stringify(step)}`);
    }
  }
} catch (e) {
  error = String(e && e.message ? e.message : e);
}
let result = { logs: {}, states: {}, snapshots: {} };
try {
  if (page) result = await pageLogs();
} catch (e) {
  error = error || String(e);
}
await browser.close();
process.stdout.write(`${JSON.stringify({ ok: !error, error, ...result, saved, pageErrors })}\n`);
