// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Runs the kill-at-the-worst-moment scenarios (bus_faults_scenarios.mjs) on
// the repository's wasm_js runtime (packages/wasm_js/src, no build), in
// Node.js worker threads or in Debian's Chromium (a page served here with
// COOP/COEP, its workers Web Workers), and prints one JSON line per
// scenario: {scenario, ok, error?, step?, facts, ms}. Run by
// tests/test_bus_faults.py:
//
//   node bus_faults.mjs --list
//   node bus_faults.mjs node [SCENARIO...]
//   node bus_faults.mjs chromium /usr/bin/chromium [SCENARIO...]

import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

import { NODE_ONLY, runScenario, SCENARIOS } from './bus_faults_scenarios.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const wasmJs = path.resolve(here, '..', '..', 'packages', 'wasm_js');
const args = process.argv.slice(2);

function print(r) {
  process.stdout.write(`${JSON.stringify(r)}\n`);
}

if (args[0] === '--list') {
  for (const name of Object.keys(SCENARIOS)) print({ scenario: name, nodeOnly: NODE_ONLY.has(name) });
  process.exit(0);
}

async function runNode(names) {
  const src = `${pathToFileURL(path.join(wasmJs, 'src')).href}/`;
  const env = {
    Runtime: (await import(`${src}index.mjs`)).Runtime,
    ProgramWorker: (await import(`${src}platform.mjs`)).ProgramWorker,
    layout: await import(`${src}layout.mjs`),
    src,
    workerUrl: pathToFileURL(path.join(here, 'bus_faults_worker.mjs')).href,
  };
  for (const name of names) print(await runScenario(name, env));
}

const PAGE = `<!doctype html>
<meta charset="utf-8">
<title>bus faults</title>
<script type="module">
import { runScenario } from '/tests/bus_faults_scenarios.mjs';
const src = new URL('/wasm_js/src/', location.href).href;
const env = {
  Runtime: (await import(src + 'index.mjs')).Runtime,
  ProgramWorker: (await import(src + 'platform.mjs')).ProgramWorker,
  layout: await import(src + 'layout.mjs'),
  src,
  workerUrl: new URL('/tests/bus_faults_worker.mjs', location.href).href,
};
window.runScenario = (name) => runScenario(name, env);
window.pageReady = true;
</script>`;

/** Serve /wasm_js/ (packages/wasm_js) and /tests/ (tests/js) cross-origin isolated. */
function serve() {
  const routes = [['/wasm_js/', wasmJs], ['/tests/', here]];
  const server = http.createServer((req, res) => {
    const url = new URL(req.url, 'http://localhost');
    const isolated = { 'Cross-Origin-Opener-Policy': 'same-origin', 'Cross-Origin-Embedder-Policy': 'require-corp', 'Cache-Control': 'no-store' };
    if (url.pathname === '/faults.html') {
      res.writeHead(200, { ...isolated, 'Content-Type': 'text/html' }).end(PAGE);
      return;
    }
    const route = routes.find(([prefix]) => url.pathname.startsWith(prefix));
    const file = route && path.resolve(route[1], decodeURIComponent(url.pathname.slice(route[0].length)));
    if (!file || !file.startsWith(route[1]) || !file.endsWith('.mjs') || !fs.existsSync(file)) {
      res.writeHead(404).end();
      return;
    }
    res.writeHead(200, { ...isolated, 'Content-Type': 'text/javascript' });
    fs.createReadStream(file).pipe(res);
  });
  return new Promise((resolve) => server.listen(0, '127.0.0.1', () => resolve(server)));
}

async function runChromium(chromium, names) {
  const { launchChromium } = await import('./chromium.mjs');
  const server = await serve();
  const base = `http://127.0.0.1:${server.address().port}`;
  const browser = await launchChromium(chromium);
  try {
    for (const name of names) {
      const page = await browser.newPage();
      const console = [];
      page.on('console', (m) => { if (console.length < 50) console.push(`${m.type()}: ${m.text()}`); });
      page.on('pageerror', (e) => console.push(`pageerror: ${e.message}`));
      let r;
      try {
        await page.goto(`${base}/faults.html`);
        await page.waitForFunction(() => window.pageReady === true, null, { timeout: 30000 });
        r = await page.evaluate((n) => window.runScenario(n), name);
      } catch (e) {
        r = { scenario: name, ok: false, error: `the page failed: ${e.message}`, facts: {} };
      }
      if (!r.ok) r.console = console;
      print(r);
      await page.close();
    }
  } finally {
    await browser.close();
    server.close();
  }
}

const platform = args[0];
if (platform === 'node') {
  const names = args.slice(1);
  await runNode(names.length ? names : Object.keys(SCENARIOS));
} else if (platform === 'chromium' && args[1]) {
  const names = args.slice(2);
  await runChromium(args[1], names.length ? names : Object.keys(SCENARIOS).filter((n) => !NODE_ONLY.has(n)));
} else {
  process.stderr.write('usage: node bus_faults.mjs --list | node [SCENARIO...] | chromium CHROMIUM [SCENARIO...]\n');
  process.exit(2);
}
process.exit(0);
