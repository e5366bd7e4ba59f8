// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Unit checks of the bus internals (wasm_js/src/bus.mjs, bus_client.mjs),
 * driven by tests/test_core_bus.py:
 *
 *   node bus_unit.mjs WASM_JS_SRC_DIR CHECK   -> exit 0 and prints "ok", or throws
 *
 * Several BusClients on one buffer stand for several processes; processes
 * "die" the way the runtime sees it (their record is marked dead).
 */

import assert from 'node:assert/strict';
import path from 'node:path';
import { pathToFileURL } from 'node:url';
import { Worker } from 'node:worker_threads';

const [srcDir, name] = process.argv.slice(2);
const src = (file) => pathToFileURL(path.join(path.resolve(srcDir), file)).href;
const { Bus, BusError, Code, KIND_CLIENT, KIND_PUBLISHER, KIND_SERVICE, KIND_SUBSCRIPTION } = await import(src('bus.mjs'));
const { BusClient, EventType, TakeMode } = await import(src('bus_client.mjs'));
const { ENDPOINT, HEADER, PROCESS, PROC_DEAD, PROC_KIND_NODE, PROC_KIND_RUNTIME } = await import(src('layout.mjs'));
const { checkCompatible, encodeQos, resolveQos, PolicyKind } = await import(src('qos.mjs'));

/** A bus with a runtime process (pid 1) and `n` node processes. */
function world(n, options = {}) {
  const bus = Bus.create(options);
  assert.ok(bus.tryLock(1));
  const runtime = bus.allocProcess(PROC_KIND_RUNTIME);
  const pids = [];
  for (let i = 0; i < n; i++) pids.push(bus.allocProcess(PROC_KIND_NODE));
  bus.unlock(1);
  const clients = pids.map((pid) => new BusClient(Bus.attach(bus.sab), pid));
  return { bus, runtime, clients };
}

function die(bus, pid) {
  Atomics.store(bus.i32, bus.proc(pid) + PROCESS.STATE, PROC_DEAD);
}

function endpoint(c, kind, node, name, qos = {}, extra = {}) {
  return c.createEndpoint({ kind, node, name, type: 'test_msgs/msg/Bytes', qos, ...extra }).index;
}

const bytes = (...v) => Uint8Array.from(v);

const CHECKS = {
  /** A lock held by a dead process is stolen; a live owner's is not. */
  async lock_stolen_from_dead_owner() {
    const { bus, clients: [a, b] } = world(2);
    assert.ok(bus.tryLock(a.pid));
    assert.equal(bus.tryLock(b.pid), false, 'a live owner keeps the lock');
    die(bus, a.pid);
    assert.ok(bus.tryLock(b.pid), 'the lock of a dead owner is stolen');
    bus.unlock(b.pid);
    // The runtime's non-blocking path steals from a dead owner too.
    const c = world(1);
    assert.ok(c.bus.tryLock(c.clients[0].pid));
    die(c.bus, c.clients[0].pid);
    await c.bus.lockAsync(c.runtime);
    c.bus.unlock(c.runtime);
  },

  /** Several non-blocking (main-thread) lockers all get the lock in turn: no lost wake-up. */
  async async_lockers_all_proceed() {
    const { bus, runtime, clients } = world(4);
    assert.ok(bus.tryLock(clients[0].pid));
    const order = [];
    const waiters = [runtime, clients[1].pid, clients[2].pid, clients[3].pid].map(async (pid) => {
      await bus.lockAsync(pid);
      order.push(pid);
      await new Promise((r) => setTimeout(r, 1));
      bus.unlock(pid);
    });
    await new Promise((r) => setTimeout(r, 10));
    assert.deepEqual(order, [], 'nobody gets a held lock');
    bus.unlock(clients[0].pid);
    const timeout = new Promise((_, reject) => setTimeout(() => reject(new Error(`stuck after ${JSON.stringify(order)}`)), 5000));
    await Promise.race([Promise.all(waiters), timeout]);
    assert.equal(order.length, 4);
    assert.equal(Atomics.load(bus.i32, HEADER.LOCK), 0);
  },

  /** A process killed in the middle of a registry change leaves nothing half visible. */
  async killed_mid_mutation_leaves_nothing_half_visible() {
    const { bus, runtime, clients: [a, b] } = world(2);
    const node = a.createNode({ name: 'victim' });
    // `a` takes the lock and writes half an endpoint record, then dies.
    assert.ok(bus.tryLock(a.pid));
    const half = bus.ep(5);
    bus.i32[half + ENDPOINT.KIND] = KIND_PUBLISHER;
    bus.i32[half + ENDPOINT.PID] = a.pid;
    bus.i32[half + ENDPOINT.NODE] = node.index;
    assert.equal(bus.snapshot().endpoints.length, 0, 'no STATE store, nothing visible');
    die(bus, a.pid);
    // The runtime cleans up without blocking: it steals the lock.
    await bus.lockAsync(runtime);
    bus.cleanupProcess(a.pid);
    bus.releaseProcess(a.pid);
    bus.bumpGraph();
    bus.unlock(runtime);
    const g = bus.snapshot();
    assert.deepEqual(g.nodes, [], 'the dead node left the graph');
    // The other process goes on and reuses the slots.
    const n2 = b.createNode({ name: 'survivor' });
    const ep = endpoint(b, KIND_PUBLISHER, n2.index, '/after');
    assert.equal(b.graph().endpoints.length, 1);
    assert.equal(b.graph().endpoints[0].name, '/after');
    assert.ok(ep >= 0);
  },

  /** Messages published just before a writer goes away are still delivered. */
  async zombie_ring_is_drained_then_freed() {
    const { bus, clients: [a, b] } = world(2);
    const na = a.createNode({ name: 'talker' });
    const nb = b.createNode({ name: 'listener' });
    const sub = endpoint(b, KIND_SUBSCRIPTION, nb.index, '/z');
    const pub = endpoint(a, KIND_PUBLISHER, na.index, '/z');
    for (let i = 0; i < 3; i++) a.publish(pub, bytes(i));
    a.destroyEndpoint(pub);
    assert.equal(Atomics.load(bus.i32, bus.ep(pub) + ENDPOINT.STATE), 3, 'a zombie keeps the ring');
    assert.equal(b.matchedCount(sub), 0, 'but it is no longer matched');
    assert.equal(b.graph().endpoints.filter((e) => e.name === '/z').length, 1, 'only the subscription is in the graph');
    const got = [];
    let m;
    while ((m = b.take(sub))) got.push(m[0]);
    assert.deepEqual(got, [0, 1, 2]);
    assert.equal(b.take(sub), null);
    assert.equal(Atomics.load(bus.i32, bus.ep(pub) + ENDPOINT.STATE), 0, 'drained: freed');
  },

  /**
   * While another thread removes a writer (its record is DYING, under the
   * registry lock), a reader that was told "ready" still takes the message.
   */
  async dying_writer_is_still_read() {
    const { bus, clients: [a, b] } = world(2);
    const sub = endpoint(b, KIND_SUBSCRIPTION, b.createNode({ name: 'listener' }).index, '/d');
    const pub = endpoint(a, KIND_PUBLISHER, a.createNode({ name: 'talker' }).index, '/d');
    a.publish(pub, bytes(7));
    assert.ok(b.hasData(sub), 'ready while the writer is alive');
    // The state removeEndpoint() gives the record before it decides ZOMBIE or FREE.
    Atomics.store(bus.i32, bus.ep(pub) + ENDPOINT.STATE, 2);
    assert.ok(b.hasData(sub), 'still ready while the writer is being removed');
    const m = b.take(sub);
    assert.ok(m, 'taken while the writer is being removed');
    assert.equal(m[0], 7);
    assert.equal(b.take(sub), null);
  },

  /** The bus grows (growable SharedArrayBuffer) for large messages; other threads see them. */
  async bus_grows_for_large_messages() {
    const { bus, clients: [a, b] } = world(2, { initialBytes: 4 << 20, maxBytes: 256 << 20, maxMessageBytes: 64 << 20 });
    const before = bus.sab.byteLength;
    const na = a.createNode({ name: 'big' });
    const sub = endpoint(b, KIND_SUBSCRIPTION, b.createNode({ name: 'sink' }).index, '/big', { history: 'keep_all' });
    const pub = endpoint(a, KIND_PUBLISHER, na.index, '/big', { depth: 2 });
    const payload = new Uint8Array(32 << 20);
    for (let i = 0; i < payload.length; i += 4093) payload[i] = i & 255;
    a.publish(pub, payload);
    assert.ok(before < (32 << 20) && bus.sab.byteLength > (32 << 20), `grew from ${before} to ${bus.sab.byteLength}`);
    const got = b.take(sub);
    assert.equal(got.length, payload.length);
    assert.deepEqual(got.subarray(0, 100000), payload.subarray(0, 100000));
    assert.equal(got[32 * 4093], payload[32 * 4093]);
  },

  /**
   * A process whose views predate another's growth of the bus (the tools
   * worker while a camera publishes large frames) creates endpoints and
   * publishes: its rings and blocks lie beyond its views, and nothing is lost.
   */
  async stale_views_after_another_thread_grew_the_bus() {
    const { bus, clients: [a, b, c] } = world(3, { initialBytes: 4 << 20, maxBytes: 256 << 20, maxMessageBytes: 16 << 20 });
    const sink = c.createNode({ name: 'sink' }).index;
    const bigSub = endpoint(c, KIND_SUBSCRIPTION, sink, '/camera', { history: 'keep_all' });
    const camera = endpoint(a, KIND_PUBLISHER, a.createNode({ name: 'camera' }).index, '/camera', { history: 'keep_all' });
    const frame = new Uint8Array(12 << 20).fill(5);
    a.publish(camera, frame);
    assert.ok(bus.byteLength() > b.bus.u8.length, 'b has not seen the growth yet');
    // b makes a node and many endpoints: their records and rings come from
    // the arena's top (beyond b's views) and from freed blocks.
    const nb = b.createNode({ name: 'tools' }).index;
    const subs = [];
    const pubs = [];
    for (let i = 0; i < 40; i++) {
      subs.push(endpoint(c, KIND_SUBSCRIPTION, sink, `/t${i}`, { history: 'keep_all' }));
      pubs.push(endpoint(b, KIND_PUBLISHER, nb, `/t${i}`, { history: 'keep_all' }));
    }
    for (let i = 0; i < pubs.length; i++) b.publish(pubs[i], bytes(i, 1, 2, 3));
    const second = new Uint8Array(1 << 20).fill(9);
    b.publish(pubs[0], second);
    for (let i = 0; i < subs.length; i++) {
      const m = c.take(subs[i]);
      assert.ok(m, `message on /t${i} taken`);
      assert.deepEqual([...m], [i, 1, 2, 3], `/t${i}`);
    }
    const big = c.take(subs[0]);
    assert.equal(big.length, second.length);
    assert.equal(big[big.length - 1], 9);
    assert.equal(c.take(bigSub).length, frame.length);
  },

  /**
   * Copies above the small-copy loop's 512 bytes keep every byte at any
   * alignment, the tail of an odd length included, and write nothing around
   * the destination.
   */
  async large_copies_keep_every_byte() {
    const { clients: [a, b] } = world(2);
    const sub = endpoint(b, KIND_SUBSCRIPTION, b.createNode({ name: 'sink' }).index, '/copy', { history: 'keep_all' });
    const pub = endpoint(a, KIND_PUBLISHER, a.createNode({ name: 'src' }).index, '/copy', { history: 'keep_all' });
    // Wasm heaps of pthread builds are SharedArrayBuffers, like the bus.
    const heap = new Uint8Array(new SharedArrayBuffer(1 << 18));
    for (let i = 0; i < heap.length; i++) heap[i] = (i * 7 + (i >> 8)) & 255;
    const dst = new Uint8Array(new SharedArrayBuffer(1 << 18));
    for (const len of [513, 514, 515, 516, 4097, 65536, 65539]) {
      for (const srcOff of [0, 1, 2, 3, 8]) {
        for (const dstOff of [0, 3, 16]) {
          a.publishFrom(pub, heap, srcOff + 64, len);
          dst.fill(0xee);
          const n = b.takeBegin(sub, TakeMode.MESSAGE);
          assert.equal(n, len);
          assert.ok(b.takeCopy(dst, dstOff + 64), 'taken');
          const where = `len ${len}, source offset ${srcOff}, destination offset ${dstOff}`;
          assert.deepEqual(dst.subarray(dstOff + 64, dstOff + 64 + len), heap.subarray(srcOff + 64, srcOff + 64 + len), where);
          assert.equal(dst[dstOff + 63], 0xee, `byte before the copy written: ${where}`);
          assert.equal(dst[dstOff + 64 + len], 0xee, `byte after the copy written: ${where}`);
        }
      }
    }
  },

  /** A freed block is not reused at once (a reader may still be copying from it). */
  async freed_blocks_wait_before_reuse() {
    const { bus, runtime } = world(0);
    assert.ok(bus.tryLock(runtime));
    const x = bus.alloc(1000, runtime);
    bus.free(x);
    const y = bus.alloc(1000, runtime);
    bus.unlock(runtime);
    assert.notEqual(x, y, 'quarantined');
    assert.equal(bus.blockCapacity(y), 1024);
  },

  /** The DDS/ROS request-offered rules, and SYSTEM_DEFAULT resolution. */
  async qos_compatibility_rules() {
    const q = (p) => resolveQos(encodeQos(p));
    const cases = [
      [{}, {}, true, 0],
      [{ reliability: 'best_effort' }, {}, false, PolicyKind.RELIABILITY],
      [{}, { reliability: 'best_effort' }, true, 0],
      [{}, { durability: 'transient_local' }, false, PolicyKind.DURABILITY],
      [{ durability: 'transient_local' }, {}, true, 0],
      [{}, { deadlineMs: 100 }, false, PolicyKind.DEADLINE],
      [{ deadlineMs: 200 }, { deadlineMs: 100 }, false, PolicyKind.DEADLINE],
      [{ deadlineMs: 50 }, { deadlineMs: 100 }, true, 0],
      [{}, { liveliness: 'manual_by_topic' }, false, PolicyKind.LIVELINESS],
      [{ leaseMs: 200 }, { leaseMs: 100 }, false, PolicyKind.LIVELINESS_LEASE_DURATION],
      [{ reliability: 'system_default' }, {}, true, 0],
    ];
    for (const [pub, sub, ok, policy] of cases) {
      const r = checkCompatible(q(pub), q(sub));
      assert.equal(r.ok, ok, JSON.stringify([pub, sub, r]));
      assert.equal(r.policy, policy, JSON.stringify([pub, sub, r]));
    }
    const d = q({ history: 'system_default', depth: 0 });
    assert.equal(d[1], 10, 'SYSTEM_DEFAULT depth resolves to 10');
  },

  /** Full tables and bad buffers give errors that say what to do. */
  async limits_give_clear_errors() {
    const { clients: [a] } = world(1, { maxEndpoints: 3 });
    const n = a.createNode({ name: 'many' });
    for (let i = 0; i < 3; i++) endpoint(a, KIND_PUBLISHER, n.index, `/t${i}`);
    assert.throws(() => endpoint(a, KIND_PUBLISHER, n.index, '/t3'), (e) => e instanceof BusError &&
      e.code === Code.BAD_ALLOC && /endpoint table is full \(3 endpoints\); start the Runtime with a larger maxEndpoints/.test(e.message));
    assert.throws(() => Bus.attach(new SharedArrayBuffer(4096)), /not a wasm_js bus of layout version/);
    assert.throws(() => Bus.attach(new ArrayBuffer(4096)), /expected a SharedArrayBuffer/);
    assert.throws(() => Bus.create({ maxMessageBytes: 600 << 20, maxBytes: 1024 << 20 }), /needs maxBytes >= /);
    assert.throws(() => a.createNode({ name: 'x', namespace: 'relative' }), /invalid namespace "relative"/);
    assert.throws(() => a.publish(12345, bytes(1)), /endpoint handle 12345/);
  },

  /** Responses find their client by the request id's gid, across interleaved requests. */
  async request_ids_route_responses() {
    const { clients: [s, c1, c2] } = world(3);
    const srv = endpoint(s, KIND_SERVICE, s.createNode({ name: 'server' }).index, '/add');
    const cl1 = endpoint(c1, KIND_CLIENT, c1.createNode({ name: 'one' }).index, '/add');
    const cl2 = endpoint(c2, KIND_CLIENT, c2.createNode({ name: 'two' }).index, '/add');
    const seq = [c1.publish(cl1, bytes(1)), c2.publish(cl2, bytes(2)), c1.publish(cl1, bytes(3))];
    assert.deepEqual(seq, [1, 1, 2], 'each client numbers its own requests');
    let req;
    while ((req = s.take(srv, TakeMode.REQUEST))) {
      s.sendResponse(srv, Int32Array.from(s.info.gid), s.info.reqLo, s.info.reqHi, bytes(req[0] * 10));
    }
    const got = (c, ep) => {
      const out = [];
      let r;
      while ((r = c.take(ep, TakeMode.RESPONSE))) out.push([c.info.reqLo, r[0]]);
      return out;
    };
    assert.deepEqual(got(c1, cl1), [[1, 10], [2, 30]]);
    assert.deepEqual(got(c2, cl2), [[1, 20]]);
    // A response to a client that is gone is dropped, not an error.
    c2.destroyEndpoint(cl2);
    assert.equal(s.sendResponse(srv, [s.bus.id, c2.pid, (KIND_CLIENT << 24) | cl2, 0], 9, 0, bytes(0)), false);
  },

  /** Lifespan: an expired message is not delivered. */
  async lifespan_expired_messages_are_skipped() {
    const { clients: [a] } = world(1);
    const n = a.createNode({ name: 'ls' });
    const sub = endpoint(a, KIND_SUBSCRIPTION, n.index, '/ls', { depth: 10 });
    const pub = endpoint(a, KIND_PUBLISHER, n.index, '/ls', { lifespanMs: 40 });
    a.publish(pub, bytes(1));
    await new Promise((r) => setTimeout(r, 80));
    a.publish(pub, bytes(2));
    assert.deepEqual(Array.from(a.take(sub)), [2]);
    assert.equal(a.take(sub), null);
  },

  /** A BEST_EFFORT reader that falls behind counts what it lost. */
  async best_effort_overrun_counts_lost() {
    const { clients: [a] } = world(1);
    const n = a.createNode({ name: 'be' });
    const sub = endpoint(a, KIND_SUBSCRIPTION, n.index, '/be', { reliability: 'best_effort', depth: 5 });
    const pub = endpoint(a, KIND_PUBLISHER, n.index, '/be', { depth: 8 });
    for (let i = 0; i < 100; i++) a.publish(pub, bytes(i));
    const got = [];
    let m;
    while ((m = a.take(sub))) got.push(m[0]);
    assert.deepEqual(got, [95, 96, 97, 98, 99]);
    const lost = a.eventStatus(sub, EventType.MESSAGE_LOST, true);
    assert.equal(lost.total, 95);
    assert.equal(lost.change, 95);
    assert.equal(a.eventStatus(sub, EventType.MESSAGE_LOST, true).change, 0, 'taking resets the change');
  },

  /** RELIABLE + KEEP_ALL never drops: publish blocks, then times out with a clear error. */
  async keep_all_blocks_then_times_out() {
    const { clients: [a, b] } = world(2);
    const sub = endpoint(b, KIND_SUBSCRIPTION, b.createNode({ name: 'slow' }).index, '/ka', { history: 'keep_all' });
    const pub = endpoint(a, KIND_PUBLISHER, a.createNode({ name: 'fast' }).index, '/ka', { history: 'keep_all' }, { keepAllDepth: 4 });
    for (let i = 0; i < 4; i++) a.publish(pub, bytes(i), 0);
    const t0 = performance.now();
    assert.throws(() => a.publish(pub, bytes(4), 50), (e) => e.code === Code.TIMEOUT &&
      /timed out after 50 ms: the subscription of node 'slow' has not taken its oldest pending message/.test(e.message));
    assert.ok(performance.now() - t0 >= 49);
    assert.equal(b.take(sub)[0], 0);
    a.publish(pub, bytes(4), 0);
    const got = [];
    let m;
    while ((m = b.take(sub))) got.push(m[0]);
    assert.deepEqual(got, [1, 2, 3, 4], 'nothing dropped');
  },

  /**
   * A writer blocked on a full KEEP_ALL ring goes on soon after its reader
   * frees a slot, even when the reader then stops short of the point where
   * it rings writers (every eighth of the ring, or when it has taken
   * everything): the writer looks again meanwhile. Here the reader takes one
   * message of 64 and then takes nothing for 3 s; a writer woken only by
   * rings would stay blocked until its 2 s timeout.
   */
  async blocked_writer_goes_on_when_its_reader_stops_mid_batch() {
    const { bus, clients: [a, b] } = world(2);
    const sub = endpoint(b, KIND_SUBSCRIPTION, b.createNode({ name: 'reader' }).index, '/ka', { history: 'keep_all' });
    const pub = endpoint(a, KIND_PUBLISHER, a.createNode({ name: 'writer' }).index, '/ka', { history: 'keep_all' }, { keepAllDepth: 64 });
    for (let i = 0; i < 64; i++) a.publish(pub, bytes(i), 0);
    const reader = new Worker(`
      const { workerData: d, parentPort } = require('node:worker_threads');
      (async () => {
        const { Bus } = await import(d.bus);
        const { BusClient } = await import(d.client);
        const c = new BusClient(Bus.attach(d.sab), d.pid);
        const pause = (ms) => Atomics.wait(new Int32Array(new SharedArrayBuffer(4)), 0, 0, ms);
        pause(50);
        parentPort.postMessage({ first: c.take(d.sub)[0] });
        pause(3000);
      })();
    `, { eval: true, workerData: { sab: bus.sab, pid: b.pid, sub, bus: src('bus.mjs'), client: src('bus_client.mjs') } });
    const first = new Promise((resolve, reject) => { reader.on('message', resolve); reader.on('error', reject); });
    const t0 = performance.now();
    a.publish(pub, bytes(64), 2000);
    const blockedMs = performance.now() - t0;
    const r = await first;
    await reader.terminate();
    assert.equal(r.first, 0, 'the reader took the oldest message');
    assert.ok(blockedMs < 1000, `the writer went on ${blockedMs.toFixed(1)} ms after it blocked (a slot was free after ~50 ms)`);
    const got = [];
    let m;
    while ((m = b.take(sub))) got.push(m[0]);
    assert.equal(got.length, 64, 'nothing dropped');
    assert.equal(got[63], 64, 'the blocked message came last');
  },
};

const check = CHECKS[name];
if (!check) {
  process.stderr.write(`unknown check '${name}' (known: ${Object.keys(CHECKS).join(', ')})\n`);
  process.exit(2);
}
await check();
process.stdout.write('ok\n');
