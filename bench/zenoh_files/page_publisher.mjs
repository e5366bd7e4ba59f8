// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The page side of bench/zenoh: opens the launcher page of a running
 * `colcon-wasm serve` with `?zenoh=ws/...` in headless Chromium (Debian's,
 * through playwright-core), waits for the gateway, then publishes
 * demo_interfaces/msg/Chatter messages on /bench from the page's tools
 * process: a burst (throughput) and a paced run (latency), each message's
 * text starting with its send time (ns since the epoch) and `|`.
 *
 *   node page_publisher.mjs '{"url", "chromium", "runs": [{"size", "count", "rateHz"}]}'
 *
 * A run with rateHz 0 is a burst (KEEP_ALL RELIABLE: nothing is dropped on
 * the bus). Waits for "go" lines on stdin before each run (the Python side
 * is ready), prints one JSON line per run.
 */

import { createInterface } from 'node:readline';

const modules = new URL('../../tests/js/node_modules/', import.meta.url);
const { chromium } = await import(new URL('playwright-core/index.mjs', modules).href);

const options = JSON.parse(process.argv[2]);
const lines = createInterface({ input: process.stdin })[Symbol.asyncIterator]();
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
  console.log(JSON.stringify({ ready: true }));
  for (const run of options.runs) {
    await lines.next();
    const result = await page.evaluate(async ({ size, count, rateHz }) => {
      const session = window.colconWasm.session;
      const tools = await session.runtime.tools();
      const chatter = (text, n) => {
        const bytes = new TextEncoder().encode(text);
        const len = bytes.length + 1;
        const pad = (4 - ((8 + len) % 4)) % 4;
        const out = new Uint8Array(8 + len + pad + 4);
        const view = new DataView(out.buffer);
        out.set([0, 1, 0, 0]);
        view.setUint32(4, len, true);
        out.set(bytes, 8);
        view.setUint32(8 + len + pad, n, true);
        return out;
      };
      const filler = 'x'.repeat(Math.max(0, size - 24));
      const stamp = () => `${BigInt(Math.round((performance.timeOrigin + performance.now()) * 1e6))}|`;
      const qos = { history: 'keep_all', reliability: 'reliable', durability: 'volatile' };
      if (!window.benchPublisher) {
        window.benchPublisher = await tools.advertise({ topic: '/bench', type: 'demo_interfaces/msg/Chatter', qos });
      }
      const pub = window.benchPublisher;
      const t0 = performance.now();
      if (!rateHz) {
        for (let i = 0; i < count; i += 50) {
          const list = [];
          for (let j = i; j < Math.min(count, i + 50); j++) list.push(chatter(stamp() + filler, j));
          await pub.publishMany(list);
        }
      } else {
        for (let i = 0; i < count; i++) {
          await pub.publish(chatter(stamp() + filler, i));
          const due = t0 + ((i + 1) * 1000) / rateHz;
          const wait = due - performance.now();
          if (wait > 0) await new Promise((r) => setTimeout(r, wait));
        }
      }
      return { seconds: (performance.now() - t0) / 1000, status: session.zenoh.status() };
    }, run);
    console.log(JSON.stringify({ run, ...result }));
  }
} finally {
  await browser.close();
}
process.exit(0); // stdin stays open

