// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Launch files started from the page (tests/test_page_launch.py), as a user
// starts them: the Launch files list, ⋯ for the arguments' form, ▶ Launch.
// `launches` are run one after the other: [{file: 'PKG/PATH', args: {name: value},
// until: 'JS expression' (what must come true while it runs), stop: true (press
// its Stop once `until` holds) or end: true (wait until it ends by itself),
// screenshot: PATH}]. Prints one JSON line: {ok, error, checks, logs, pageErrors}.
//
//   node page_launch.mjs '<json: {url, chromium, launches}>'

import { launchChromium } from './chromium.mjs';

const options = JSON.parse(process.argv[2]);
const browser = await launchChromium(options.chromium);
const pageErrors = [];
const checks = { launches: [] };
let error = null;
let page = null;

/** The launch's own process entry of the page (the newest for the file), as plain data. */
const launchEntry = (file) => page.evaluate((name) => {
  const entries = [...window.colconWasm.session.processes.values()].filter((p) => p.kind === 'launch' && p.exe === name);
  const p = entries[entries.length - 1];
  return p ? { id: p.id, state: p.state, exit: p.exit, log: p.log.map((e) => e.text) } : null;
}, file);

try {
  page = await browser.newPage({ viewport: { width: 1440, height: 900 } });
  page.on('pageerror', (e) => pageErrors.push(String(e && e.stack ? e.stack : e)));
  await page.goto(options.url);
  await page.waitForFunction(() => document.body.dataset.state === 'ready', null, { timeout: 60000 });
  checks.listed = await page.$$eval('.launch-file', (rows) => rows.map((r) => r.dataset.launch));
  for (const launch of options.launches) {
    const seen = { file: launch.file };
    checks.launches.push(seen);
    const row = page.locator(`.launch-file[data-launch="${launch.file}"]`);
    await row.locator('button.icon').click();
    // the form: the arguments, "No arguments.", or why they could not be read
    await row.locator('.launch-arg, .launch-args .hint:text("No arguments."), .launch-args .error-text').first().waitFor({ timeout: 60000 });
    seen.formError = await row.locator('.launch-args .error-text').first().textContent({ timeout: 100 }).catch(() => null);
    seen.form = await row.locator('.launch-arg').evaluateAll((labels) => labels.map((l) => {
      const input = l.querySelector('input, select');
      return { name: input.dataset.argument, placeholder: input.placeholder || null, text: l.textContent };
    }));
    for (const [name, value] of Object.entries(launch.args || {})) {
      await row.locator(`[data-argument="${name}"]`).fill(value);
    }
    await row.locator('button.run').click();
    const name = launch.file.split('/').pop();
    await page.waitForFunction((n) => [...window.colconWasm.session.processes.values()].some((p) => p.kind === 'launch' && p.exe.endsWith(n)), name, { timeout: 30000 });
    const file = await page.evaluate((n) => [...window.colconWasm.session.processes.values()].filter((p) => p.kind === 'launch' && p.exe.endsWith(n)).pop().exe, name);
    try {
      if (launch.until) await page.waitForFunction(launch.until, null, { timeout: launch.timeoutMs || 120000, polling: 200 });
      if (launch.values) seen.values = await page.evaluate(launch.values);
      if (launch.screenshot) await page.screenshot({ path: launch.screenshot });
      if (launch.stop) {
        const { id } = await launchEntry(file);
        await page.locator(`.proc[data-proc="${await page.evaluate((i) => window.colconWasm.session.processes.get(i).label, id)}"] button.stop`).click();
      }
      await page.waitForFunction((n) => {
        const entries = [...window.colconWasm.session.processes.values()].filter((p) => p.kind === 'launch' && p.exe === n);
        return entries.length && entries[entries.length - 1].state !== 'running';
      }, file, { timeout: 60000, polling: 200 });
      // what the launch started has ended with it
      await page.waitForFunction(() => [...window.colconWasm.session.processes.values()].every((p) => p.state !== 'running' && p.state !== 'starting'), null, { timeout: 30000, polling: 200 });
    } finally {
      seen.entry = await launchEntry(file);
      seen.processes = await page.evaluate((n) => [...window.colconWasm.session.processes.values()].filter((p) => p.launch && p.launch.exe === n).map((p) => ({ label: p.label, state: p.state, exit: p.exit, args: p.args })), file);
    }
  }
} catch (e) {
  error = String(e && e.message ? e.message : e);
}
let logs = {};
try {
  logs = await page.evaluate(() => Object.fromEntries([...window.colconWasm.session.processes.values()].map((p) => [p.label, p.log.map((e) => e.text).slice(-30)])));
} catch { /* the page is gone */ }
await browser.close();
process.stdout.write(`${JSON.stringify({ ok: !error, error, checks, logs, pageErrors })}\n`);
