// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Headless Chromium for the rmw_wasm_cpp tests: serves an install space and
 * the scenario page with COOP/COEP, then runs scenarios (web/scenario.mjs)
 * given as JSON lines on stdin, one page each:
 *
 *   {"id": 1, "scenario": {...}}   ->   {"id": 1, "result": {report}}
 *
 *   node browser_scenario.mjs INSTALL_DIR [/PREFIX/=DIR ...]
 *
 * Extra routes serve more folders (bench/rclcpp adds its page and the core's
 * bench nodes); {"id": 2, "page": "/bench/page.html", "call": "runBench",
 * "arg": ...} opens that page and returns `await window[call](arg)`.
 *
 * The first line printed is {"ready": true, "base": URL}: executables are
 * at BASE/install/<pkg>/lib/<pkg>/<exe>.js. playwright-core comes from
 * tests/js (npm ci there); Chromium is the system's (COLCON_WASM_CHROMIUM,
 * default /usr/bin/chromium); nothing is downloaded.
 */

import fs from 'node:fs';
import http from 'node:http';
import { createRequire } from 'node:module';
import path from 'node:path';
import readline from 'node:readline';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const require = createRequire(path.join(here, '..', 'js', 'package.json'));
const { chromium } = require('playwright-core');

const [installDir, ...extraRoutes] = process.argv.slice(2);
const TYPES = {
  '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript',
  '.wasm': 'application/wasm', '.json': 'application/json',
};
const ROUTES = [['/install/', installDir], ['/rmw/', path.join(here, 'web')],
  ...extraRoutes.map((r) => [r.slice(0, r.indexOf('=')), r.slice(r.indexOf('=') + 1)])];

const server = http.createServer((req, res) => {
  const url = new URL(req.url, 'http://localhost');
  const route = ROUTES.find(([prefix]) => url.pathname.startsWith(prefix));
  if (!route) {
    res.writeHead(404).end();
    return;
  }
  const [prefix, dir] = route;
  const file = path.resolve(dir, decodeURIComponent(url.pathname.slice(prefix.length)));
  if (!file.startsWith(path.resolve(dir)) || !fs.existsSync(file) || !fs.statSync(file).isFile()) {
    res.writeHead(404).end();
    return;
  }
  res.writeHead(200, {
    'Content-Type': TYPES[path.extname(file)] || 'application/octet-stream',
    'Cache-Control': 'no-store',
    'Cross-Origin-Opener-Policy': 'same-origin',
    'Cross-Origin-Embedder-Policy': 'require-corp',
    'Cross-Origin-Resource-Policy': 'same-origin',
  });
  fs.createReadStream(file).pipe(res);
});
await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
const base = `http://127.0.0.1:${server.address().port}`;

const browser = await chromium.launch({
  executablePath: process.env.COLCON_WASM_CHROMIUM || '/usr/bin/chromium',
  headless: true,
  args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
    '--disable-background-networking', '--disable-component-update', '--disable-sync'],
});
// Playwright gives the browser a fresh temporary profile (--user-data-dir) itself.
const context = await browser.newContext();

// Open a page, wait until it is ready, return `await window[call](arg)` (plus the console).
async function callPage(pagePath, call, arg) {
  const page = await context.newPage();
  const console = [];
  page.on('console', (m) => console.push(`${m.type()}: ${m.text()}`));
  page.on('pageerror', (e) => console.push(`pageerror: ${e.message}`));
  try {
    await page.goto(`${base}${pagePath}`);
    await page.waitForFunction('window.pageReady === true', null, { timeout: 30000 });
    const status = await page.textContent('#status');
    if (status !== 'ready') return { ok: false, error: `page not ready: ${status}`, console };
    const value = await page.evaluate(([f, a]) => window[f](a), [call, arg]);
    return { ...value, console };
  } finally {
    await page.close();
  }
}

async function shutdown(code) {
  await browser.close().catch(() => {});
  server.close();
  process.exit(code);
}

process.stdout.write(`${JSON.stringify({ ready: true, base, version: browser.version() })}\n`);
const rl = readline.createInterface({ input: process.stdin });
rl.on('close', () => shutdown(0));
for await (const line of rl) {
  if (!line.trim()) continue;
  const msg = JSON.parse(line);
  if (msg.cmd === 'quit') break;
  let reply;
  try {
    const result = msg.page
      ? await callPage(msg.page, msg.call, msg.arg)
      : await callPage('/rmw/page.html', 'runScenario', msg.scenario);
    reply = { id: msg.id, result };
  } catch (e) {
    reply = { id: msg.id, error: e && e.stack ? e.stack : String(e) };
  }
  process.stdout.write(`${JSON.stringify(reply)}\n`);
}
await shutdown(0);
