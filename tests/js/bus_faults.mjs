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
//   node bus_faults.mjs node [--demo INSTALL] [SCENARIO...]
//   node bus_faults.mjs chromium /usr/bin/chromium [--demo INSTALL] [SCENARIO...]
//
// --demo: the demo's install space (demo/src built with colcon build --wasm),
// for the scenarios that kill its C++ programs.

import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

import { DEMO, NODE_ONLY, runScenario, SCENARIOS } from './bus_faults_scenarios.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const wasmJs = path.resolve(here, '..', '..', 'packages', 'wasm_js');
let args = process.argv.slice(2);
let demo = null;
if (args.includes('--demo')) {
  const at = args.indexOf('--demo');
  demo = path.resolve(args[at + 1]);
  args = [...args.slice(0, at), ...args.slice(at + 2)];
}
const DEMO_EXES = ['talker', 'add_two_ints_server'];

/** The demo executables' paths: isolated (demo_nodes/lib/demo_nodes/) or merged layout. */
function demoPaths() {
  const out = {};
  for (const exe of DEMO_EXES) {
    const candidates = [path.join(demo, 'demo_nodes', 'lib', 'demo_nodes', `${exe}.js`), path.join(demo, 'lib', 'demo_nodes', `${exe}.js`)];
    out[exe] = candidates.find((p) => fs.existsSync(p));
    if (!out[exe]) throw new Error(`no ${exe}.js in the demo install ${demo}`);
  }
  return out;
}

function print(r) {
  process.stdout.write(`${JSON.stringify(r)}\n`);
}

if (args[0] === '--list') {
  for (const name of Object.keys(SCENARIOS)) print({ scenario: name, nodeOnly: NODE_ONLY.has(name), demo: DEMO.has(name) });
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
    demo: demo && demoPaths(),
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
  demo: DEMO_URLS,
};
window.runScenario = (name) => runScenario(name, env);
window.pageReady = true;
</script>`;

const TYPES = { '.mjs': 'text/javascript', '.js': 'text/javascript', '.wasm': 'application/wasm', '.json': 'application/json' };

/**
 * Serve /wasm_js/ (packages/wasm_js), /tests/ (tests/js) and /demo/ (the demo's
 * install space) cross-origin isolated.
 */
function serve() {
  const routes = [['/wasm_js/', wasmJs], ['/tests/', here]];
  if (demo) routes.push(['/demo/', demo]);
  const server = http.createServer((req, res) => {
    const url = new URL(req.url, 'http://localhost');
    const isolated = { 'Cross-Origin-Opener-Policy': 'same-origin', 'Cross-Origin-Embedder-Policy': 'require-corp', 'Cache-Control': 'no-store' };
    if (url.pathname === '/faults.html') {
      const urls = demo ? Object.fromEntries(Object.entries(demoPaths()).map(([exe, p]) => [exe, `/demo/${path.relative(demo, p)}`])) : null;
      res.writeHead(200, { ...isolated, 'Content-Type': 'text/html' })
        .end(PAGE.replace('DEMO_URLS', urls ? `Object.fromEntries(Object.entries(${JSON.stringify(urls)}).map(([k, v]) => [k, new URL(v, location.href).href]))` : 'null'));
      return;
    }
    const route = routes.find(([prefix]) => url.pathname.startsWith(prefix));
    const file = route && path.resolve(route[1], decodeURIComponent(url.pathname.slice(route[0].length)));
    const type = file && TYPES[path.extname(file)];
    if (!type || !file.startsWith(route[1]) || !fs.existsSync(file) || !fs.statSync(file).isFile()) {
      res.writeHead(404).end();
      return;
    }
    res.writeHead(200, { ...isolated, 'Content-Type': type });
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
  await runNode(names.length ? names : Object.keys(SCENARIOS).filter((n) => demo || !DEMO.has(n)));
} else if (platform === 'chromium' && args[1]) {
  const names = args.slice(2);
  await runChromium(args[1], names.length ? names
    : Object.keys(SCENARIOS).filter((n) => !NODE_ONLY.has(n) && (demo || !DEMO.has(n))));
} else {
  process.stderr.write('usage: node bus_faults.mjs --list | node [--demo INSTALL] [SCENARIO...] | chromium CHROMIUM [--demo INSTALL] [SCENARIO...]\n');
  process.exit(2);
}
process.exit(0);
