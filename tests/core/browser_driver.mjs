// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Headless Chromium for the core tests: serves the test page with
 * COOP/COEP, then answers JSON-line commands on stdin:
 *
 *   {"id": 1, "cmd": "scenario", "name": "lossless"}  -> {"id": 1, "result": {...}}
 *   {"id": 2, "cmd": "isolation"}                     -> {"id": 2, "result": {"status": ..., "isolated": false}}
 *
 *   node browser_driver.mjs WASM_JS_SHARE_DIR NODES_DIR
 *
 * playwright-core comes from tests/js (npm ci there); Chromium is the
 * system's (COLCON_WASM_CHROMIUM, default /usr/bin/chromium); nothing is
 * downloaded.
 */

import fs from 'node:fs';
import http from 'node:http';
import { createRequire } from 'node:module';
import os from 'node:os';
import path from 'node:path';
import readline from 'node:readline';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const require = createRequire(path.join(here, '..', 'js', 'package.json'));
const { chromium } = require('playwright-core');

const [shareDir, nodesDir] = process.argv.slice(2);
const TYPES = {
  '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript',
  '.wasm': 'application/wasm', '.json': 'application/json',
};
const ROUTES = [
  ['/wasm_js/', shareDir, true],
  ['/nodes/', nodesDir, true],
  ['/core/', here, true],
  ['/plain/', here, false],
];

const server = http.createServer((req, res) => {
  const url = new URL(req.url, 'http://localhost');
  if (url.pathname === '/favicon.ico') {
    res.writeHead(204).end();
    return;
  }
  const route = ROUTES.find(([prefix]) => url.pathname.startsWith(prefix));
  if (!route) {
    res.writeHead(404).end();
    return;
  }
  const [prefix, dir, isolated] = route;
  const file = path.resolve(dir, decodeURIComponent(url.pathname.slice(prefix.length)));
  if (!file.startsWith(path.resolve(dir)) || !fs.existsSync(file) || !fs.statSync(file).isFile()) {
    res.writeHead(404).end();
    return;
  }
  const headers = { 'Content-Type': TYPES[path.extname(file)] || 'application/octet-stream', 'Cache-Control': 'no-store' };
  if (isolated) {
    headers['Cross-Origin-Opener-Policy'] = 'same-origin';
    headers['Cross-Origin-Embedder-Policy'] = 'require-corp';
  }
  res.writeHead(200, headers);
  fs.createReadStream(file).pipe(res);
});
await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
const base = `http://127.0.0.1:${server.address().port}`;

const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'wasm-js-chromium-'));
const browser = await chromium.launch({
  executablePath: process.env.COLCON_WASM_CHROMIUM || '/usr/bin/chromium',
  headless: true,
  args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
    '--disable-background-networking', '--disable-component-update', '--disable-sync'],
});
const context = await browser.newContext();

async function openPage(url) {
  const page = await context.newPage();
  const console = [];
  page.on('console', (m) => console.push(`${m.type()}: ${m.text()}`));
  page.on('pageerror', (e) => console.push(`pageerror: ${e.message}`));
  await page.goto(url);
  await page.waitForFunction('window.pageReady === true', null, { timeout: 30000 });
  return { page, console };
}

async function handle(msg) {
  if (msg.cmd === 'scenario') {
    const { page, console } = await openPage(`${base}/core/page.html`);
    try {
      const status = await page.textContent('#status');
      if (status !== 'ready') return { ok: false, error: `page not ready: ${status}`, console };
      const result = await page.evaluate((name) => window.runScenario(name), msg.name);
      return { ...result, console };
    } finally {
      await page.close();
    }
  }
  if (msg.cmd === 'isolation') {
    const { page, console } = await openPage(`${base}/plain/page.html`);
    try {
      return {
        status: await page.textContent('#status'),
        isolated: await page.evaluate('crossOriginIsolated'),
        console,
      };
    } finally {
      await page.close();
    }
  }
  throw new Error(`unknown command ${JSON.stringify(msg.cmd)}`);
}

async function shutdown(code) {
  await browser.close().catch(() => {});
  server.close();
  fs.rmSync(profile, { recursive: true, force: true });
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
    reply = { id: msg.id, result: await handle(msg) };
  } catch (e) {
    reply = { id: msg.id, error: e && e.stack ? e.stack : String(e) };
  }
  process.stdout.write(`${JSON.stringify(reply)}\n`);
}
await shutdown(0);
