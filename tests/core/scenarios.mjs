// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Core test scenarios, the same code in Node.js (run_scenario.mjs) and in
 * headless Chromium (page.html). Each scenario starts test nodes
 * (core_node.js roles) on one Runtime, drives them, and returns what it
 * observed; the pytest tests assert on that.
 *
 * Observations per process: exit {code, crashed, reason}, `results` (the
 * key=value pairs of its "RESULT" lines), `messages` ("MESSAGE" lines),
 * `lines` (all log lines, capped).
 *
 * Over 500 lines on purpose: one table of scenarios that page.html and
 * run_scenario.mjs import as a whole, so that Node.js and Chromium run the
 * same code.
 */

const MAX_LINES = 400;

/** Start core_node with a role; resolves when spawned. */
async function start(ctx, name, role, opts = {}, extra = {}) {
  const args = [role];
  for (const [k, v] of Object.entries(opts)) args.push(`--${k}`, String(v));
  args.push(...(extra.args || []));
  const rec = { exit: null, results: {}, messages: [], lines: [], waiters: [] };
  ctx.procs[name] = rec;
  const proc = await ctx.rt.spawn({
    url: ctx.exe,
    args,
    name,
    env: extra.env || {},
    stdin: extra.stdin,
    files: extra.files,
    onLog: ({ text, severity, stream }) => {
      if (rec.lines.length < MAX_LINES) rec.lines.push({ stream, severity, text });
      if (extra.onText) extra.onText(text);
      if (text.startsWith('RESULT ')) {
        for (const kv of text.slice(7).split(' ')) {
          const eq = kv.indexOf('=');
          if (eq > 0) rec.results[kv.slice(0, eq)] = kv.slice(eq + 1);
        }
      } else if (text.startsWith('MESSAGE ')) {
        rec.messages.push(text.slice(8));
      }
      for (const w of [...rec.waiters]) {
        if (w.key in rec.results) {
          rec.waiters.splice(rec.waiters.indexOf(w), 1);
          w.resolve(rec.results[w.key]);
        }
      }
    },
    onExit: (e) => {
      rec.exit = e;
      for (const w of rec.waiters) w.reject(new Error(`${name} exited (${e.reason || e.code}) before reporting '${w.key}'; log: ${rec.lines.map((l) => l.text).join(' | ')}`));
      rec.waiters.length = 0;
    },
  });
  rec.proc = proc;
  return proc;
}

/** Resolve when process `name` reported RESULT key=... */
function result(ctx, name, key, timeoutMs = 30000) {
  const rec = ctx.procs[name];
  if (key in rec.results) return Promise.resolve(rec.results[key]);
  if (rec.exit) return Promise.reject(new Error(`${name} already exited without '${key}'`));
  return new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`${name} did not report '${key}' within ${timeoutMs} ms; log: ${rec.lines.map((l) => l.text).join(' | ')}`)), timeoutMs);
    rec.waiters.push({
      key,
      resolve: (v) => { clearTimeout(timer); resolve(v); },
      reject: (e) => { clearTimeout(timer); reject(e); },
    });
  });
}

async function exits(ctx, names, timeoutMs = 60000) {
  let timer;
  const all = Promise.all(names.map((n) => ctx.procs[n].proc.exited));
  const timeout = new Promise((_, reject) => {
    timer = setTimeout(() => reject(new Error(`processes ${names.join(', ')} did not all exit within ${timeoutMs} ms`)), timeoutMs);
  });
  try {
    await Promise.race([all, timeout]);
  } finally {
    clearTimeout(timer);
  }
}

/**
 * Two publishers feed a survivor; the victim fails after 3000 messages by
 * core_node's `failOption` (abort-after, trap-after). Records the graph once
 * the victim has exited, then waits for the survivor to go on.
 */
async function victimFailsMidStream(ctx, failOption) {
  await start(ctx, 'survivor', 'survivor', { publishers: 2, after: 2000 });
  await start(ctx, 'other', 'pub', { topic: '/stream', count: -1, tag: 2, 'period-us': 100, name: 'other' });
  await start(ctx, 'victim', 'pub', { topic: '/stream', count: -1, tag: 1, 'period-us': 100, [failOption]: 3000, name: 'victim' });
  await ctx.procs.victim.proc.exited;
  ctx.extra.graph_after = ctx.rt.graph().nodes.map((n) => n.name).sort();
  await result(ctx, 'survivor', 'continued');
  await exits(ctx, ['survivor']);
  await ctx.procs.other.proc.stop();
}

/** Resolve when pred(rt.graph()) holds (woken by graph changes, no polling). */
function waitGraph(rt, pred, timeoutMs = 20000) {
  if (pred(rt.graph())) return Promise.resolve();
  return new Promise((resolve, reject) => {
    const timer = setTimeout(() => {
      off();
      reject(new Error(`graph condition not met within ${timeoutMs} ms: ${JSON.stringify(rt.graph())}`));
    }, timeoutMs);
    const off = rt.onGraphChange((g) => {
      if (pred(g)) {
        clearTimeout(timer);
        off();
        resolve();
      }
    });
  });
}

/** A counter whose `reached(n)` promise resolves once add() brought it to n. */
function counter() {
  const c = { value: 0, waiters: [] };
  c.add = (n) => {
    c.value += n;
    for (const w of [...c.waiters]) {
      if (c.value >= w.n) {
        c.waiters.splice(c.waiters.indexOf(w), 1);
        w.resolve();
      }
    }
  };
  c.reached = (n, timeoutMs = 20000) => (c.value >= n ? Promise.resolve() : new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`counter stuck at ${c.value} of ${n}`)), timeoutMs);
    c.waiters.push({ n, resolve: () => { clearTimeout(timer); resolve(); } });
  }));
  return c;
}

function summary(ctx) {
  const out = {};
  for (const [name, rec] of Object.entries(ctx.procs)) {
    out[name] = { exit: rec.exit, results: rec.results, messages: rec.messages, lines: rec.lines.map((l) => `${l.severity} ${l.text}`) };
  }
  return out;
}

const SCENARIOS = {
  /** 100 000 messages between two node workers, lossless and in order. */
  async lossless(ctx) {
    await start(ctx, 'sub', 'sub', { qos: 'keep_all', count: 100000, size: 64 });
    await start(ctx, 'pub', 'pub', { qos: 'keep_all', count: 100000, size: 64, 'keep-all-depth': 256 });
    await exits(ctx, ['sub', 'pub']);
  },

  /**
   * Messages of changing sizes (grow, shrink, grow past the last buffer),
   * all taken after the publisher finished, into one reused Message.
   */
  async varying_sizes(ctx) {
    await start(ctx, 'sub', 'sub', { qos: 'keep_all', count: 600, 'wait-signal': '/test/sizes_done' });
    await start(ctx, 'pub', 'pub', {
      qos: 'keep_all', count: 600, sizes: '16,5000,8,70000,300,1500,69999,9', 'keep-all-depth': 1024, signal: '/test/sizes_done',
    });
    await exits(ctx, ['sub', 'pub']);
  },

  /**
   * Messages of 1-3 MiB, all held until the publisher finished: the bus grows
   * past its initial 16 MiB while nodes copy into it and out of it (with
   * memory.copy where the bus is a WebAssembly.Memory).
   */
  async large_messages(ctx) {
    const before = ctx.rt.bus.byteLength();
    await start(ctx, 'sub', 'sub', { qos: 'keep_all', count: 12, 'wait-signal': '/test/large_done' });
    await start(ctx, 'pub', 'pub', {
      qos: 'keep_all', count: 12, sizes: '3000000,1048577,3145728', 'keep-all-depth': 16, signal: '/test/large_done',
    });
    await exits(ctx, ['sub', 'pub']);
    ctx.extra.bus = { memory: ctx.rt.bus.memory !== null, bytes_before: before, bytes_after: ctx.rt.bus.byteLength() };
    ctx.extra.memory_copy = { pub: ctx.procs.pub.proc.memoryCopy, sub: ctx.procs.sub.proc.memoryCopy };
  },

  /** One publisher fans out to 4 subscribers. */
  async fanout(ctx) {
    const subs = ['s1', 's2', 's3', 's4'];
    for (const s of subs) await start(ctx, s, 'sub', { qos: 'keep_all', count: 2000, size: 256, name: s });
    await start(ctx, 'pub', 'pub', { qos: 'keep_all', count: 2000, size: 256, 'wait-matched': 4 });
    await exits(ctx, [...subs, 'pub']);
  },

  /** A slow KEEP_LAST(5) reader receives the newest 5. */
  async keep_last(ctx) {
    await start(ctx, 'sub', 'sub', { qos: 'keep_last:5', count: -1, drain: 1, 'wait-signal': '/test/done' });
    await start(ctx, 'pub', 'pub', { qos: 'keep_last:10', count: 20, signal: '/test/done' });
    await exits(ctx, ['sub', 'pub']);
  },

  /** A TRANSIENT_LOCAL late joiner receives the history. */
  async transient_local(ctx) {
    await start(ctx, 'pub', 'pub', { qos: 'transient_local:5', count: 10, 'wait-matched': 0, hold: 1 });
    await result(ctx, 'pub', 'published');
    await start(ctx, 'late', 'sub', { qos: 'transient_local:10', count: 5, 'timeout-ms': 10000 });
    await result(ctx, 'late', 'received');
    await start(ctx, 'volatile', 'sub', { count: 1, 'timeout-ms': 300 });
    await exits(ctx, ['late', 'volatile']);
    await ctx.procs.pub.proc.stop();
  },

  /** 50 concurrent requests from 5 clients each receive their own response. */
  async services(ctx) {
    await start(ctx, 'server', 'server', { count: 50 });
    const clients = [1, 2, 3, 4, 5].map((i) => `client${i}`);
    await Promise.all(clients.map((c, i) => start(ctx, c, 'client', { requests: 10, tag: i + 1, name: c })));
    await exits(ctx, [...clients, 'server']);
  },

  /** A wait is woken by a publish, and a timed wait times out on time. */
  async wait(ctx) {
    await start(ctx, 'waiter', 'waiter', { 'timeout-ms': 200, topic: '/wake' });
    await result(ctx, 'waiter', 'ready_for_wake');
    await start(ctx, 'waker', 'pub', { topic: '/wake', count: 1 });
    await exits(ctx, ['waiter', 'waker']);
  },

  /** An incompatible QoS pair does not match, and both sides get events. */
  async incompatible(ctx) {
    await start(ctx, 'pub', 'incompat', { side: 'pub', qos: 'best_effort', 'wait-signal': '/test/sub_done' });
    await start(ctx, 'sub', 'incompat', { side: 'sub', signal: '/test/sub_done' });
    await exits(ctx, ['pub', 'sub']);
  },

  /** A node's worker is terminated mid-stream: the graph is updated, the others go on. */
  async kill(ctx) {
    await start(ctx, 'survivor', 'survivor', { publishers: 2, after: 2000 });
    await start(ctx, 'victim', 'pub', { topic: '/stream', count: -1, tag: 1, 'period-us': 100, name: 'victim' });
    await start(ctx, 'other', 'pub', { topic: '/stream', count: -1, tag: 2, 'period-us': 100, name: 'other' });
    await result(ctx, 'survivor', 'receiving_from');
    const before = ctx.rt.graph().nodes.map((n) => n.name).sort();
    await ctx.procs.victim.proc.stop();
    const after = ctx.rt.graph().nodes.map((n) => n.name).sort();
    await result(ctx, 'survivor', 'continued');
    await exits(ctx, ['survivor']);
    await ctx.procs.other.proc.stop();
    ctx.extra.graph_before = before;
    ctx.extra.graph_after = after;
  },

  /** A node crashes (abort) mid-stream: reported with a reason, the others go on. */
  async crash(ctx) {
    await victimFailsMidStream(ctx, 'abort-after');
  },

  /** A node's main() traps (an invalid instruction): reported crashed, the other goes on. */
  async trap(ctx) {
    await victimFailsMidStream(ctx, 'trap-after');
  },

  /** A KEEP_ALL publisher blocked on a reader that dies goes on. */
  async blocked_writer(ctx) {
    await start(ctx, 'reader', 'sub', { qos: 'keep_all', count: 1, 'wait-signal': '/test/never', topic: '/blocked' });
    await start(ctx, 'writer', 'pub', { qos: 'keep_all', count: 200, topic: '/blocked', 'keep-all-depth': 16, 'publish-timeout-ms': 60000, 'progress-at': 15 });
    await result(ctx, 'writer', 'progress');
    const t0 = performance.now();
    await new Promise((r) => setTimeout(r, 300));
    ctx.extra.writer_blocked = !('published' in ctx.procs.writer.results);
    await ctx.procs.reader.proc.stop();
    await exits(ctx, ['writer']);
    ctx.extra.unblocked_ms = performance.now() - t0;
  },

  /** Oversized and malformed input get a clear error; the bus is not corrupted. */
  async errors(ctx) {
    await start(ctx, 'errors', 'errors', {});
    await exits(ctx, ['errors']);
    const tools = await ctx.rt.tools();
    const caught = {};
    const attempt = async (key, fn) => {
      try {
        await fn();
        caught[key] = null;
      } catch (e) {
        caught[key] = { name: e.name, code: e.code, message: e.message };
      }
    };
    await attempt('string_payload', () => tools.publish({ topic: '/errors_js', type: 'test_msgs/msg/Bytes' }, 'not bytes'));
    await attempt('bad_topic', () => tools.publish({ topic: 'bad topic', type: 'test_msgs/msg/Bytes' }, new Uint8Array(4)));
    await attempt('bad_qos', () => tools.publish({ topic: '/errors_js', type: 'test_msgs/msg/Bytes', qos: { reliability: 'sometimes' } }, new Uint8Array(4)));
    await attempt('oversized', () => tools.publish({ topic: '/errors_js', type: 'test_msgs/msg/Bytes' }, new Uint8Array(ctx.rt.bus.maxMessage + 1)));
    // After all that, a normal round trip through the JS tools still works.
    const got = [];
    const arrived = counter();
    const sub = await tools.subscribe({ topic: '/errors_js_ok', type: 'test_msgs/msg/Bytes' }, (batch) => {
      got.push(...batch);
      arrived.add(batch.length);
    });
    await tools.publish({ topic: '/errors_js_ok', type: 'test_msgs/msg/Bytes' }, Uint8Array.of(1, 2, 3));
    await arrived.reached(1);
    await sub.close();
    ctx.extra.js_errors = caught;
    ctx.extra.js_roundtrip = got.map((m) => Array.from(m.data));
  },

  /** A pthread that logs while the main thread waits does not deadlock. */
  async threads(ctx) {
    await start(ctx, 'threads', 'threads', {});
    await exits(ctx, ['threads']);
  },

  /** New-message callbacks. */
  async callbacks(ctx) {
    await start(ctx, 'callbacks', 'callbacks', {});
    await exits(ctx, ['callbacks']);
  },

  /** Graph queries from C++ and from the runtime; duplicate node names warn. */
  async graph(ctx) {
    await start(ctx, 'peer', 'graph', { name: 'peer', 'wait-signal': '/test/graph_done' });
    await result(ctx, 'peer', 'nodes');
    await start(ctx, 'grapher', 'graph', { 'want-pubs': 2, signal: '/test/graph_done', ns: '/' });
    await exits(ctx, ['grapher', 'peer']);
    await start(ctx, 'dup1', 'graph', { name: 'twin', 'wait-signal': '/test/twin_done' });
    await result(ctx, 'dup1', 'nodes');
    await start(ctx, 'dup2', 'graph', { name: 'twin', signal: '/test/twin_done', 'want-pubs': 2 });
    await exits(ctx, ['dup1', 'dup2']);
  },

  /** Runtime graph snapshot and change notifications (never blocking). */
  async runtime_graph(ctx) {
    const seen = [];
    const off = ctx.rt.onGraphChange((g) => seen.push(g.nodes.map((n) => n.name)));
    await start(ctx, 'peer', 'graph', { name: 'peer', 'wait-signal': '/test/rg_done' });
    await result(ctx, 'peer', 'nodes');
    const g = ctx.rt.graph();
    const tools = await ctx.rt.tools();
    await tools.publish({ topic: '/test/rg_done', type: 'test_msgs/msg/Signal', qos: { durability: 'transient_local', depth: 1 } }, Uint8Array.of(1));
    await exits(ctx, ['peer']);
    await waitGraph(ctx.rt, (graph) => !graph.nodes.some((n) => n.name === 'peer'));
    off();
    ctx.extra.snapshot = {
      nodes: g.nodes.map((n) => `${n.namespace}|${n.name}|${n.process}`),
      topics: g.topics.map((t) => `${t.name}|${t.types.join('+')}|${t.publishers.length}|${t.subscriptions.length}`),
      services: g.services.map((s) => `${s.name}|${s.types.join('+')}|${s.servers.length}|${s.clients.length}`),
      qos: (g.topics.find((t) => t.name === '/graph/topic') || { publishers: [{}] }).publishers[0].qos,
    };
    ctx.extra.changes = seen;
    ctx.extra.final_nodes = ctx.rt.graph().nodes.map((n) => n.name);
  },

  /** Deadline and liveliness events, computed lazily (no timers). */
  async deadline(ctx) {
    await start(ctx, 'deadline', 'deadline', {});
    await exits(ctx, ['deadline']);
  },

  /** ignore_local_publications, service/client/event callbacks, the C++ QoS check. */
  async misc(ctx) {
    await start(ctx, 'misc', 'misc', {});
    await exits(ctx, ['misc']);
  },

  /** Separate ROS_DOMAIN_IDs never see each other. */
  async domains(ctx) {
    await start(ctx, 'sub', 'sub', { count: 1, 'timeout-ms': 1500, topic: '/dom' }, { env: { ROS_DOMAIN_ID: '7' } });
    await start(ctx, 'pub', 'pub', { count: 5, topic: '/dom', 'wait-matched': 0, hold: 1 }, { env: { ROS_DOMAIN_ID: '8' } });
    await result(ctx, 'pub', 'published');
    await exits(ctx, ['sub']);
    ctx.extra.domains = ctx.rt.graph().nodes.map((n) => `${n.name}@${n.domain}`).sort();
    await ctx.procs.pub.proc.stop();
  },

  /** The JS tools worker talks to C++ nodes: echo, publish, service call. */
  async tools(ctx) {
    const tools = await ctx.rt.tools();
    const echoed = counter();
    let batches = 0;
    const sub = await tools.subscribe({ topic: '/from_cpp', type: 'test_msgs/msg/Bytes', qos: { history: 'keep_all' } }, (b) => {
      batches++;
      echoed.add(b.length);
    });
    await start(ctx, 'pub', 'pub', { topic: '/from_cpp', count: 500, size: 32, qos: 'keep_all' });
    await start(ctx, 'sub', 'sub', { topic: '/from_js', count: 20, qos: 'keep_all', 'timeout-ms': 20000 });
    await start(ctx, 'server', 'server', { count: 3, tag: 9 });
    const advert = await tools.advertise({ topic: '/from_js', type: 'test_msgs/msg/Bytes', qos: { history: 'keep_all' } });
    await waitGraph(ctx.rt, (g) => g.topics.some((t) => t.name === '/from_js' && t.subscriptions.length > 0));
    for (let i = 0; i < 20; i++) {
      const p = new Uint8Array(16);
      new DataView(p.buffer).setUint32(0, i, true);
      new DataView(p.buffer).setUint32(4, 3, true);
      for (let j = 8; j < 16; j++) p[j] = (i + j) & 255;
      await advert.publish(p);
    }
    const responses = [];
    await result(ctx, 'server', 'serving');
    for (let i = 0; i < 3; i++) {
      const req = new Uint8Array(24);
      new DataView(req.buffer).setUint32(0, 100 + i, true);
      const r = await tools.call({ service: '/echo', type: 'test_msgs/srv/Echo', timeoutMs: 10000 }, req);
      const dv = new DataView(r.data.buffer, r.data.byteOffset, r.data.byteLength);
      responses.push({ index: dv.getUint32(0, true), tag: dv.getUint32(24, true), len: r.data.length });
    }
    await exits(ctx, ['pub', 'sub', 'server']);
    await echoed.reached(500);
    await sub.close();
    ctx.extra.echo_total = echoed.value;
    ctx.extra.echo_batches = batches;
    ctx.extra.responses = responses;
  },
};

SCENARIOS.prestarted_pthreads = async (ctx) => {
  // A warm worker boots the program's pthread pool ahead; its threads work.
  // Three hosts: warm and ready, taken while still warming up, and one that
  // boots no pthread workers (the program starts its own). On a warm worker
  // the pool loads the program when main() settles or a thread starts,
  // whichever comes first: 'ready' starts its thread at once, 'settled'
  // after a first wait on the bus.
  const main = ctx.rt;
  const runOn = async (rt, name, opts = {}) => {
    ctx.rt = rt;
    try {
      const proc = await start(ctx, name, 'threads', opts);
      await exits(ctx, [name]);
      ctx.extra[`${name}_prestarted`] = proc.prestartedPthreadWorkers;
      ctx.extra[`${name}_glue_from_memory`] = proc.glueFromMemory;
      ctx.extra[`${name}_settled_ms`] = proc.settledAt === null ? null : proc.settledAt - proc.spawnedAt;
      ctx.extra[`${name}_started_ms`] = proc.startedAt - proc.spawnedAt;
    } finally {
      ctx.rt = main;
    }
  };
  await main.warm();
  await runOn(main, 'ready');
  // no warm() here: the Runtime booted the next warm worker when 'ready' settled
  await runOn(main, 'settled', { 'wait-first-ms': 300 });
  const early = await ctx.Runtime.create({ maxMessageBytes: 4 * 1024 * 1024, maxBytes: 64 * 1024 * 1024 });
  try {
    await runOn(early, 'warming');
  } finally {
    await early.close();
  }
  const none = await ctx.Runtime.create({ maxMessageBytes: 4 * 1024 * 1024, maxBytes: 64 * 1024 * 1024, warmPthreadWorkers: 0 });
  try {
    await none.warm();
    await runOn(none, 'none');
  } finally {
    await none.close();
  }
};

SCENARIOS.io = async (ctx) => {
  // standard input, files and ROS_NAMESPACE reach the executable
  await start(ctx, 'io', 'io', {}, {
    stdin: '2\n3\nq\n',
    files: { '/cfg/params.yaml': 'talker:\n  ros__parameters:\n    greeting: hi\n' },
    env: { IO_FILE: '/cfg/params.yaml', ROS_NAMESPACE: 'robot1' },
  });
  await start(ctx, 'io_ns', 'io', {}, { env: { ROS_NAMESPACE: '/robot2' } });
  await start(ctx, 'io_own_ns', 'io', {}, {
    args: ['--ros-args', '-r', '__ns:=/mine'], env: { ROS_NAMESPACE: '/ignored' } });
  await exits(ctx, ['io', 'io_ns', 'io_own_ns']);
};

SCENARIOS.stdin_pipe = async (ctx) => {
  // an open standard input: lines arrive while the program runs, a write
  // larger than the pipe waits for the reader, close gives end of file
  const texts = []; // every line (rec.lines is capped)
  const watchers = new Set(); // checks re-run on every line and at exit
  const recheck = () => {
    for (const watcher of [...watchers]) watcher();
  };
  const proc = await start(ctx, 'lines', 'lines', {}, {
    stdin: true,
    onText: (t) => {
      texts.push(t);
      recheck();
    },
  });
  const rec = ctx.procs.lines;
  proc.exited.then(recheck);
  // resolve with the first line starting with `text`, driven by log lines
  const seen = (text, timeoutMs = 20000) => new Promise((resolve, reject) => {
    const log = () => texts.join(' | ');
    const done = () => {
      clearTimeout(timer);
      watchers.delete(check);
    };
    const check = () => {
      const line = texts.find((t) => t.startsWith(text));
      if (line !== undefined) {
        done();
        resolve(line);
      } else if (rec.exit) {
        done();
        reject(new Error(`lines exited before printing '${text}': ${log()}`));
      }
    };
    const timer = setTimeout(() => {
      done();
      reject(new Error(`no '${text}' within ${timeoutMs} ms: ${log()}`));
    }, timeoutMs);
    watchers.add(check);
    check();
  });
  ctx.extra.threads = (await seen('READY')).endsWith('threads=1');
  // a thread prints while main() sleeps in read(): its printf is proxied to main
  if (ctx.extra.threads) await seen('THREAD 2');
  await proc.writeStdin('first line\n');
  await seen('LINE 1 first line');
  ctx.extra.before_close = rec.exit === null;
  // 3000 lines of 40 bytes: twice the pipe's 64 KiB
  const big = Array.from({ length: 3000 }, (_, i) => `row ${String(i).padStart(35, '0')}`).join('\n') + '\n';
  await proc.writeStdin(big);
  await proc.writeStdin(new TextEncoder().encode('last\n'));
  await proc.closeStdin();
  await exits(ctx, ['lines']);
  const got = texts.filter((t) => t.startsWith('LINE ') || t.startsWith('EOF '));
  ctx.extra.line_count = got.length;
  ctx.extra.in_order = got.slice(1, 3001).every((t, i) => t === `LINE ${i + 2} row ${String(i).padStart(35, '0')}`);
  ctx.extra.tail = got.slice(-2);
  try {
    await proc.writeStdin('too late\n');
    ctx.extra.late_write = 'accepted';
  } catch (e) {
    ctx.extra.late_write = e.message;
  }
};

/** Names of all scenarios. */
export const names = Object.keys(SCENARIOS);

/**
 * Run one scenario on a fresh Runtime.
 * @param {string} name
 * @param {object} env {Runtime, exe: URL or path of core_node.js}
 * @returns {Promise<object>} {ok, error, processes, extra}
 */
export async function run(name, env) {
  const fn = SCENARIOS[name];
  if (!fn) throw new Error(`unknown scenario '${name}' (known: ${names.join(', ')})`);
  const rt = await env.Runtime.create({ maxMessageBytes: env.maxMessageBytes || 4 * 1024 * 1024, maxBytes: 256 * 1024 * 1024 });
  const ctx = { rt, Runtime: env.Runtime, exe: env.exe, procs: {}, extra: {} };
  const t0 = performance.now();
  let error = null;
  try {
    await fn(ctx);
  } catch (e) {
    error = e && e.stack ? e.stack : String(e);
  }
  const ms = performance.now() - t0;
  await rt.close();
  return { ok: !error, error, ms, processes: summary(ctx), extra: ctx.extra };
}
