// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Headless Chromium for the core tests and bench/transport: serves folders
 * (with COOP/COEP, or without for --plain routes; --no-eval routes add a
 * Content-Security-Policy that refuses eval to the documents and workers
 * they serve), then answers JSON-line commands on stdin:
 *
 *   {"id": 1, "cmd": "evaluate", "url": "/core/page.html", "expr": "runScenario('x')"}
 *       -> {"id": 1, "result": {"value": ..., "status": ..., "isolated": ..., "console": [...]}}
 *
 *   node browser_driver.mjs --route /prefix/=DIR... [--plain|--no-eval /prefix/=DIR]...
 *
 * Each command opens a fresh page, waits for `window.pageReady`, evaluates
 * the expression (awaiting a promise) and closes the page. playwright-core
 * comes from tests/js (npm ci there); Chromium is the system's
 * (COLCON_WASM_CHROMIUM, default /usr/bin/chromium); nothing is downloaded.
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

const TYPES = {
  '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript',
  '.wasm': 'application/wasm', '.json': 'application/json',
};
/** A policy that allows scripts from the server and wasm, but no eval. */
const NO_EVAL_POLICY = "script-src 'self' 'wasm-unsafe-eval'";
const ROUTE_KINDS = ['--route', '--plain', '--no-eval'];
const ROUTES = [];
const argv = process.argv.slice(2);
for (let i = 0; i < argv.length; i += 2) {
  const [prefix, dir] = (argv[i + 1] || '').split('=');
  if (!ROUTE_KINDS.includes(argv[i]) || !prefix || !dir) {
    process.stderr.write('usage: node browser_driver.mjs --route /prefix/=DIR... [--plain|--no-eval /prefix/=DIR]...\n');
    process.exit(2);
  }
  ROUTES.push([prefix, path.resolve(dir), argv[i] !== '--plain', argv[i] === '--no-eval']);
}

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
  const [prefix, dir, isolated, noEval] = route;
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
  if (noEval) headers['Content-Security-Policy'] = NO_EVAL_POLICY;
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
  const note = (line) => {
    console.push(line);
    // BROWSER_DRIVER_LOG=1 streams the page's console to stderr (bench progress).
    if (process.env.BROWSER_DRIVER_LOG) process.stderr.write(`${line}\n`);
  };
  page.on('console', (m) => note(`${m.type()}: ${m.text()}`));
  page.on('pageerror', (e) => note(`pageerror: ${e.message}`));
  await page.goto(url);
  await page.waitForFunction('window.pageReady === true', null, { timeout: 30000 });
  return { page, console };
}

async function handle(msg) {
  if (msg.cmd !== 'evaluate') throw new Error(`unknown command ${JSON.stringify(msg.cmd)}`);
  const { page, console } = await openPage(new URL(msg.url, base).href);
  try {
    return {
      status: await page.textContent('#status'),
      isolated: await page.evaluate('crossOriginIsolated'),
      value: msg.expr ? await page.evaluate(msg.expr) : null,
      console,
    };
  } finally {
    await page.close();
  }
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
