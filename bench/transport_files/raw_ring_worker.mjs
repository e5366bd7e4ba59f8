// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Baseline 1 of bench/transport: the floor. A single-producer single-consumer
 * byte ring in a SharedArrayBuffer, woken with Atomics.wait/notify, with the
 * same sleep protocol as the bus (sleeper count, notify only when someone
 * sleeps) and the same copies (producer copies in, consumer copies out into
 * its own buffer). No registry, no QoS, no wasm: what a bus cannot beat.
 *
 * Roles (first message {role, rings, size, count, warmup}):
 *   ping  — write to rings[0], read the echo from rings[1], report one-way µs
 *   pong  — echo rings[0] to rings[1] until an empty message
 *   flood — write `count` messages to every ring in `rings`
 *   sink  — read `count` messages from rings[0], report msgs/s
 */

const isNode = typeof process === 'object' && !!(process.versions && process.versions.node) &&
  typeof self === 'undefined';
const port = isNode ? (await import('node:worker_threads')).parentPort : self;
const post = (m) => port.postMessage(m);

const HEAD = 0; // bytes written (i32, wraps)
const TAIL = 1; // bytes read
const HEAD_SLEEPERS = 2; // consumers sleeping on HEAD
const TAIL_SLEEPERS = 3; // producers sleeping on TAIL
const DATA = 64;

class Ring {
  constructor(sab) {
    this.dv = new DataView(sab);
    this.i32 = new Int32Array(sab, 0, 16);
    this.u8 = new Uint8Array(sab, DATA);
    this.cap = sab.byteLength - DATA; // power of two
    this.mask = this.cap - 1;
  }

  write(src, len) {
    const i32 = this.i32;
    const need = 4 + ((len + 3) & ~3);
    for (;;) {
      const head = Atomics.load(i32, HEAD);
      const tail = Atomics.load(i32, TAIL);
      const pos = head & this.mask;
      const contiguous = this.cap - pos;
      const pad = contiguous < need ? contiguous : 0;
      if (this.cap - ((head - tail) | 0) >= need + pad) {
        if (pad) {
          this.dv.setInt32(DATA + pos, -1, true);
        }
        const at = (head + pad) & this.mask;
        this.dv.setInt32(DATA + at, len, true);
        if (len) this.u8.set(len === src.length ? src : src.subarray(0, len), at + 4);
        Atomics.store(i32, HEAD, (head + pad + need) | 0);
        if (Atomics.load(i32, HEAD_SLEEPERS) > 0) Atomics.notify(i32, HEAD);
        return;
      }
      Atomics.add(i32, TAIL_SLEEPERS, 1);
      Atomics.wait(i32, TAIL, tail);
      Atomics.sub(i32, TAIL_SLEEPERS, 1);
    }
  }

  read(dst) {
    const i32 = this.i32;
    for (;;) {
      const tail = Atomics.load(i32, TAIL);
      const head = Atomics.load(i32, HEAD);
      if (head !== tail) {
        let pos = tail & this.mask;
        let len = this.dv.getInt32(DATA + pos, true);
        let skip = 0;
        if (len === -1) {
          skip = this.cap - pos;
          pos = 0;
          len = this.dv.getInt32(DATA, true);
        }
        if (len) dst.set(this.u8.subarray(pos + 4, pos + 4 + len));
        Atomics.store(i32, TAIL, (tail + skip + 4 + ((len + 3) & ~3)) | 0);
        if (Atomics.load(i32, TAIL_SLEEPERS) > 0) Atomics.notify(i32, TAIL);
        return len;
      }
      Atomics.add(i32, HEAD_SLEEPERS, 1);
      Atomics.wait(i32, HEAD, head);
      Atomics.sub(i32, HEAD_SLEEPERS, 1);
    }
  }
}

function onMessage(cfg) {
  const rings = cfg.rings.map((sab) => new Ring(sab));
  const size = cfg.size;
  const buf = new Uint8Array(Math.max(size, 8));
  const dv = new DataView(buf.buffer);
  if (cfg.role === 'ping') {
    const samples = [];
    for (let i = 0; i < cfg.warmup + cfg.count; i++) {
      dv.setUint32(0, i, true);
      const t0 = performance.now();
      rings[0].write(buf, size);
      rings[1].read(buf);
      const us = (performance.now() - t0) * 1000 / 2;
      if (dv.getUint32(0, true) !== i) throw new Error(`ping ${i}: wrong echo`);
      if (i >= cfg.warmup) samples.push(us);
    }
    rings[0].write(buf, 0);
    post({ samples });
  } else if (cfg.role === 'pong') {
    let n = 0;
    for (;;) {
      const len = rings[0].read(buf);
      if (!len) break;
      rings[1].write(buf, len);
      n++;
    }
    post({ echoed: n });
  } else if (cfg.role === 'flood') {
    const t0 = performance.now();
    for (let i = 0; i < cfg.count; i++) {
      dv.setUint32(0, i, true);
      for (const r of rings) r.write(buf, size);
    }
    post({ ms: performance.now() - t0 });
  } else if (cfg.role === 'sink') {
    let first = 0;
    let disorder = 0;
    for (let i = 0; i < cfg.count; i++) {
      const len = rings[0].read(buf);
      if (i === 0) first = performance.now();
      if (len !== size || dv.getUint32(0, true) !== i) disorder++;
    }
    const s = (performance.now() - first) / 1000;
    post({ received: cfg.count, disorder, seconds: s, msgsPerS: (cfg.count - 1) / s });
  }
}

if (isNode) port.on('message', onMessage);
else port.onmessage = (e) => onMessage(e.data);

