// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The page side of bench/zenoh: opens the launcher page of a running
 * `colcon-wasm serve` with `?zenoh=ws/...` in headless Chromium (Debian's,
 * through playwright-core), waits for the gateway, starts the C++ node
 * zenoh_bench_nodes/chatter_flood in the page (as a user's node: its own
 * worker on the page's bus) and has it publish demo_interfaces/msg/Chatter
 * on /bench: a burst (throughput) or a paced run (latency), each message's
 * text starting with its send time (ns since the epoch) and `|`, as the
 * Python floor's publisher does.
 *
 *   node page_publisher.mjs '{"url", "chromium", "runs": [{"size", "count", "rateHz"}]}'
 *
 * A run with rateHz 0 is a burst (KEEP_ALL RELIABLE: nothing is dropped on
 * the bus). Waits for a "go" line on stdin before each run (the Python side
 * is ready), prints one JSON line per run. A run {"ceiling": BYTES} instead
 * measures Chromium's WebSocket alone: the page sends BYTES in 64 KiB binary
 * messages, as fast as it can, to a server of this script that only counts
 * them (what a page can send at all, with no Zenoh in the way).
 */

import { createServer } from 'node:http';
import { createInterface } from 'node:readline';

import { acceptKey } from '../../packages/wasm_js/src/bridges/rosbridge/ws_node.mjs';

const modules = new URL('../../tests/js/node_modules/', import.meta.url);
const { chromium } = await import(new URL('playwright-core/index.mjs', modules).href);

const options = JSON.parse(process.argv[2]);
const lines = createInterface({ input: process.stdin })[Symbol.asyncIterator]();

/** A WebSocket server that counts the bytes it receives (frames are not decoded). */
async function countingServer() {
  const counted = { bytes: 0, first: 0, last: 0 };
  const server = createServer((request, response) => response.end());
  server.on('upgrade', (request, socket) => {
    socket.write('HTTP/1.1 101 Switching Protocols\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n'
      + `Sec-WebSocket-Accept: ${acceptKey(request.headers['sec-websocket-key'])}\r\n\r\n`);
    socket.on('data', (chunk) => {
      counted.last = performance.now();
      if (!counted.first) counted.first = counted.last;
      counted.bytes += chunk.length;
    });
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  return { server, counted, port: server.address().port };
}

/** Send `bytes` from the page through a WebSocket to the counting server; its MB/s. */
async function ceiling(page, bytes) {
  const { server, counted, port } = await countingServer();
  try {
    await page.evaluate(async ({ port, bytes }) => {
      const ws = new WebSocket(`ws://127.0.0.1:${port}/`);
      await new Promise((resolve, reject) => { ws.onopen = resolve; ws.onerror = reject; });
      const frame = new Uint8Array(65536);
      for (let sent = 0; sent < bytes; sent += frame.length) ws.send(frame);
      while (ws.bufferedAmount) await new Promise((resolve) => setTimeout(resolve, 5));
      ws.close();
    }, { port, bytes });
    const deadline = Date.now() + 30000;
    while (counted.bytes < bytes && Date.now() < deadline) await new Promise((resolve) => setTimeout(resolve, 20));
    return { bytes: counted.bytes, mbPerSecond: counted.bytes / ((counted.last - counted.first) / 1000) / 1e6 };
  } finally {
    server.close();
  }
}

const browser = await chromium.launch({
  executablePath: options.chromium,
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
    '--disable-background-networking', '--disable-component-update', '--disable-sync'],
});
try {
  const page = await browser.newPage();
  await page.goto(options.url);
  await page.waitForFunction(() => window.colconWasm && window.colconWasm.session
    && window.colconWasm.session.zenoh && window.colconWasm.session.zenoh.state === 'connected',
  null, { timeout: 60000 });
  const id = await page.evaluate(() => window.colconWasm.session.startProcess('zenoh_bench_nodes', 'chatter_flood', []).id);
  // the first log line of the process from `from` on that has `text`, or why it ended
  const logLine = (text, from) => page.waitForFunction(({ id, text, from }) => {
    const p = window.colconWasm.session.processes.get(id);
    const line = p.log.slice(from).find((l) => l.text.includes(text));
    if (line) return line.text;
    return p.state === 'running' || p.state === 'starting' ? false
      : `chatter_flood ${p.state}: ${p.log.map((l) => l.text).join('\n')}`;
  }, { id, text, from }, { timeout: 300000, polling: 50 }).then((h) => h.jsonValue());
  const ready = await logLine('READY', 0);
  if (!ready.startsWith('READY')) throw new Error(ready);
  console.log(JSON.stringify({ ready: true }));
  for (const run of options.runs) {
    await lines.next();
    if (run.ceiling) {
      console.log(JSON.stringify({ run, ...(await ceiling(page, run.ceiling)) }));
      continue;
    }
    const from = await page.evaluate((id) => window.colconWasm.session.processes.get(id).log.length, id);
    await page.evaluate(({ id, run }) => window.colconWasm.session.sendStdin(id, `${run.size} ${run.count} ${run.rateHz}`), { id, run });
    const result = await logLine('RESULT', from);
    if (!result.startsWith('RESULT')) throw new Error(result);
    const seconds = Number(/seconds=([\d.]+)/.exec(result)[1]);
    console.log(JSON.stringify({ run, seconds, status: await page.evaluate(() => window.colconWasm.session.zenoh.status()) }));
  }
} finally {
  await browser.close();
}
process.exit(0); // stdin stays open
