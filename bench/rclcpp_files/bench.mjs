// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * bench/rclcpp's measurements, the same code in Node.js (run_node.mjs) and in
 * Chromium (page.html): rclcpp nodes on rmw_wasm_cpp (the probe executable of
 * tests/rmw/rmw_wasm_cpp_node_tests) next to the bare core (bench_node of
 * bench/transport_files), in one run.
 *
 * Latency is measured as in bench/transport: ping publishes, pong echoes,
 * ping waits for the echo; one-way latency = round trip / 2.
 */

// Served at /transport_files/ in Chromium (bench/rclcpp's routes).
import { measureNodeStart } from '../transport_files/node_start.mjs';

/** Samples per latency measurement. */
const COUNTS = { string: 1000, image: 200 };
/**
 * Round trips before measuring, the same for rclcpp and the core: with 50,
 * V8 was still tiering up inside the measurement (slow samples at the same
 * round trips run after run; see docs/performance.md on bench/transport).
 */
const WARMUP = { string: 2000, image: 200 };

function parseResults(text, into) {
  const at = text.indexOf('RESULT ');
  if (at < 0) return;
  for (const kv of text.slice(at + 7).split(' ')) {
    const eq = kv.indexOf('=');
    if (eq > 0) into[kv.slice(0, eq)] = Number(kv.slice(eq + 1));
  }
}

class Bench {
  constructor(env) {
    /** {Runtime, probe: exe of probe, core: exe of bench_node} */
    this.env = env;
  }

  async runtime() {
    return this.env.Runtime.create({ maxMessageBytes: 4 * 1024 * 1024, maxBytes: 1024 * 1024 * 1024 });
  }

  /** Start an executable; resolves {proc, results, wait(key), line(text)}. */
  async spawn(rt, url, args, name) {
    const results = {};
    const lines = [];
    const waiters = [];
    let exited = null;
    const check = () => {
      for (const w of [...waiters]) {
        const done = w.key ? w.key in results : lines.some((l) => l.includes(w.text));
        if (done) {
          waiters.splice(waiters.indexOf(w), 1);
          w.resolve(w.key ? results[w.key] : true);
        }
      }
    };
    const proc = await rt.spawn({
      url, args, name,
      onLog: ({ text }) => {
        lines.push(text);
        parseResults(text, results);
        check();
      },
      onExit: (e) => {
        exited = e;
        for (const w of waiters) {
          w.reject(new Error(`${name} exited (${e.reason || e.code}): ${lines.slice(-5).join(' | ')}`));
        }
      },
    });
    const waitFor = (w) => new Promise((resolve, reject) => {
      const waiter = { ...w, resolve, reject };
      waiters.push(waiter);
      check(); // what it printed before it exited still counts
      if (exited && waiters.includes(waiter)) {
        waiters.splice(waiters.indexOf(waiter), 1);
        reject(new Error(`${name} exited (${exited.reason || exited.code}): ${lines.slice(-5).join(' | ')}`));
      }
    });
    return {
      proc, results,
      wait: (key) => waitFor({ key }),
      line: (text) => waitFor({ text }),
    };
  }

  /** rclcpp ping/pong over rmw_wasm_cpp. */
  async rclcppLatency(kind) {
    const rt = await this.runtime();
    try {
      const pong = await this.spawn(rt, this.env.probe, [`bench_pong_${kind}`], 'pong');
      await pong.line('READY');
      const ping = await this.spawn(
        rt, this.env.probe, [`bench_ping_${kind}`, String(COUNTS[kind]), String(WARMUP[kind])], 'ping');
      await ping.wait('p99_us');
      return { p50: ping.results.p50_us, p99: ping.results.p99_us, n: ping.results.count };
    } finally {
      await rt.close();
    }
  }

  /** The bare core (wasm_cpp, opaque bytes) with the same payload size. */
  async coreLatency(size, count, warmup) {
    const rt = await this.runtime();
    try {
      const pong = await this.spawn(rt, this.env.core, ['pong', '--size', String(size)], 'core pong');
      const ping = await this.spawn(rt, this.env.core,
        ['ping', '--size', String(size), '--count', String(count), '--warmup', String(warmup)], 'core ping');
      await ping.wait('p99_us');
      await pong.proc.exited;
      return { p50: ping.results.p50_us, p99: ping.results.p99_us, n: ping.results.count };
    } finally {
      await rt.close();
    }
  }

  /** rclcpp RELIABLE KEEP_ALL flood of strings: rate with no loss. */
  async rclcppThroughput(count) {
    const rt = await this.runtime();
    try {
      const sink = await this.spawn(rt, this.env.probe, ['bench_sink', String(count)], 'sink');
      await sink.line('READY');
      const flood = await this.spawn(rt, this.env.probe, ['bench_flood', String(count)], 'flood');
      await sink.wait('msgs_per_s');
      await flood.wait('published');
      return {
        msgsPerS: sink.results.msgs_per_s, lost: sink.results.lost,
        disorder: sink.results.disorder, received: sink.results.received,
      };
    } finally {
      await rt.close();
    }
  }

  /**
   * Node start: spawn() → the first message of bench_hello, seen by the tools
   * worker; on a warm worker (its pthread pool booted ahead), with the shared module.
   */
  async start(url, args, type) {
    const rt = await this.runtime();
    try {
      return await measureNodeStart(rt, { url, args, type });
    } finally {
      await rt.close();
    }
  }
}

function median(values) {
  const s = [...values].sort((a, b) => a - b);
  return s[Math.floor(s.length / 2)];
}

/**
 * Run every measurement; returns a JSON-able object.
 * @param {object} env {Runtime, probe: URL/path of probe.js, core: URL/path of bench_node.js}
 * @param {object} [options] {quick: fewer messages}
 */
export async function runAll(env, options = {}) {
  const b = new Bench(env);
  if (options.quick) {
    COUNTS.string = 200;
    COUNTS.image = 30;
  }
  const result = { latency: {}, throughput: {}, start: {} };
  result.latency.string = await b.rclcppLatency('string');
  // the serialized 32-character std_msgs/String is 4 + 4 + 33 bytes
  result.latency.core_string = await b.coreLatency(41, COUNTS.string, WARMUP.string);
  result.latency.image = await b.rclcppLatency('image');
  // the serialized 512x512 rgba8 Image is about 1 MiB + 60 bytes
  result.latency.core_image = await b.coreLatency(1024 * 1024 + 64, COUNTS.image, WARMUP.image);
  result.throughput.string = await b.rclcppThroughput(options.quick ? 2000 : 20000);
  const rclcpp = [];
  const core = [];
  for (let i = 0; i < 5; i++) {
    rclcpp.push(await b.start(env.probe, ['bench_hello'], 'std_msgs/msg/String'));
    core.push(await b.start(env.core, ['hello'], 'bench/msg/Bytes'));
  }
  result.start = { rclcpp: median(rclcpp), core: median(core), rclcppAll: rclcpp, coreAll: core };
  return result;
}
