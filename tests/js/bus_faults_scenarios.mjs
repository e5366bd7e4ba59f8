// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Kill-at-the-worst-moment scenarios of the bus (docs/faults.md), the same
// code in Node.js (bus_faults.mjs node) and in a Chromium page
// (bus_faults.mjs chromium). Each scenario starts a Runtime and JS-only bus
// processes in workers (bus_faults_worker.mjs, each a Runtime.helperProcess
// as the bridges' workers are), stops the victim at a fault point of one
// bus operation (packages/wasm_js/src/bus/faults.mjs), terminates its
// worker there and has the runtime clean up after it, then checks what the
// bus guarantees:
//   1. the locks are free: a process that was blocked on the registry lock
//      goes on, another process completes the same operation, and the
//      victim's endpoint records are reused with their writer and event locks;
//   2. the victim's nodes and endpoints are gone from the graph (and the
//      runtime's graph listeners were told), and the arena is whole (every
//      block on the one list its state says, none leaked, no record
//      pointing at a freed block);
//   3. its peers' events: matched counts drop, a subscription's liveliness
//      changes, a call to a server that went away ends with an error;
//   4. traffic between the live processes goes on: no RELIABLE message
//      lost, no stuck take, publish or call.
// Every scenario is bounded: fixed message counts, and SCENARIO_MS at most.

/** A scenario that takes longer has hung somewhere (its step is reported). */
const SCENARIO_MS = 40000;
/** Longer than a scenario: a wait or publish that needs this long is stuck. */
const STUCK_MS = 60000;
/** Messages that must all pass between live processes after a kill. */
const TRAFFIC = 200;
const KEEP_ALL = { history: 'keep_all', reliability: 'reliable' };

class Failure extends Error {}

function expect(cond, message) {
  if (!cond) throw new Failure(message);
}

const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

/** Start a JS-only bus process in a worker of its own (as the bridges do). */
async function proc(ctx, name) {
  const { pid, release } = await ctx.rt.helperProcess(name);
  const worker = await ctx.env.ProgramWorker.start(ctx.env.workerUrl, { name, type: 'module' });
  const p = { name, pid, worker, endpoints: [], pending: new Map(), next: 1, killed: false };
  let ready;
  const isReady = new Promise((resolve) => { ready = resolve; });
  worker.on('message', (m) => {
    if (m.ready) return ready();
    const w = p.pending.get(m.id);
    if (!w) return undefined;
    p.pending.delete(m.id);
    if (m.ok) w.resolve(m.value);
    else w.reject(Object.assign(new Error(`${name}.${w.method}: ${m.error.message}`), { code: m.error.code }));
    return undefined;
  });
  worker.on('error', (e) => ctx.errors.push(`${name}: ${e.message}`));
  p.call = (method, ...args) => new Promise((resolve, reject) => {
    const id = p.next++;
    p.pending.set(id, { resolve, reject, method });
    worker.postMessage({ id, method, args });
  });
  /** Create an endpoint and remember its index (the reuse check). */
  p.endpoint = async (...args) => {
    const ep = await p.call('endpoint', ...args);
    p.endpoints.push(ep);
    return ep;
  };
  /** Terminate the worker where it is, then have the runtime clean up (a bridge's exit). */
  p.kill = async () => {
    p.killed = true;
    await worker.terminate();
    await release();
  };
  ctx.procs.push(p);
  await isReady;
  await p.call('init', ctx.env.src, ctx.rt.bus.handle, pid);
  return p;
}

async function procs(ctx, ...names) {
  const out = [];
  for (const n of names) out.push(await proc(ctx, n));
  return out;
}

/** Two words of shared memory a fault point sets when the thread stops there. */
function newFlag() {
  return new Int32Array(new SharedArrayBuffer(8));
}

/**
 * Resolve once the thread stopped at the flag's point; fail when the
 * operation `call` returned first, or after 10 s.
 */
async function reached(flag, call, what) {
  let timer;
  const bounded = new Promise((resolve) => { timer = setTimeout(resolve, 10000); });
  const w = Atomics.waitAsync(flag, 0, 0);
  const returned = call.then(
    (v) => { throw new Failure(`${what} returned ${JSON.stringify(v)} without reaching its fault point`); },
    (e) => { throw new Failure(`${what} failed before its fault point: ${e.message}`); });
  returned.catch(() => {});
  try {
    await Promise.race([w.async ? w.value : Promise.resolve(), bounded, returned]);
  } finally {
    clearTimeout(timer);
  }
  expect(Atomics.load(flag, 0) === 1, `${what} did not reach its fault point within 10 s`);
}

/** Arm `point` in process p, start its operation and resolve when it stopped there. */
async function stopAt(ctx, p, point, start, skip = 0) {
  const flag = newFlag();
  await p.call('arm', { point, flag: flag.buffer, skip });
  const call = start();
  call.catch(() => {});
  ctx.step = `${p.name} stopping at ${point}`;
  await reached(flag, call, `${p.name}'s operation`);
  ctx.facts.stopped = point;
}

/** A promise that tells whether it has settled. */
function watched(promise) {
  const w = { done: false, promise };
  promise.then(() => { w.done = true; }, () => { w.done = true; });
  return w;
}

// ------------------------------------------------------------- checks

function layoutOf(ctx) {
  return ctx.env.layout;
}

/** The registry lock is free (or held by a live process). */
function checkLockFree(ctx) {
  const L = layoutOf(ctx);
  const v = Atomics.load(ctx.rt.bus.i32, L.HEADER.LOCK) & L.LOCK_OWNER_MASK;
  expect(v === 0 || ctx.rt.bus.processAlive(v), `the registry lock is still held by dead process ${v}`);
}

/** The victim's nodes and endpoints are gone: from graph() and from the records. */
function checkGone(ctx, victim) {
  const L = layoutOf(ctx);
  const g = ctx.rt.graph();
  const nodes = g.nodes.filter((n) => n.pid === victim.pid).map((n) => n.name);
  expect(nodes.length === 0, `the victim's nodes are still in the graph: ${nodes.join(', ')}`);
  for (const t of [...g.topics, ...g.services]) {
    for (const list of [t.publishers, t.subscriptions, t.servers, t.clients]) {
      expect(!(list || []).some((e) => e.pid === victim.pid), `an endpoint of the victim is still on '${t.name}'`);
    }
  }
  const bus = ctx.rt.bus;
  const i32 = bus.i32;
  for (let e = 0; e < i32[L.HEADER.EP_HWM]; e++) {
    const b = bus.ep(e);
    const st = Atomics.load(i32, b + L.ENDPOINT.STATE);
    if (i32[b + L.ENDPOINT.PID] !== victim.pid) continue;
    expect(st === L.REC_FREE || st === L.REC_ZOMBIE, `endpoint record ${e} of the victim is in state ${st}`);
  }
  for (let n = 0; n < i32[L.HEADER.NODE_HWM]; n++) {
    const b = bus.node(n);
    expect(i32[b + L.NODE.PID] !== victim.pid || Atomics.load(i32, b + L.NODE.STATE) === L.REC_FREE,
      `node record ${n} of the victim is still there`);
  }
  ctx.facts.gone = true;
}

/**
 * The arena is whole (under the registry lock): every free block on its
 * class' list, every quarantined one on the quarantine (which ends at its
 * tail word), each once; the byte count right; every block a record refers
 * to in use, and every block in use referred to.
 * @returns {Promise<void>}
 */
async function checkArena(ctx) {
  const L = layoutOf(ctx);
  const bus = ctx.rt.bus;
  await bus.lockAsync(ctx.rt.pid);
  try {
    bus.refreshViews();
    const problems = arenaProblems(bus, L);
    expect(problems.length === 0, `the arena is damaged: ${problems.slice(0, 5).join('; ')}`);
  } finally {
    bus.unlock(ctx.rt.pid);
  }
  ctx.facts.arena = 'whole';
}

/** The arena's blocks in address order, by their headers (payload offsets). */
function walkBlocks(bus, L) {
  const i32 = bus.i32;
  const top = i32[L.HEADER.ARENA_TOP];
  const blocks = [];
  const index = new Map();
  for (let at = i32[L.HEADER.ARENA_BASE]; at < top;) {
    const cls = i32[(at >> 2) + L.BLOCK.CLASS];
    if (cls < 0 || cls >= L.SIZE_CLASSES) return { blocks, index, why: `no block header at byte ${at}` };
    index.set(at + L.BLOCK_HEADER_BYTES, blocks.length);
    blocks.push(at + L.BLOCK_HEADER_BYTES);
    at += L.BLOCK_HEADER_BYTES + 2 ** (cls + L.MIN_CLASS_SHIFT);
  }
  return { blocks, index };
}

function arenaProblems(bus, L) {
  const i32 = bus.i32;
  const H = L.HEADER;
  const B = L.BLOCK;
  const walk = walkBlocks(bus, L);
  if (walk.why) return [walk.why];
  const problems = [];
  const hw = (off) => (off - L.BLOCK_HEADER_BYTES) >> 2;
  const listed = new Map();
  for (let cls = 0; cls < L.SIZE_CLASSES; cls++) {
    let guard = 0;
    for (let off = i32[H.FREE_BASE + cls]; off; off = i32[hw(off) + B.NEXT]) {
      if (!walk.index.has(off) || ++guard > walk.blocks.length) {
        problems.push(`free list ${cls} leads to ${off}, which is no block (or loops)`);
        break;
      }
      if (listed.has(off)) problems.push(`block ${off} is on two lists`);
      listed.set(off, 'free');
      if (i32[hw(off) + B.STATE] !== L.BLOCK_FREE) problems.push(`block ${off} on free list ${cls} is in state ${i32[hw(off) + B.STATE]}`);
      if (i32[hw(off) + B.CLASS] !== cls) problems.push(`block ${off} of class ${i32[hw(off) + B.CLASS]} is on free list ${cls}`);
    }
  }
  let last = 0;
  let guard = 0;
  for (let off = i32[H.QUAR_HEAD]; off; off = i32[hw(off) + B.NEXT]) {
    if (!walk.index.has(off) || ++guard > walk.blocks.length) {
      problems.push(`the quarantine leads to ${off}, which is no block (or loops)`);
      break;
    }
    if (listed.has(off)) problems.push(`block ${off} is on the quarantine and a free list`);
    listed.set(off, 'quarantine');
    if (i32[hw(off) + B.STATE] !== L.BLOCK_QUARANTINE) problems.push(`block ${off} on the quarantine is in state ${i32[hw(off) + B.STATE]}`);
    last = off;
  }
  if (last !== i32[H.QUAR_TAIL]) problems.push(`the quarantine ends at block ${last} but its tail word says ${i32[H.QUAR_TAIL]}`);
  const referenced = new Map();
  const refer = (off, what) => {
    if (!off) return;
    if (referenced.has(off)) problems.push(`block ${off} is referred to by ${referenced.get(off)} and by ${what}`);
    referenced.set(off, what);
  };
  for (let n = 0; n < i32[H.NODE_HWM]; n++) {
    const b = bus.node(n);
    if (Atomics.load(i32, b + L.NODE.STATE) !== L.REC_FREE) refer(i32[b + L.NODE.STR_OFF], `node ${n}`);
  }
  for (let e = 0; e < i32[H.EP_HWM]; e++) {
    const b = bus.ep(e);
    if (Atomics.load(i32, b + L.ENDPOINT.STATE) === L.REC_FREE) continue;
    refer(i32[b + L.ENDPOINT.STR_OFF], `endpoint ${e}'s names`);
    const ring = i32[b + L.ENDPOINT.RING_OFF];
    refer(ring, `endpoint ${e}'s ring`);
    if (!ring) continue;
    for (let s = 0; s < i32[b + L.ENDPOINT.RING_SLOTS]; s++) {
      refer(i32[(ring >> 2) + s * L.SLOT.WORDS + L.SLOT.BLOCK], `slot ${s} of endpoint ${e}`);
    }
  }
  let used = 0;
  for (const off of walk.blocks) {
    const st = i32[hw(off) + B.STATE];
    const size = 2 ** (i32[hw(off) + B.CLASS] + L.MIN_CLASS_SHIFT);
    if (st === L.BLOCK_USED) {
      used += size;
      if (!referenced.has(off)) problems.push(`block ${off} (owner ${i32[hw(off) + B.OWNER]}) is in use but nothing refers to it (leaked)`);
    } else {
      if (referenced.has(off)) problems.push(`${referenced.get(off)} refers to block ${off}, which is ${st === L.BLOCK_FREE ? 'free' : 'in quarantine'}`);
      const want = st === L.BLOCK_FREE ? 'free' : 'quarantine';
      if (listed.get(off) !== want) problems.push(`block ${off} (${want}) is on no ${want} list`);
    }
  }
  if (used !== Atomics.load(i32, H.ARENA_USED)) problems.push(`ARENA_USED says ${Atomics.load(i32, H.ARENA_USED)} bytes, the blocks in use hold ${used}`);
  return problems;
}

/**
 * The victim's endpoint records are reused by another process, and their
 * writer and event locks are free: a publish and an event status on each
 * return. The runtime runs with a table of 64 endpoints so that this is
 * bounded.
 */
async function checkReuse(ctx, victim) {
  if (!victim.endpoints.length) return;
  const reuser = await proc(ctx, 'reuser');
  const node = await reuser.call('node', 'reuser');
  const want = new Set(victim.endpoints);
  for (let i = 0; i < 64 && want.size; i++) {
    let ep;
    try {
      ep = await reuser.call('endpoint', 'publisher', node, `/reuse${i}`, { depth: 1 });
    } catch (e) {
      break; // the table is full
    }
    if (!want.delete(ep)) continue;
    await reuser.call('publish', ep, 7, i, 1, 1000);
    await reuser.call('event', ep, 'OFFERED_DEADLINE_MISSED');
  }
  expect(want.size === 0, `the victim's endpoint records ${[...want].join(', ')} were never freed for reuse`);
  ctx.facts.reused = victim.endpoints.length;
}

/**
 * RELIABLE traffic between live processes goes on: `writer` publishes
 * TRAFFIC messages (tag, from ...) while `reader` waits for them; each
 * arrives once, in order.
 */
async function checkTraffic(ctx, writer, pub, tag, reader, sub, from = 0) {
  ctx.step = `traffic ${writer.name} -> ${reader.name}`;
  const got = reader.call('waitTake', sub, 'subscription', TRAFFIC, STUCK_MS);
  await writer.call('publish', pub, tag, from, TRAFFIC, STUCK_MS);
  const msgs = await got;
  const mine = msgs.filter((m) => m.tag === tag).map((m) => m.n);
  expect(mine.length === TRAFFIC, `${reader.name} got ${mine.length} of ${TRAFFIC} RELIABLE messages from ${writer.name}`);
  expect(mine.every((n, i) => n === from + i), `${reader.name} got ${writer.name}'s messages out of order or twice`);
  ctx.facts.traffic = TRAFFIC;
}

/** The lock-held points: a process blocked on the registry lock must go on after the kill. */
const LOCKED = new Set([
  'publish.renewing', 'take.reaping', 'graph.locked', 'graph.node_written', 'graph.endpoint_written',
  'graph.matching', 'graph.removing', 'graph.changed', 'arena.freeing', 'arena.releasing',
]);

/** While the victim holds the registry lock, `waiter` starts a registry change (it blocks). */
async function blockOnLock(ctx, point, waiter) {
  if (!LOCKED.has(point)) return null;
  const node = watched(waiter.call('node', 'blocked'));
  await sleep(50);
  expect(!node.done, `a node was created while ${point} should hold the registry lock`);
  return node;
}

async function unblocked(ctx, blocked) {
  if (!blocked) return;
  ctx.step = 'the process blocked on the registry lock';
  await blocked.promise;
  ctx.facts.lock_waiter = 'went on';
}

/**
 * Run `killing()`, and expect the runtime's graph listeners to be told of a
 * graph without process `pid` (within 5 s).
 */
async function graphEventWithout(ctx, pid, killing) {
  let told = false;
  const off = ctx.rt.onGraphChange((g) => {
    if (!g.nodes.some((n) => n.pid === pid)) told = true;
  });
  try {
    await killing();
    const deadline = performance.now() + 5000;
    while (!told && performance.now() < deadline) await sleep(10);
  } finally {
    off();
  }
  expect(told, 'no graph change without the killed process reached onGraphChange');
  ctx.facts.graph_event = true;
}

/** Kill the victim (it stopped at a point) and record what the cleanup repaired. */
async function kill(ctx, victim) {
  ctx.step = `killing ${victim.name}`;
  ctx.rt.bus.lastRecovery = null;
  await graphEventWithout(ctx, victim.pid, () => victim.kill());
  const r = ctx.rt.bus.lastRecovery;
  if (r) ctx.facts.recovered = `lock of ${r.pid === victim.pid ? 'the victim' : r.pid}: ${r.leaked} leaked blocks, ${r.slots} slots, ${r.orphans} zombies`;
  checkLockFree(ctx);
  checkGone(ctx, victim);
}

// ------------------------------------------------------------- scenarios

/**
 * publish.{locked,writing,committed,unrung,renewing}: the victim and another
 * process publish RELIABLE KEEP_ALL to one subscriber; the victim is killed
 * in the middle of a publish. Its message is delivered only when it was
 * committed (unrung: the sleeping subscriber is woken by the cleanup).
 */
async function publishKill(ctx, point) {
  const [victim, other, sub, late] = await procs(ctx, 'victim', 'other', 'subscriber', 'late');
  const renewing = point === 'publish.renewing';
  // renewing: KEEP_LAST, so that the subscriber can leave messages untaken (a zombie ring).
  const subQos = renewing ? { depth: 16 } : KEEP_ALL;
  const vPub = await victim.endpoint('publisher', await victim.call('node', 'victim'), '/faults', renewing ? { depth: 16 } : KEEP_ALL, { keepAllDepth: 16 });
  const oPub = await other.endpoint('publisher', await other.call('node', 'other'), '/faults', KEEP_ALL, { keepAllDepth: 16 });
  const sSub = await sub.endpoint('subscription', await sub.call('node', 'subscriber'), '/faults', subQos);
  const warm = renewing ? 20 : 5;
  await victim.call('publish', vPub, 1, 0, warm);
  await other.call('publish', oPub, 2, 0, 5);
  const first = await sub.call(renewing ? 'take' : 'waitTake', sSub, 'subscription', ...(renewing ? [5] : [warm + 5, 5000]));
  expect(renewing || first.length === warm + 5, `the subscriber got ${first.length} of ${warm + 5} messages before the kill`);
  expect(await sub.call('matched', sSub) === 2, 'two publishers matched before the kill');
  const live = await sub.call('event', sSub, 'LIVELINESS_CHANGED');
  expect(live.alive === 2, `liveliness before the kill: ${live.alive} alive`);
  const waiting = point === 'publish.unrung' ? sub.call('waitTake', sSub, 'subscription', 1, STUCK_MS) : null;
  if (waiting) await sleep(20); // asleep in its wait when the message is committed
  // renewing: a message larger than the slot's block, so that the slot gets a new one
  await stopAt(ctx, victim, point, () => victim.call('publish', vPub, 1, warm, 1, 5000, renewing ? 200 : 8));
  const blocked = await blockOnLock(ctx, point, late);
  await kill(ctx, victim);
  await unblocked(ctx, blocked);
  if (waiting) {
    ctx.step = 'the subscriber asleep when the victim committed';
    const woke = await waiting;
    expect(woke.length === 1 && woke[0].tag === 1 && woke[0].n === warm, `the sleeping subscriber got ${JSON.stringify(woke)}`);
  }
  // 3. events
  expect(await sub.call('matched', sSub) === 1, 'the subscription\'s matched count did not drop to 1');
  const after = await sub.call('event', sSub, 'LIVELINESS_CHANGED');
  expect(after.alive === 1 && after.aliveChange === -1, `liveliness after the kill: ${JSON.stringify(after)}`);
  ctx.facts.liveliness = `alive ${after.alive} (${after.aliveChange})`;
  if (renewing) {
    // The victim's ring stays (a zombie) while the subscriber has not taken it all;
    // meanwhile the block the victim freed leaves the quarantine and is reused.
    await sleep(2100);
    const filler = await proc(ctx, 'filler');
    const fNode = await filler.call('node', 'filler');
    for (let i = 0; i < 8; i++) {
      const ep = await filler.endpoint('publisher', fNode, `/filler${i}`, { depth: 1 });
      await filler.call('publish', ep, 5, i, 1);
    }
  }
  // 4. what the victim published before: every committed message, intact, once
  const rest = await sub.call('take', sSub, 'subscription');
  const fromVictim = [...first, ...(waiting ? [{ tag: 1, n: warm, intact: true }] : []), ...rest].filter((m) => m.tag === 1);
  expect(fromVictim.every((m) => m.intact), 'a message of the victim arrived torn');
  const ns = fromVictim.map((m) => m.n);
  expect(!ns.includes(warm) || point === 'publish.unrung', `the message the victim was killed publishing (${point}) was delivered`);
  expect(new Set(ns).size === ns.length, 'a message of the victim arrived twice');
  if (!renewing) expect(ns.length === warm + (point === 'publish.unrung' ? 1 : 0), `the subscriber got ${ns.length} messages of the victim`);
  ctx.facts.victim_messages = ns.length;
  if (renewing) {
    // the subscriber keeps the last 16: the traffic goes to a RELIABLE KEEP_ALL one
    const listener = await proc(ctx, 'listener');
    const tSub = await listener.endpoint('subscription', await listener.call('node', 'listener'), '/faults', KEEP_ALL);
    await checkTraffic(ctx, other, oPub, 2, listener, tSub, 5);
    await sub.call('take', sSub, 'subscription');
  } else {
    await checkTraffic(ctx, other, oPub, 2, sub, sSub, 5);
  }
  // 1. another process publishes on the topic
  const lPub = await late.endpoint('publisher', await late.call('node', 'late'), '/faults', KEEP_ALL);
  await late.call('publish', lPub, 3, 0);
  const l = await sub.call('waitTake', sSub, 'subscription', 1, STUCK_MS);
  expect(l.length === 1 && l[0].tag === 3, 'a new publisher\'s message did not arrive');
  await checkArena(ctx);
  await checkReuse(ctx, victim);
}

/**
 * publish.blocked: the victim is blocked publishing to a RELIABLE KEEP_ALL
 * subscription that does not take. What it committed is still delivered.
 */
async function publishBlocked(ctx) {
  const [victim, sub, late] = await procs(ctx, 'victim', 'subscriber', 'late');
  const vPub = await victim.endpoint('publisher', await victim.call('node', 'victim'), '/faults/full', KEEP_ALL, { keepAllDepth: 4 });
  const sSub = await sub.endpoint('subscription', await sub.call('node', 'subscriber'), '/faults/full', KEEP_ALL);
  await victim.call('publish', vPub, 1, 0, 4);
  await stopAt(ctx, victim, 'publish.blocked', () => victim.call('publish', vPub, 1, 4, 1, STUCK_MS));
  await kill(ctx, victim);
  expect(await sub.call('matched', sSub) === 0, 'the subscription still counts the victim');
  const got = await sub.call('take', sSub, 'subscription');
  expect(got.map((m) => m.n).join() === '0,1,2,3', `the subscriber got ${got.map((m) => m.n)} of the victim's 4 committed messages`);
  ctx.facts.victim_messages = got.length;
  const lPub = await late.endpoint('publisher', await late.call('node', 'late'), '/faults/full', KEEP_ALL, { keepAllDepth: 4 });
  await checkTraffic(ctx, late, lPub, 3, sub, sSub);
  await checkArena(ctx);
  await checkReuse(ctx, victim);
}

/**
 * take.{found,copied,consumed}: the victim and a peer subscribe RELIABLE
 * KEEP_ALL; the writer is blocked on the victim's full history when the
 * victim is killed in the middle of a take. The writer goes on.
 */
async function takeKill(ctx, point) {
  const [victim, writer, peer, late] = await procs(ctx, 'victim', 'writer', 'peer', 'late');
  const wPub = await writer.endpoint('publisher', await writer.call('node', 'writer'), '/faults', KEEP_ALL, { keepAllDepth: 4 });
  const vSub = await victim.endpoint('subscription', await victim.call('node', 'victim'), '/faults', KEEP_ALL);
  const pSub = await peer.endpoint('subscription', await peer.call('node', 'peer'), '/faults', KEEP_ALL);
  await writer.call('publish', wPub, 1, 0, 4);
  expect(await writer.call('matched', wPub) === 2, 'two subscriptions matched before the kill');
  const peerGot = await peer.call('waitTake', pSub, 'subscription', 4, 5000);
  expect(peerGot.length === 4, 'the peer took the first 4');
  // The writer's history is full for the victim: its next publish blocks.
  const blockedPublish = watched(writer.call('publish', wPub, 1, 4, 1, STUCK_MS));
  await sleep(50);
  expect(!blockedPublish.done, 'the writer did not block on the victim\'s full history');
  await stopAt(ctx, victim, point, () => victim.call('take', vSub, 'subscription', 1));
  await kill(ctx, victim);
  ctx.step = 'the writer blocked on the victim';
  await blockedPublish.promise;
  ctx.facts.blocked_writer = 'went on';
  expect(await writer.call('matched', wPub) === 1, 'the publisher\'s matched count did not drop to 1');
  ctx.facts.matched = 1;
  const next = await peer.call('waitTake', pSub, 'subscription', 1, STUCK_MS);
  expect(next.length === 1 && next[0].n === 4, 'the peer did not get the message the writer was blocked on');
  await checkTraffic(ctx, writer, wPub, 2, peer, pSub);
  const lSub = await late.endpoint('subscription', await late.call('node', 'late'), '/faults', KEEP_ALL);
  await writer.call('publish', wPub, 3, 0);
  const l = await late.call('waitTake', lSub, 'subscription', 1, STUCK_MS);
  expect(l.length === 1 && l[0].tag === 3, 'a new subscription did not take');
  await checkArena(ctx);
  await checkReuse(ctx, victim);
}

/**
 * take.reaping: the victim has taken everything a departed writer left
 * (a zombie ring) and dies dropping that writer's links under the lock;
 * reap@arena.freeing: it dies later, freeing the zombie's blocks (the
 * zombie has no link left: the recovery frees it).
 */
async function takeReaping(ctx, point) {
  const [victim, writer, late] = await procs(ctx, 'victim', 'writer', 'late');
  const vSub = await victim.endpoint('subscription', await victim.call('node', 'victim'), '/faults/z', KEEP_ALL);
  const wNode = await writer.call('node', 'writer');
  const wPub = await writer.endpoint('publisher', wNode, '/faults/z', { depth: 4 });
  await writer.call('publish', wPub, 1, 0, 2);
  await writer.call('destroy', wPub);
  const got = await victim.call('take', vSub, 'subscription', 2);
  expect(got.length === 2, 'the victim took the departed writer\'s 2 messages');
  await stopAt(ctx, victim, point, () => victim.call('take', vSub, 'subscription'));
  const blocked = await blockOnLock(ctx, point, late);
  await kill(ctx, victim);
  await unblocked(ctx, blocked);
  const L = layoutOf(ctx);
  expect(Atomics.load(ctx.rt.bus.i32, ctx.rt.bus.ep(wPub) + L.ENDPOINT.STATE) === L.REC_FREE, 'the departed writer\'s ring was not freed');
  const lSub = await late.endpoint('subscription', await late.call('node', 'late'), '/faults/z', KEEP_ALL);
  const pub2 = await writer.endpoint('publisher', wNode, '/faults/z', KEEP_ALL);
  await checkTraffic(ctx, writer, pub2, 2, late, lSub);
  await checkArena(ctx);
  await checkReuse(ctx, victim);
}

/**
 * request@{publish.writing,publish.unrung}: a client is killed sending a
 * request. The server drops the answer to a client that is gone; another
 * client's calls go on.
 */
async function requestKill(ctx, point) {
  const [victim, server, client] = await procs(ctx, 'victim', 'server', 'client');
  const srv = await server.endpoint('service', await server.call('node', 'server'), '/faults/srv');
  const vCli = await victim.endpoint('client', await victim.call('node', 'victim'), '/faults/srv');
  const cCli = await client.endpoint('client', await client.call('node', 'client'), '/faults/srv');
  expect(await server.call('matched', srv) === 2, 'two clients matched before the kill');
  await stopAt(ctx, victim, point, () => victim.call('publish', vCli, 1, 0));
  await kill(ctx, victim);
  expect(await server.call('matched', srv) === 1, 'the service\'s matched count did not drop to 1');
  const requests = await server.call('take', srv, 'service');
  const committed = point === 'publish.unrung';
  expect(requests.length === (committed ? 1 : 0), `the server got ${requests.length} requests of the killed client`);
  if (committed) {
    const sent = await server.call('respond', srv, requests, 9);
    expect(sent[0] === false, 'the answer to a client that is gone was not dropped');
    ctx.facts.answer = 'dropped';
  }
  // the other client's calls go on
  for (let i = 0; i < 20; i++) {
    await client.call('publish', cCli, 2, i);
    const req = await server.call('waitTake', srv, 'service', 1, STUCK_MS);
    expect(req.length === 1 && req[0].n === i, `the server did not get request ${i}`);
    expect((await server.call('respond', srv, req, 9))[0] === true, 'an answer was dropped');
    const res = await client.call('waitTake', cCli, 'client', 1, STUCK_MS);
    expect(res.length === 1 && res[0].n === i * 1000, `response ${i} did not arrive`);
  }
  ctx.facts.calls = 20;
  await checkArena(ctx);
  await checkReuse(ctx, victim);
}

/**
 * reply@{take.copied,publish.locked,publish.writing,publish.unrung}: the only
 * server is killed taking a request or answering it; the caller is the
 * runtime's tools process. The call ends: with the answer when it was
 * committed, else with an error that the server went away (before its
 * timeout). A new server answers the next call.
 */
async function replyKill(ctx, point) {
  const [victim, late] = await procs(ctx, 'victim', 'late');
  const srv = await victim.endpoint('service', await victim.call('node', 'victim'), '/faults/srv');
  const tools = await ctx.rt.tools();
  const spec = { service: '/faults/srv', type: 'test_msgs/msg/Bytes', timeoutMs: 20000 };
  const request = Uint8Array.of(3, 0, 0, 0, 1, 0, 0, 0);
  const call = watched(tools.call(spec, request));
  call.promise.catch(() => {});
  if (point === 'take.copied') {
    await stopAt(ctx, victim, point, () => victim.call('waitTake', srv, 'service', 1, STUCK_MS));
  } else {
    const reqs = await victim.call('waitTake', srv, 'service', 1, STUCK_MS);
    expect(reqs.length === 1 && reqs[0].n === 1, 'the server got the request');
    await stopAt(ctx, victim, point, () => victim.call('respond', srv, reqs, 9));
  }
  const tKill = performance.now();
  await kill(ctx, victim);
  ctx.step = 'the call to the server that died';
  let outcome;
  try {
    const r = await call.promise;
    outcome = { ok: true, data: Array.from(r.data) };
  } catch (e) {
    outcome = { ok: false, message: e.message };
  }
  const ms = performance.now() - tKill;
  if (point === 'publish.unrung') {
    expect(outcome.ok && outcome.data[4] === 232 && outcome.data[5] === 3, `the committed answer did not arrive: ${JSON.stringify(outcome)}`);
    ctx.facts.call = 'answered';
  } else {
    expect(!outcome.ok, `the call succeeded: ${JSON.stringify(outcome)}`);
    expect(/went away|no longer/.test(outcome.message), `the call ended with: ${outcome.message}`);
    expect(ms < spec.timeoutMs, `the call ended only at its timeout (${Math.round(ms)} ms after the kill)`);
    ctx.facts.call = `failed ${Math.round(ms)} ms after the kill (timeout ${spec.timeoutMs} ms): ${outcome.message}`;
  }
  const g = ctx.rt.graph();
  expect(!g.services.some((s) => s.name === '/faults/srv' && s.servers.length), 'the service server is still in the graph');
  // A new server answers the next calls.
  const srv2 = await late.endpoint('service', await late.call('node', 'late'), '/faults/srv');
  const answers = (async () => {
    for (let i = 0; i < 10; i++) {
      const req = await late.call('waitTake', srv2, 'service', 1, STUCK_MS);
      await late.call('respond', srv2, req, 4);
    }
  })();
  for (let i = 0; i < 10; i++) {
    const r = await tools.call(spec, Uint8Array.of(3, 0, 0, 0, i, 0, 0, 0));
    expect(r.data[4] === (i * 1000) % 256, `answer ${i} of the new server is wrong`);
  }
  await answers;
  ctx.facts.calls = 10;
  await checkArena(ctx);
  await checkReuse(ctx, victim);
}

/**
 * graph.*: the victim is killed in the middle of a registry change (the
 * registry lock held); a process blocked on the lock goes on and the others
 * make the same change.
 */
async function graphKill(ctx, point) {
  const [victim, sub1, sub2, late] = await procs(ctx, 'victim', 'sub1', 'sub2', 'late');
  const s1 = await sub1.endpoint('subscription', await sub1.call('node', 'sub1'), '/faults', KEEP_ALL);
  const s2 = await sub2.endpoint('subscription', await sub2.call('node', 'sub2'), '/faults', KEEP_ALL);
  const vNode = await victim.call('node', 'victim');
  let op;
  if (point === 'graph.node_written') {
    op = () => victim.call('node', 'victim2');
  } else if (point === 'graph.removing') {
    const vPub = await victim.endpoint('publisher', vNode, '/faults', KEEP_ALL);
    expect(await sub1.call('matched', s1) === 1, 'the victim\'s publisher matched');
    op = () => victim.call('destroy', vPub);
  } else {
    op = () => victim.call('endpoint', 'publisher', vNode, '/faults', KEEP_ALL);
  }
  await stopAt(ctx, victim, point, op);
  const blocked = await blockOnLock(ctx, point, late);
  await kill(ctx, victim);
  await unblocked(ctx, blocked);
  for (const [p, s] of [[sub1, s1], [sub2, s2]]) {
    expect(await p.call('matched', s) === 0, `${p.name} still counts a publisher of the victim`);
  }
  // The same change by another process, and traffic over it.
  const lNode = await late.call('node', 'late');
  const lPub = await late.endpoint('publisher', lNode, '/faults', KEEP_ALL, { keepAllDepth: 16 });
  expect(await late.call('matched', lPub) === 2, 'a new publisher did not match both subscriptions');
  const s2got = sub2.call('waitTake', s2, 'subscription', TRAFFIC, STUCK_MS);
  await checkTraffic(ctx, late, lPub, 2, sub1, s1);
  expect((await s2got).length === TRAFFIC, 'the second subscription lost messages');
  await late.call('destroy', lPub);
  await late.call('node', 'victim');
  expect(ctx.rt.graph().nodes.some((n) => n.name === 'victim' && n.pid === late.pid), 'the victim\'s node name was not free for another');
  await checkArena(ctx);
  await checkReuse(ctx, victim);
}

/**
 * arena.freeing, arena.releasing: the victim is killed between the stores
 * of a free, or of a release from the quarantine (registry lock held).
 * The lists are repaired before anyone allocates again; then many
 * allocations and frees keep every message intact.
 */
async function arenaKill(ctx, point) {
  const [victim, writer, reader, late] = await procs(ctx, 'victim', 'writer', 'reader', 'late');
  const vNode = await victim.call('node', 'victim');
  const a = await victim.endpoint('subscription', vNode, '/faults/a');
  const b = await victim.endpoint('publisher', vNode, '/faults/b', { depth: 4 });
  await victim.call('publish', b, 1, 0, 4);
  await victim.call('destroy', a); // the quarantine is not empty now
  let op;
  if (point === 'arena.freeing') {
    op = () => victim.call('destroy', b);
  } else {
    await sleep(2100); // past the quarantine's grace: the next allocation releases it
    op = () => victim.call('endpoint', 'subscription', vNode, '/faults/c');
  }
  await stopAt(ctx, victim, point, op);
  const blocked = await blockOnLock(ctx, point, late);
  await kill(ctx, victim);
  await unblocked(ctx, blocked);
  await checkArena(ctx);
  // Churn: endpoints made and removed, messages of mixed sizes, past a quarantine's grace.
  const rSub = await reader.endpoint('subscription', await reader.call('node', 'reader'), '/faults/churn', KEEP_ALL);
  const wNode = await writer.call('node', 'writer');
  for (let round = 0; round < 2; round++) {
    const pub = await writer.endpoint('publisher', wNode, '/faults/churn', KEEP_ALL, { keepAllDepth: 8 });
    const got = reader.call('waitTake', rSub, 'subscription', 40, STUCK_MS);
    for (let i = 0; i < 40; i++) await writer.call('publish', pub, 2, i, 1, STUCK_MS, 8 + ((i * 97) % 700));
    const msgs = await got;
    expect(msgs.length === 40 && msgs.every((m, i) => m.n === i && m.intact), `round ${round}: messages lost or damaged`);
    await writer.call('destroy', pub);
    if (round === 0) await sleep(2100);
  }
  ctx.facts.churn = 'intact';
  await checkArena(ctx);
  await checkReuse(ctx, victim);
}

/** event.locked: the victim dies holding its subscription's event lock. */
async function eventKill(ctx) {
  const [victim, writer] = await procs(ctx, 'victim', 'writer');
  const wPub = await writer.endpoint('publisher', await writer.call('node', 'writer'), '/faults', KEEP_ALL, { keepAllDepth: 4 });
  const vSub = await victim.endpoint('subscription', await victim.call('node', 'victim'), '/faults', KEEP_ALL);
  await stopAt(ctx, victim, 'event.locked', () => victim.call('event', vSub, 'LIVELINESS_CHANGED'));
  await kill(ctx, victim);
  expect(await writer.call('matched', wPub) === 0, 'the publisher still counts the victim');
  await writer.call('publish', wPub, 1, 0, 10, STUCK_MS); // nobody to block on
  await checkArena(ctx);
  await checkReuse(ctx, victim);
}

/** wait.sleeping: the victim dies asleep in a wait; its writer does not wait for it. */
async function waitKill(ctx) {
  const [victim, writer, peer] = await procs(ctx, 'victim', 'writer', 'peer');
  const wPub = await writer.endpoint('publisher', await writer.call('node', 'writer'), '/faults', KEEP_ALL, { keepAllDepth: 4 });
  const vSub = await victim.endpoint('subscription', await victim.call('node', 'victim'), '/faults', KEEP_ALL);
  const pSub = await peer.endpoint('subscription', await peer.call('node', 'peer'), '/faults', KEEP_ALL);
  await stopAt(ctx, victim, 'wait.sleeping', () => victim.call('waitTake', vSub, 'subscription', 1, STUCK_MS));
  await kill(ctx, victim);
  expect(await writer.call('matched', wPub) === 1, 'the publisher\'s matched count did not drop');
  await checkTraffic(ctx, writer, wPub, 2, peer, pSub);
  await checkArena(ctx);
  await checkReuse(ctx, victim);
}

/**
 * tools@{publish.writing,graph.locked}: the runtime's tools process is
 * killed in the middle of a publish, or of a subscribe (registry lock
 * held). Its endpoints go, and the runtime's next tools() is a new one.
 */
async function toolsKill(ctx, point) {
  const [sub, late] = await procs(ctx, 'subscriber', 'late');
  const sSub = await sub.endpoint('subscription', await sub.call('node', 'subscriber'), '/faults', KEEP_ALL);
  const tools = await ctx.rt.tools();
  const spec = { topic: '/faults', type: 'test_msgs/msg/Bytes', qos: KEEP_ALL };
  const pub = await tools.advertise(spec);
  await pub.publish(Uint8Array.of(1, 0, 0, 0, 0, 0, 0, 0));
  expect((await sub.call('waitTake', sSub, 'subscription', 1, 5000)).length === 1, 'the tools\' first message');
  const flag = newFlag();
  await tools.armFaultPoint({ point, flag: flag.buffer });
  const op = point === 'graph.locked'
    ? tools.subscribe({ topic: '/faults/other', type: 'test_msgs/msg/Bytes' }, () => {})
    : pub.publish(Uint8Array.of(1, 0, 0, 0, 1, 0, 0, 0));
  op.catch(() => {});
  ctx.step = `the tools stopping at ${point}`;
  await reached(flag, op, 'the tools\' operation');
  ctx.facts.stopped = point;
  const blocked = await blockOnLock(ctx, point, late);
  ctx.step = 'killing the tools';
  await graphEventWithout(ctx, tools.pid, () => tools.kill());
  await unblocked(ctx, blocked);
  checkLockFree(ctx);
  checkGone(ctx, { pid: tools.pid });
  expect(await sub.call('matched', sSub) === 0, 'the subscription still counts the tools\' publisher');
  let failed = false;
  await op.then(() => {}, () => { failed = true; });
  expect(failed, 'the interrupted tools call did not fail');
  const again = await ctx.rt.tools();
  expect(again !== tools && again.pid !== tools.pid, 'tools() gave the killed tools process');
  const pub2 = await again.advertise(spec);
  await pub2.publish(Uint8Array.of(2, 0, 0, 0, 0, 0, 0, 0));
  const got = await sub.call('waitTake', sSub, 'subscription', 1, STUCK_MS);
  expect(got.length === 1 && got[0].tag === 2, 'the new tools process\' message did not arrive');
  ctx.facts.new_tools = `pid ${again.pid}`;
  await checkArena(ctx);
}

/**
 * tools_exit (Node.js): the tools worker ends without the Tools handle
 * knowing (a crash); its exit event has the runtime clean up.
 */
async function toolsExit(ctx) {
  const tools = await ctx.rt.tools();
  await tools.advertise({ topic: '/faults', type: 'test_msgs/msg/Bytes' });
  await tools._worker.terminate();
  ctx.step = 'the tools\' exit event';
  const deadline = performance.now() + 10000;
  while (ctx.rt.graph().nodes.some((n) => n.pid === tools.pid) && performance.now() < deadline) await sleep(20);
  checkGone(ctx, { pid: tools.pid });
  checkLockFree(ctx);
  const again = await ctx.rt.tools();
  expect(again.pid !== tools.pid, 'tools() gave the crashed tools process');
  await again.publish({ topic: '/faults', type: 'test_msgs/msg/Bytes' }, Uint8Array.of(1));
  ctx.facts.new_tools = `pid ${again.pid}`;
}

// ------------------------------------------------- wasm programs (the demo)

/** Resolve when pred(rt.graph()) holds, looking every 20 ms for at most 10 s. */
async function graphHolds(ctx, pred, what) {
  ctx.step = `waiting for ${what}`;
  const deadline = performance.now() + 10000;
  while (!pred(ctx.rt.graph())) {
    expect(performance.now() < deadline, `${what}: not within 10 s`);
    await sleep(20);
  }
}

/** Spawn a demo executable (demo_nodes) with a fault point armed on its main thread. */
async function spawnArmed(ctx, exe, args, point, skip = 0) {
  const flag = newFlag();
  const lines = [];
  const proc = await ctx.rt.spawn({
    url: ctx.env.demo[exe], args, name: exe, faultPoint: { point, flag: flag.buffer, skip },
    onLog: ({ text }) => { if (lines.length < 50) lines.push(text); },
  });
  proc.lines = lines;
  proc.flag = flag;
  return proc;
}

async function programStopped(ctx, proc, point) {
  ctx.step = `${proc.name} stopping at ${point}`;
  await reached(proc.flag, proc.exited, `${proc.name} (log: ${proc.lines.join(' | ')})`);
  ctx.facts.stopped = point;
}

/** Kill a program where it stopped: NodeProcess.stop() (terminate, then the runtime's cleanup). */
async function stopProgram(ctx, proc) {
  ctx.step = `stopping ${proc.name}`;
  ctx.rt.bus.lastRecovery = null;
  await graphEventWithout(ctx, proc.id, () => proc.stop());
  const r = ctx.rt.bus.lastRecovery;
  if (r) ctx.facts.recovered = `lock of ${r.pid === proc.id ? 'the victim' : r.pid}: ${r.leaked} leaked blocks, ${r.slots} slots, ${r.orphans} zombies`;
  checkLockFree(ctx);
  checkGone(ctx, { pid: proc.id });
}

/** The count of a demo_interfaces/msg/Chatter message ("Hello World: N", N). */
function chatterCount(bytes) {
  const u8 = Uint8Array.from(bytes);
  const v = new DataView(u8.buffer);
  const len = v.getUint32(4, true);
  const at = 8 + len + ((4 - ((len + 4) % 4)) % 4);
  return v.getUint32(at, true);
}

const CHATTER = { type: 'demo_interfaces/msg/Chatter' };

/**
 * demo_talker@publish.writing: the demo's C++ talker (wasm_cpp) is killed
 * in the middle of its sixth publish; the subscriber got the five before,
 * its liveliness changed, and a new talker's messages all arrive.
 */
async function demoTalker(ctx) {
  const [sub] = await procs(ctx, 'subscriber');
  const sSub = await sub.endpoint('subscription', await sub.call('node', 'subscriber'), '/chatter', KEEP_ALL, CHATTER);
  const first = sub.call('waitTake', sSub, 'subscription', 5, STUCK_MS, true);
  const talker = await spawnArmed(ctx, 'talker', ['--ros-args', '-p', 'rate:=200', '-r', '__node:=talker_a'], 'publish.writing', 5);
  await programStopped(ctx, talker, 'publish.writing');
  const five = await first;
  expect((await sub.call('event', sSub, 'LIVELINESS_CHANGED')).alive === 1, 'the talker was alive before the kill');
  await stopProgram(ctx, talker);
  expect(await sub.call('matched', sSub) === 0, 'the subscription still counts the killed talker');
  const live = await sub.call('event', sSub, 'LIVELINESS_CHANGED');
  expect(live.alive === 0 && live.aliveChange === -1, `liveliness after the kill: ${JSON.stringify(live)}`);
  ctx.facts.liveliness = `alive ${live.alive} (${live.aliveChange})`;
  const rest = await sub.call('take', sSub, 'subscription', 100, true);
  const counts = [...five, ...rest].map((m) => chatterCount(m.bytes));
  expect(counts.join() === '1,2,3,4,5', `the subscriber got the killed talker's messages ${counts}`);
  ctx.facts.victim_messages = counts.length;
  const next = sub.call('waitTake', sSub, 'subscription', 50, STUCK_MS, true);
  const other = await ctx.rt.spawn({ url: ctx.env.demo.talker, args: ['--ros-args', '-p', 'rate:=200', '-r', '__node:=talker_b'], name: 'talker_b' });
  ctx.step = 'the new talker\'s messages';
  const got = (await next).map((m) => chatterCount(m.bytes));
  expect(got.length === 50 && got.every((n, i) => n === i + 1), `the new talker's messages: ${got}`);
  ctx.facts.traffic = got.length;
  await other.stop();
  await checkArena(ctx);
}

/**
 * demo_talker@graph.endpoint_written: the C++ talker is killed creating its
 * publisher (the registry lock held); a process blocked on the lock goes on.
 */
async function demoTalkerCreating(ctx) {
  const [late] = await procs(ctx, 'late');
  const talker = await spawnArmed(ctx, 'talker', ['--ros-args', '-r', '__node:=talker_a'], 'graph.endpoint_written');
  await programStopped(ctx, talker, 'graph.endpoint_written');
  const blocked = await blockOnLock(ctx, 'graph.endpoint_written', late);
  await stopProgram(ctx, talker);
  await unblocked(ctx, blocked);
  await checkArena(ctx);
  const sSub = await late.endpoint('subscription', await late.call('node', 'listener'), '/chatter', KEEP_ALL, CHATTER);
  const next = late.call('waitTake', sSub, 'subscription', 3, STUCK_MS, true);
  const other = await ctx.rt.spawn({ url: ctx.env.demo.talker, args: ['--ros-args', '-p', 'rate:=100'], name: 'talker' });
  ctx.step = 'a new talker\'s messages';
  expect((await next).length === 3, 'a new talker\'s messages did not arrive');
  await other.stop();
  ctx.facts.traffic = 3;
}

/** An AddTwoInts request (CDR): a, b as int64. */
function addTwoInts(a, b) {
  const u8 = new Uint8Array(20);
  const v = new DataView(u8.buffer);
  u8[1] = 1;
  v.setBigInt64(4, BigInt(a), true);
  v.setBigInt64(12, BigInt(b), true);
  return u8;
}

/**
 * demo_server@publish.writing: the demo's C++ add_two_ints_server is killed
 * in the middle of its answer; the tools' call ends with an error at once,
 * and a new server answers.
 */
async function demoServer(ctx) {
  const server = await spawnArmed(ctx, 'add_two_ints_server', [], 'publish.writing');
  const hasServer = (g) => g.services.some((s) => s.name === '/add_two_ints' && s.servers.length);
  await graphHolds(ctx, hasServer, 'the server');
  const tools = await ctx.rt.tools();
  const spec = { service: '/add_two_ints', type: 'demo_interfaces/srv/AddTwoInts', timeoutMs: 20000 };
  const call = tools.call(spec, addTwoInts(2, 3));
  call.catch(() => {});
  await programStopped(ctx, server, 'publish.writing');
  const t = performance.now();
  await stopProgram(ctx, server);
  let message = null;
  await call.then(() => {}, (e) => { message = e.message; });
  const ms = performance.now() - t;
  expect(message && /went away/.test(message), `the call to the killed server ended with: ${message}`);
  expect(ms < spec.timeoutMs, 'the call ended only at its timeout');
  ctx.facts.call = `failed ${Math.round(ms)} ms after the kill (timeout ${spec.timeoutMs} ms): ${message}`;
  const again = await ctx.rt.spawn({ url: ctx.env.demo.add_two_ints_server, args: [], name: 'add_two_ints_server' });
  await graphHolds(ctx, hasServer, 'the new server');
  const r = await tools.call(spec, addTwoInts(40, 2));
  const sum = new DataView(r.data.buffer, r.data.byteOffset).getBigInt64(4, true);
  expect(sum === 42n, `the new server answered ${sum}`);
  ctx.facts.calls = 1;
  await again.stop();
  await checkArena(ctx);
}

/** Every scenario: name -> function(ctx); `node` only where browsers cannot tell. */
export const SCENARIOS = {
  'publish.locked': (ctx) => publishKill(ctx, 'publish.locked'),
  'publish.writing': (ctx) => publishKill(ctx, 'publish.writing'),
  'publish.committed': (ctx) => publishKill(ctx, 'publish.committed'),
  'publish.unrung': (ctx) => publishKill(ctx, 'publish.unrung'),
  'publish.blocked': publishBlocked,
  'publish.renewing': (ctx) => publishKill(ctx, 'publish.renewing'),
  'take.found': (ctx) => takeKill(ctx, 'take.found'),
  'take.copied': (ctx) => takeKill(ctx, 'take.copied'),
  'take.consumed': (ctx) => takeKill(ctx, 'take.consumed'),
  'take.reaping': (ctx) => takeReaping(ctx, 'take.reaping'),
  'reap@arena.freeing': (ctx) => takeReaping(ctx, 'arena.freeing'),
  'request@publish.writing': (ctx) => requestKill(ctx, 'publish.writing'),
  'request@publish.unrung': (ctx) => requestKill(ctx, 'publish.unrung'),
  'reply@take.copied': (ctx) => replyKill(ctx, 'take.copied'),
  'reply@publish.locked': (ctx) => replyKill(ctx, 'publish.locked'),
  'reply@publish.writing': (ctx) => replyKill(ctx, 'publish.writing'),
  'reply@publish.unrung': (ctx) => replyKill(ctx, 'publish.unrung'),
  'graph.locked': (ctx) => graphKill(ctx, 'graph.locked'),
  'graph.node_written': (ctx) => graphKill(ctx, 'graph.node_written'),
  'graph.endpoint_written': (ctx) => graphKill(ctx, 'graph.endpoint_written'),
  'graph.matching': (ctx) => graphKill(ctx, 'graph.matching'),
  'graph.removing': (ctx) => graphKill(ctx, 'graph.removing'),
  'graph.changed': (ctx) => graphKill(ctx, 'graph.changed'),
  'arena.freeing': (ctx) => arenaKill(ctx, 'arena.freeing'),
  'arena.releasing': (ctx) => arenaKill(ctx, 'arena.releasing'),
  'event.locked': eventKill,
  'wait.sleeping': waitKill,
  'tools@publish.writing': (ctx) => toolsKill(ctx, 'publish.writing'),
  'tools@graph.locked': (ctx) => toolsKill(ctx, 'graph.locked'),
  tools_exit: toolsExit,
  'demo_talker@publish.writing': demoTalker,
  'demo_talker@graph.endpoint_written': demoTalkerCreating,
  'demo_server@publish.writing': demoServer,
};

/** Scenarios that run the demo's wasm programs (env.demo: executable name -> URL). */
export const DEMO = new Set(Object.keys(SCENARIOS).filter((n) => n.startsWith('demo_')));

/** Scenarios that need Node.js (a browser gives no event when a worker ends). */
export const NODE_ONLY = new Set(['tools_exit']);

/**
 * Run one scenario.
 * @param {string} name
 * @param {object} env {Runtime, ProgramWorker, layout (layout.mjs), src: the URL of
 *   wasm_js/src/ (with its slash), workerUrl: bus_faults_worker.mjs, demo: the demo's
 *   executables (name -> URL or path) for the demo_ scenarios}
 * @returns {Promise<{scenario: string, ok: boolean, error?: string, step?: string, facts: object, ms: number}>}
 */
export async function runScenario(name, env) {
  const fn = SCENARIOS[name];
  if (!fn) return { scenario: name, ok: false, error: `unknown scenario '${name}'`, facts: {}, ms: 0 };
  if (DEMO.has(name) && !env.demo) return { scenario: name, ok: false, error: 'no demo install given (--demo)', facts: {}, ms: 0 };
  const t0 = performance.now();
  const rt = await env.Runtime.create({ warmWorkers: 0, maxEndpoints: 64 });
  const ctx = { env, rt, procs: [], facts: {}, errors: [], step: 'setting up' };
  let timer;
  const timeout = new Promise((_, reject) => {
    timer = setTimeout(() => reject(new Failure(`timed out after ${SCENARIO_MS} ms at: ${ctx.step}`)), SCENARIO_MS);
  });
  let result;
  try {
    await Promise.race([fn(ctx), timeout]);
    result = { ok: ctx.errors.length === 0, error: ctx.errors.join('; ') || undefined };
  } catch (e) {
    result = { ok: false, error: e instanceof Failure ? e.message : `${e.message}\n${e.stack}`, step: ctx.step };
  } finally {
    clearTimeout(timer);
  }
  for (const p of ctx.procs) if (!p.killed) await p.worker.terminate();
  await Promise.race([rt.close(), sleep(5000)]);
  ctx.facts.bus = rt.bus.memory ? 'WebAssembly.Memory' : 'SharedArrayBuffer';
  return { scenario: name, ...result, facts: ctx.facts, ms: Math.round(performance.now() - t0) };
}
