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
 * is ready), prints one JSON line per run. Two kinds of runs measure
 * Chromium's WebSocket alone, to a server of this script (what a page can
 * do at all, with no Zenoh in the way):
 * - {"ceiling": BYTES}: the page sends BYTES in 64 KiB binary messages, as
 *   fast as it can; the server counts the bytes that come (MB/s);
 * - {"wsLatency": {size, count, rateHz}}: a worker of the page (as the
 *   gateway's) sends paced messages that start with their send time; the
 *   server reads it from each frame as it comes (one-way p50/p99, ms).
 */

import { createServer } from 'node:http';
import { createInterface } from 'node:readline';

import { acceptKey } from '../../packages/wasm_js/src/bridges/rosbridge/ws_node.mjs';

// tests/js's Chromium launcher (its playwright-core: npm ci there; it downloads no browser)
const { launchChromium } = await import(new URL('../../tests/js/chromium.mjs', import.meta.url).href);

const options = JSON.parse(process.argv[2]);
const lines = createInterface({ input: process.stdin })[Symbol.asyncIterator]();

/**
 * A WebSocket server that counts the bytes it receives and, with `stamps`,
 * reads the float64 (ms since the epoch) each binary frame starts with:
 * now minus it, per frame (a client's frames are masked).
 */
async function countingServer(stamps = null) {
  const counted = { bytes: 0, first: 0, last: 0 };
  const server = createServer((request, response) => response.end());
  server.on('upgrade', (request, socket) => {
    socket.setNoDelay(true);
    socket.write('HTTP/1.1 101 Switching Protocols\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n'
      + `Sec-WebSocket-Accept: ${acceptKey(request.headers['sec-websocket-key'])}\r\n\r\n`);
    let pending = Buffer.alloc(0);
    socket.on('data', (chunk) => {
      counted.last = performance.now();
      if (!counted.first) counted.first = counted.last;
      counted.bytes += chunk.length;
      if (!stamps) return;
      const now = performance.timeOrigin + counted.last;
      pending = pending.length ? Buffer.concat([pending, chunk]) : chunk;
      for (;;) {
        if (pending.length < 2) break;
        let length = pending[1] & 127;
        let at = 2;
        if (length === 126) [length, at] = pending.length < 4 ? [-1, 0] : [pending.readUInt16BE(2), 4];
        else if (length === 127) [length, at] = pending.length < 10 ? [-1, 0] : [Number(pending.readBigUInt64BE(2)), 10];
        if (length < 0 || pending.length < at + 4 + length) break;
        if ((pending[0] & 15) === 2 && length >= 8) {
          const stamp = Buffer.alloc(8);
          for (let i = 0; i < 8; i++) stamp[i] = pending[at + 4 + i] ^ pending[at + (i & 3)];
          stamps.push(now - stamp.readDoubleLE(0));
        }
        pending = pending.subarray(at + 4 + length);
      }
    });
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  return { server, counted, port: server.address().port };
}

/** Paced messages from a worker of the page to the server: their one-way latency p50/p99 (ms). */
async function wsLatency(page, { size, count, rateHz }) {
  const stamps = [];
  const { server, port } = await countingServer(stamps);
  try {
    await page.evaluate(async ({ port, size, count, rateHz }) => {
      const send = async (port, size, count, rateHz) => {
        const ws = new WebSocket(`ws://127.0.0.1:${port}/`);
        await new Promise((resolve, reject) => { ws.onopen = resolve; ws.onerror = reject; });
        const data = new Uint8Array(size);
        const stamp = new Float64Array(data.buffer, 0, 1);
        const t0 = performance.now();
        for (let i = 0; i < count; i++) {
          stamp[0] = performance.timeOrigin + performance.now();
          ws.send(data);
          const wait = t0 + ((i + 1) * 1000) / rateHz - performance.now();
          if (wait > 0) await new Promise((resolve) => setTimeout(resolve, wait));
        }
        ws.close();
      };
      const blob = new Blob([`onmessage = async (e) => postMessage(await (${send})(...e.data));`], { type: 'text/javascript' });
      const worker = new Worker(URL.createObjectURL(blob));
      await new Promise((resolve) => { worker.onmessage = resolve; worker.postMessage([port, size, count, rateHz]); });
      worker.terminate();
    }, { port, size, count, rateHz });
    await new Promise((resolve) => setTimeout(resolve, 500));
    const sorted = [...stamps].sort((a, b) => a - b);
    const pick = (q) => sorted[Math.min(sorted.length - 1, Math.floor(q * sorted.length))];
    return { received: sorted.length, p50: pick(0.5), p99: pick(0.99) };
  } finally {
    server.close();
  }
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

const browser = await launchChromium(options.chromium);
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
    if (run.wsLatency) {
      console.log(JSON.stringify({ run, ...(await wsLatency(page, run.wsLatency)) }));
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
