// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * bench/transport's measurements, the same code in Node.js (run_node.mjs)
 * and in Chromium (page.html): our bus (C++ wasm_cpp nodes, the real path),
 * next to a raw SharedArrayBuffer ring (the floor) and the thesis' poll-every-
 * 10-ms postMessage design, in one run.
 */

import { measureNodeStart } from './node_start.mjs';

const SIZES = [64, 1024, 64 * 1024, 1024 * 1024];

/** Latency samples per size (ours and raw ring; the poll design takes ~10 ms each). */
const LATENCY_COUNT = { 64: 2000, 1024: 2000, 65536: 2000, 1048576: 200 };
const POLL_COUNT = 20;
/** Round trips before measuring (JIT warm-up). */
const WARMUP = { 64: 2000, 1024: 2000, 65536: 3000, 1048576: 200 };

function percentile(sorted, p) {
  return sorted[Math.min(sorted.length - 1, Math.floor(p * sorted.length))];
}

function stats(samples) {
  const s = Float64Array.from(samples).sort();
  return { p50: percentile(s, 0.5), p99: percentile(s, 0.99), n: s.length };
}

/** A SharedArrayBuffer ring for raw_ring_worker.mjs: >= bytes of data (power of two). */
function ringBuffer(bytes) {
  let cap = 1024;
  while (cap < bytes) cap *= 2;
  return new SharedArrayBuffer(64 + cap);
}

function parseResults(text, into) {
  if (!text.startsWith('RESULT ')) return;
  for (const kv of text.slice(7).split(' ')) {
    const eq = kv.indexOf('=');
    if (eq > 0) into[kv.slice(0, eq)] = kv.slice(eq + 1);
  }
}

class Bench {
  constructor(env, options = {}) {
    this.env = env;
    this.trace = env.trace || (() => {});
    /** false: the bus is a SharedArrayBuffer even where it could be a WebAssembly.Memory. */
    this.wasmMemory = options.wasmMemory !== false;
    /** Whether the runtimes' buses were WebAssembly.Memory (null until one was created). */
    this.busIsMemory = null;
  }

  /**
   * A runtime for one measurement. Only the node start measure keeps a warm
   * host: a warm worker boots a worker and its pthread pool again after each
   * spawn, which would run beside a latency or throughput measurement.
   */
  async runtime(warmWorkers = 0) {
    const rt = await this.env.Runtime.create({
      maxMessageBytes: 2 * 1024 * 1024, maxBytes: 1024 * 1024 * 1024, warmWorkers, wasmMemory: this.wasmMemory,
    });
    this.busIsMemory = rt.bus.memory !== null;
    return rt;
  }

  /** Spawn a bench_node role; resolves {proc, results, wait(key)}. */
  async spawn(rt, role, opts = {}, extra = {}) {
    const args = [role];
    for (const [k, v] of Object.entries(opts)) args.push(`--${k}`, String(v));
    const results = {};
    const waiters = [];
    const lines = [];
    let exited = null;
    this.trace(`spawn ${role} ${JSON.stringify(opts)}`);
    const proc = await rt.spawn({
      url: this.env.exe,
      args,
      name: `${role}`,
      shareModule: extra.shareModule,
      onLog: ({ text }) => {
        lines.push(text);
        parseResults(text, results);
        for (const w of [...waiters]) {
          if (w.key in results) {
            waiters.splice(waiters.indexOf(w), 1);
            w.resolve(results[w.key]);
          }
        }
      },
      onExit: (e) => {
        this.trace(`${role} exited ${JSON.stringify(e)}`);
        exited = e;
        for (const w of waiters) w.reject(new Error(`${role} exited (${e.reason || e.code}) before '${w.key}': ${lines.join(' | ')}`));
      },
    });
    const wait = (key) => {
      if (key in results) return Promise.resolve(results[key]);
      if (exited) return Promise.reject(new Error(`${role} exited (${exited.reason || exited.code}) without '${key}': ${lines.join(' | ')}`));
      return new Promise((resolve, reject) => waiters.push({ key, resolve, reject }));
    };
    return { proc, results, wait };
  }

  // ------------------------------------------------------------------ ours

  async oursLatency(size) {
    const rt = await this.runtime();
    try {
      const pong = await this.spawn(rt, 'pong', { size });
      const ping = await this.spawn(rt, 'ping', { size, count: LATENCY_COUNT[size], warmup: WARMUP[size], 'settle-ms': 500 });
      await ping.wait('p50_us');
      await Promise.all([ping.proc.exited, pong.proc.exited]);
      return { p50: Number(ping.results.p50_us), p99: Number(ping.results.p99_us), n: Number(ping.results.count) };
    } finally {
      await rt.close();
    }
  }

  async oursThroughput(size, count, subs) {
    const rt = await this.runtime();
    try {
      const sinks = [];
      for (let i = 0; i < subs; i++) sinks.push(await this.spawn(rt, 'sink', { size, count }));
      await Promise.all(sinks.map((s) => s.wait('ready')));
      const flood = await this.spawn(rt, 'flood', { size, count, subs, depth: size >= 65536 ? 32 : 1024 });
      await Promise.all(sinks.map((s) => s.wait('msgs_per_s')));
      await flood.wait('published');
      const rates = sinks.map((s) => Number(s.results.msgs_per_s));
      const disorder = sinks.reduce((a, s) => a + Number(s.results.disorder), 0);
      const received = sinks.reduce((a, s) => a + Number(s.results.received), 0);
      const msgsPerS = Math.min(...rates);
      // How the nodes copied (known once they exited): memory.copy or TypedArray.set().
      const procs = [flood, ...sinks].map((s) => s.proc);
      await Promise.all(procs.map((p) => p.exited));
      const memoryCopy = procs.every((p) => p.memoryCopy);
      return { msgsPerS, bytesPerS: msgsPerS * size, disorder, lost: subs * count - received, memoryCopy };
    } finally {
      await rt.close();
    }
  }

  /** Publish and take cost in one thread (no wake-ups), through the whole C++ → JS path. */
  async oursOps(size) {
    const rt = await this.runtime();
    try {
      const loop = await this.spawn(rt, 'loop', { size, count: 200000 });
      await loop.wait('take_ns');
      await loop.proc.exited;
      return { publishNs: Number(loop.results.publish_ns), takeNs: Number(loop.results.take_ns) };
    } finally {
      await rt.close();
    }
  }

  /**
   * Node start: the first message's source timestamp minus the moment spawn() was called.
   * mode 'cold': a new worker compiles the .wasm itself; 'shared': a new worker
   * instantiates the runtime's compiled module; 'warm': a warm program worker
   * (runtime modules loaded) instantiates the compiled module.
   */
  async oursStart(mode, exe = this.env.exe) {
    const rt = await this.runtime(mode === 'warm' ? 1 : 0);
    try {
      return await measureNodeStart(rt, { url: exe, args: ['hello'], type: 'bench/msg/Bytes', shareModule: mode !== 'cold' });
    } finally {
      await rt.close();
    }
  }

  // ------------------------------------------------------------------ raw ring

  async rawWorkers(n) {
    const workers = [];
    for (let i = 0; i < n; i++) {
      workers.push(await this.env.ProgramWorker.start(new URL('raw_ring_worker.mjs', this.env.here).href, { type: 'module', name: 'raw ring' }));
    }
    return workers;
  }

  static reply(worker) {
    return new Promise((resolve, reject) => {
      worker.on('message', resolve);
      worker.on('error', (e) => reject(new Error(e.message)));
    });
  }

  async rawLatency(size) {
    const rings = [ringBuffer(4 * (size + 8)), ringBuffer(4 * (size + 8))];
    const [a, b] = await this.rawWorkers(2);
    try {
      const pongDone = Bench.reply(b);
      const pingDone = Bench.reply(a);
      // The same settling time as ours before measuring.
      await new Promise((r) => setTimeout(r, 500));
      b.postMessage({ role: 'pong', rings, size });
      a.postMessage({ role: 'ping', rings, size, count: LATENCY_COUNT[size], warmup: WARMUP[size] });
      const r = await pingDone;
      await pongDone;
      return stats(r.samples);
    } finally {
      await a.terminate();
      await b.terminate();
    }
  }

  async rawThroughput(size, count, subs) {
    // A ring of ~1024 small messages or 32 large ones: the same history as ours.
    const rings = [];
    for (let i = 0; i < subs; i++) rings.push(ringBuffer((size >= 65536 ? 32 : 1024) * (size + 8)));
    const workers = await this.rawWorkers(subs + 1);
    try {
      const sinkDone = workers.slice(1).map((w, i) => {
        const p = Bench.reply(w);
        w.postMessage({ role: 'sink', rings: [rings[i]], size, count });
        return p;
      });
      const floodDone = Bench.reply(workers[0]);
      workers[0].postMessage({ role: 'flood', rings, size, count });
      const sinks = await Promise.all(sinkDone);
      await floodDone;
      const msgsPerS = Math.min(...sinks.map((s) => s.msgsPerS));
      return { msgsPerS, bytesPerS: msgsPerS * size, disorder: sinks.reduce((a, s) => a + s.disorder, 0), lost: 0 };
    } finally {
      for (const w of workers) await w.terminate();
    }
  }

  // ------------------------------------------------------------------ 10 ms poll

  /** The thesis' main-thread broker: a 10-slot LIFO stack per topic. */
  async pollWorkers(configs) {
    const stacks = new Map();
    const workers = [];
    const done = [];
    for (let i = 0; i < configs.length; i++) {
      const w = await this.env.ProgramWorker.start(new URL('poll_worker.mjs', this.env.here).href, { type: 'module', name: 'poll' });
      done.push(new Promise((resolve, reject) => {
        w.on('error', (e) => reject(new Error(`poll worker failed: ${e.message}`)));
        w.on('message', (m) => {
          if (m.cmd === 'publish') {
            const s = stacks.get(m.topic) || [];
            s.push(m.data);
            if (s.length > 10) s.shift();
            stacks.set(m.topic, s);
          } else if (m.cmd === 'retrieve') {
            const s = stacks.get(m.topic);
            w.postMessage({ cmd: 'message', data: s && s.length ? s.pop() : null });
          } else if (m.cmd === 'done') {
            resolve(m);
          }
        });
      }));
      workers.push(w);
    }
    workers.forEach((w, i) => w.postMessage({ cmd: 'start', cfg: configs[i] }));
    try {
      return await Promise.all(done);
    } finally {
      for (const w of workers) await w.terminate();
    }
  }

  async pollLatency(size) {
    const [ping] = await this.pollWorkers([
      { role: 'ping', size, count: POLL_COUNT }, { role: 'pong', size }]);
    return stats(ping.samples);
  }

  async pollThroughput(size, rateHz, durationMs) {
    const [flood, sink] = await this.pollWorkers([
      { role: 'flood', size, rateHz, durationMs }, { role: 'sink', size, durationMs }]);
    return {
      msgsPerS: sink.received / (durationMs / 1000),
      offeredPerS: rateHz,
      lostPct: 100 * (1 - sink.received / flood.published),
      disorder: sink.disorder,
    };
  }
}

/**
 * Run every measurement; returns a JSON-able object.
 * @param {object} env {Runtime, ProgramWorker, exe: URL/path of bench_node.js, here: URL of this folder}
 * @param {object} [options] {quick: fewer/lower counts, parts: what to measure,
 *   wasmMemory: false for a bus that is a SharedArrayBuffer everywhere}
 */
export async function runAll(env, options = {}) {
  const b = new Bench(env, options);
  const out = { latency: { ours: {}, raw: {}, poll: {} }, throughput: {}, start: {} };
  const q = options.quick ? 0.1 : 1;
  const log = env.log || (() => {});
  const parts = options.parts || ['ops', 'latency', 'throughput', 'fanout', 'start'];
  if (parts.includes('ops')) {
    log('publish/take cost');
    out.ops = { 64: await b.oursOps(64), 1024: await b.oursOps(1024) };
  }
  if (parts.includes('latency')) {
    for (const size of SIZES) {
      log(`latency ${size} B`);
      out.latency.ours[size] = await b.oursLatency(size);
      out.latency.raw[size] = await b.rawLatency(size);
      out.latency.poll[size] = await b.pollLatency(size);
    }
  }
  if (parts.includes('throughput')) {
    const n1k = Math.round(300000 * q);
    const n1m = Math.round(400 * q);
    log('throughput 1 KiB');
    out.throughput.ours_1k = await b.oursThroughput(1024, n1k, 1);
    out.throughput.raw_1k = await b.rawThroughput(1024, n1k, 1);
    out.throughput.poll_1k = await b.pollThroughput(1024, 1000, 2000);
    log('throughput 1 MiB');
    out.throughput.ours_1m = await b.oursThroughput(1024 * 1024, n1m, 1);
    out.throughput.raw_1m = await b.rawThroughput(1024 * 1024, n1m, 1);
  }
  if (parts.includes('fanout')) {
    log('fan-out to 4: ours');
    out.throughput.ours_fanout = await b.oursThroughput(1024, Math.round(100000 * q), 4);
    log('fan-out to 4: raw ring');
    out.throughput.raw_fanout = await b.rawThroughput(1024, Math.round(100000 * q), 4);
  }
  if (parts.includes('start')) {
    log('node start');
    const exes = { pthread: env.exe };
    if (env.exeNoPthread) exes.nopthread = env.exeNoPthread;
    for (const [build, exe] of Object.entries(exes)) {
      out.start[build] = {};
      for (const mode of ['cold', 'shared', 'warm']) {
        const samples = [];
        for (let i = 0; i < 5; i++) samples.push(await b.oursStart(mode, exe));
        out.start[build][mode] = stats(samples);
      }
    }
  }
  out.busIsMemory = b.busIsMemory;
  return out;
}
