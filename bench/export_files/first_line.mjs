// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Time from navigation to the listener's first line, in headless Chromium,
// for bench/export: a new browser profile (cold: nothing cached, and for an
// exported site the service worker's install and reload), then a second
// navigation in the same profile (warm). The page starts the talker and the
// listener itself (?run= for serve, export --run for a static site).
// Prints one JSON line: {cold_ms, warm_ms, bytes_cold, bytes_warm, error}.
//
//   node first_line.mjs '<json: {url, chromium, userDataDir, warmUrl?, exe?}>'
//
// warmUrl: the second visit's URL (default: url), so that a server's log
// tells the visits apart; exe: the listener's executable name (default listener).

// tests/js's Chromium launcher (its playwright-core: npm ci there; it downloads no browser)
import { launchChromiumProfile } from '../../tests/js/chromium.mjs';

const options = JSON.parse(process.argv[2]);
const context = await launchChromiumProfile(options.chromium, options.userDataDir);
const heard = (exe) => [...(window.colconWasm?.session?.processes?.values() || [])]
  .some((p) => p.exe === exe && p.log.some((e) => e.text.includes('I heard')));

async function visit(url) {
  const page = await context.newPage();
  let bytes = 0;
  // what the page was sent (compressed where the server compressed it)
  page.on('response', (response) => { bytes += Number(response.headers()['content-length'] || 0); });
  const started = Date.now();
  await page.goto(url);
  await page.waitForFunction(heard, options.exe || 'listener', { timeout: 60000, polling: 20 });
  const ms = Date.now() - started;
  await page.close();
  return { ms, bytes };
}

let out = {};
try {
  const cold = await visit(options.url);
  const warm = await visit(options.warmUrl || options.url);
  out = { cold_ms: cold.ms, warm_ms: warm.ms, bytes_cold: cold.bytes, bytes_warm: warm.bytes, error: null };
} catch (e) {
  out = { error: String(e && e.message ? e.message : e) };
}
await context.close();
process.stdout.write(`${JSON.stringify(out)}\n`);
