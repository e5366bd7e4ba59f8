// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Baseline 2 of bench/transport: the thesis' design (000, appendix C.2).
 * Nodes share no memory: a publisher posts each message to the main thread,
 * which keeps the newest 10 per topic (a 10-slot LIFO stack: a full stack
 * drops its oldest); a subscriber asks the main thread for a message every
 * 10 ms and gets the newest one. The broker is `pollBroker` in bench.mjs.
 *
 * Roles (first message {role, size, count, rateHz, durationMs}):
 *   ping  — publish 'ping' i, poll 'pong' until i comes back; report one-way µs
 *   pong  — poll 'ping', publish it back as 'pong', until an empty message
 *   flood — publish `rateHz` messages per second for `durationMs`
 *   sink  — poll 'flood' for `durationMs`, count what arrives
 */

const isNode = typeof process === 'object' && !!(process.versions && process.versions.node) &&
  typeof self === 'undefined';
const port = isNode ? (await import('node:worker_threads')).parentPort : self;
const post = (m) => port.postMessage(m);
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
let pending = null;

function publish(topic, data) {
  post({ cmd: 'publish', topic, data });
}

function retrieve(topic) {
  return new Promise((resolve) => {
    pending = resolve;
    post({ cmd: 'retrieve', topic });
  });
}

function message(index, size) {
  const data = new Uint8Array(Math.max(size, 8));
  new DataView(data.buffer).setUint32(0, index, true);
  return data;
}

const indexOf = (data) => new DataView(data.buffer, data.byteOffset).getUint32(0, true);

async function run(cfg) {
  if (cfg.role === 'ping') {
    const samples = [];
    for (let i = 0; i < cfg.count; i++) {
      const t0 = performance.now();
      publish('ping', message(i, cfg.size));
      for (;;) {
        await sleep(10);
        const m = await retrieve('pong');
        if (m && indexOf(m) === i) break;
      }
      samples.push((performance.now() - t0) * 1000 / 2);
    }
    publish('ping', new Uint8Array(0));
    post({ cmd: 'done', samples });
  } else if (cfg.role === 'pong') {
    for (;;) {
      await sleep(10);
      const m = await retrieve('ping');
      if (!m) continue;
      if (m.length === 0) break;
      publish('pong', m);
    }
    post({ cmd: 'done' });
  } else if (cfg.role === 'flood') {
    const t0 = performance.now();
    let i = 0;
    while (performance.now() - t0 < cfg.durationMs) {
      const due = Math.floor((performance.now() - t0) * cfg.rateHz / 1000);
      for (; i < due; i++) publish('flood', message(i, cfg.size));
      await sleep(1);
    }
    post({ cmd: 'done', published: i });
  } else if (cfg.role === 'sink') {
    const seen = new Set();
    let disorder = 0;
    let last = -1;
    const t0 = performance.now();
    while (performance.now() - t0 < cfg.durationMs + 50) {
      await sleep(10);
      const m = await retrieve('flood');
      if (!m) continue;
      const i = indexOf(m);
      if (i < last) disorder++;
      last = i;
      seen.add(i);
    }
    post({ cmd: 'done', received: seen.size, disorder, seconds: (performance.now() - t0) / 1000 });
  }
}

function onMessage(m) {
  if (m.cmd === 'message') {
    const p = pending;
    pending = null;
    p(m.data);
  } else if (m.cmd === 'start') {
    run(m.cfg);
  }
}

if (isNode) port.on('message', onMessage);
else port.onmessage = (e) => onMessage(e.data);
