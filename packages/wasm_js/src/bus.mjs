// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * The bus: one attachment of a thread to the shared memory of a page (or
 * Node.js process), with its registry of processes, nodes, endpoints and
 * links. Every thread of every node attaches a `Bus` to the same buffer.
 *
 * This class holds the memory, its views and the doorbells, and gives the
 * rooms of src/bus/ one face:
 *   lock.mjs      the futex lock (registry, writer and event locks)
 *   arena.mjs     blocks, strings and free table records
 *   registry.mjs  process, node and endpoint records; gids
 *   matching.mjs  matching endpoints into links
 *   graph.mjs     graph snapshots
 *   recovery.mjs  the arena repaired after a dead owner's lock is stolen
 *   faults.mjs    named fault points where the fault tests kill a thread
 *
 * Registry mutations happen under one short lock that records its owner's
 * process id; each record is committed by a final store of its STATE word
 * and retracted by clearing it first, and every committed change bumps the
 * graph version (which is also the graph doorbell). The page's main thread
 * never blocks on the lock: it uses `lockAsync()`. Whoever steals the lock
 * from a dead owner first repairs what its critical section may have left
 * half done (bus/recovery.mjs, docs/faults.md).
 *
 * @module bus
 */

import {
  DEFAULTS, ENDPOINT, HEADER, HEADER_WORDS, KIND_CLIENT, KIND_NODE, KIND_PUBLISHER, KIND_SERVICE,
  KIND_SUBSCRIPTION, LAYOUT_VERSION, LINK, LOCK_CONTENDED, LOCK_OWNER_MASK, MAGIC, NODE,
  PROC_ALIVE, PROC_DEAD, PROC_FREE, PROCESS, REC_DYING, REC_ZOMBIE,
} from './layout.mjs';
import * as arena from './bus/arena.mjs';
import { now, waitAsyncAlive } from './bus/clock.mjs';
import { BusError, Code } from './bus/errors.mjs';
import { snapshot } from './bus/graph.mjs';
import { lock, lockOwner, lockStep, tryLock, unlock } from './bus/lock.mjs';
import { recoverArena } from './bus/recovery.mjs';
import * as registry from './bus/registry.mjs';
import { multiMemorySupported } from './copier.mjs';

export { BusError, Code, now, waitAsyncAlive };

/** How often lockAsync() re-checks whether the lock's owner died (ms). */
const LOCK_RECHECK_MS = 50;
const PAGE = arena.PAGE;

/** True when `handle` is a WebAssembly.Memory (a bus handle is that or a SharedArrayBuffer). */
function isWasmMemory(handle) {
  return typeof WebAssembly === 'object' && handle instanceof WebAssembly.Memory;
}

/** The smallest power of two >= n (at least 2): ring sizes. */
function nextPow2(n) {
  let p = 2;
  while (p < n) p *= 2;
  return p;
}

/** Largest ring (slots) a writer may ask for. */
export const MAX_RING_SLOTS = 1 << 20;

/**
 * One attachment to a bus: a SharedArrayBuffer, or a shared
 * WebAssembly.Memory where the engine can copy between memories (then the
 * nodes' wasm heaps copy to and from it with memory.copy, see copier.mjs).
 */
export class Bus {
  /**
   * Create a new bus in a new shared WebAssembly.Memory where the engine
   * supports multi-memory, else in a new (growable where supported)
   * SharedArrayBuffer.
   * @param {object} [options]
   * @param {number} [options.maxMessageBytes] largest message (default 64 MiB)
   * @param {number} [options.initialBytes] initial buffer size (default 16 MiB)
   * @param {number} [options.maxBytes] largest buffer size (default 1 GiB)
   * @param {number} [options.maxProcesses] process table size
   * @param {number} [options.maxNodes] node table size
   * @param {number} [options.maxEndpoints] endpoint table size
   * @param {number} [options.maxLinks] link table size (matched writer/reader pairs)
   * @param {boolean} [options.wasmMemory] false: always a SharedArrayBuffer
   * @returns {Bus}
   */
  static create(options = {}) {
    const o = { ...DEFAULTS };
    for (const [k, v] of Object.entries(options)) {
      if (v === undefined) continue;
      if (!(k in DEFAULTS)) continue;
      if (!Number.isInteger(v) || v <= 0) {
        throw new BusError(Code.INVALID_ARGUMENT, `invalid bus option ${k}=${JSON.stringify(v)}: expected a positive integer`);
      }
      o[k] = v;
    }
    if (o.maxBytes > 0x7ff00000) {
      throw new BusError(Code.INVALID_ARGUMENT, `invalid bus option maxBytes=${o.maxBytes}: at most ${0x7ff00000} bytes (2 GiB - 1 MiB)`);
    }
    if (o.maxMessageBytes > o.maxBytes / 2) {
      throw new BusError(Code.INVALID_ARGUMENT,
        `invalid bus options: maxMessageBytes=${o.maxMessageBytes} needs maxBytes >= ${2 * o.maxMessageBytes} (got ${o.maxBytes})`);
    }
    const procOff = HEADER_WORDS;
    const nodeOff = procOff + o.maxProcesses * PROCESS.WORDS;
    const epOff = nodeOff + o.maxNodes * NODE.WORDS;
    const linkOff = epOff + o.maxEndpoints * ENDPOINT.WORDS;
    const arenaBase = Math.ceil(((linkOff + o.maxLinks * LINK.WORDS) * 4) / 64) * 64;
    const initial = Math.max(o.initialBytes, arenaBase + 1024 * 1024);
    if (initial > o.maxBytes) {
      throw new BusError(Code.INVALID_ARGUMENT, `invalid bus options: tables need ${initial} bytes, more than maxBytes=${o.maxBytes}`);
    }
    let sab;
    let memory = null;
    if (options.wasmMemory !== false && multiMemorySupported()) {
      try {
        memory = new WebAssembly.Memory({
          initial: Math.ceil(initial / PAGE), maximum: Math.floor(o.maxBytes / PAGE), shared: true,
        });
        sab = memory.buffer;
      } catch (e) {
        memory = null; // e.g. no room for the reservation: a plain buffer will do
      }
    }
    if (memory === null) {
      try {
        sab = new SharedArrayBuffer(initial, { maxByteLength: o.maxBytes });
      } catch (e) {
        throw new BusError(Code.BAD_ALLOC, `cannot allocate the bus (${initial} bytes, up to ${o.maxBytes}): ${e.message}`);
      }
    }
    const i32 = new Int32Array(sab);
    i32[HEADER.VERSION] = LAYOUT_VERSION;
    i32[HEADER.BUS_ID] = (Math.random() * 0x7fffffff) | 0;
    i32[HEADER.MAX_MESSAGE] = o.maxMessageBytes;
    i32[HEADER.MAX_BYTES_MB] = Math.floor(o.maxBytes / (1024 * 1024));
    i32[HEADER.PROC_CAP] = o.maxProcesses;
    i32[HEADER.NODE_CAP] = o.maxNodes;
    i32[HEADER.EP_CAP] = o.maxEndpoints;
    i32[HEADER.LINK_CAP] = o.maxLinks;
    i32[HEADER.PROC_OFF] = procOff;
    i32[HEADER.NODE_OFF] = nodeOff;
    i32[HEADER.EP_OFF] = epOff;
    i32[HEADER.LINK_OFF] = linkOff;
    i32[HEADER.ARENA_BASE] = arenaBase;
    i32[HEADER.ARENA_TOP] = arenaBase;
    // Process index 0 is never used, so that pid 0 can mean "nobody".
    i32[HEADER.PROC_HWM] = 1;
    i32[HEADER.PROC_HINT] = 1;
    Atomics.store(i32, HEADER.MAGIC, MAGIC);
    return new Bus(memory || sab);
  }

  /**
   * Attach to an existing bus (in another thread).
   * @param {SharedArrayBuffer|WebAssembly.Memory} handle another attachment's `handle`
   * @returns {Bus}
   */
  static attach(handle) {
    const sab = isWasmMemory(handle) ? handle.buffer : handle;
    if (!(sab instanceof SharedArrayBuffer)) {
      throw new BusError(Code.INVALID_ARGUMENT, `cannot attach to the bus: expected a SharedArrayBuffer or a shared WebAssembly.Memory, got ${Object.prototype.toString.call(handle)}`);
    }
    const i32 = new Int32Array(sab, 0, HEADER_WORDS);
    if (Atomics.load(i32, HEADER.MAGIC) !== MAGIC || i32[HEADER.VERSION] !== LAYOUT_VERSION) {
      throw new BusError(Code.ERROR,
        `cannot attach to the bus: not a wasm_js bus of layout version ${LAYOUT_VERSION} (magic ${i32[HEADER.MAGIC]}, version ${i32[HEADER.VERSION]}); were the runtime and the executable built from different wasm_js versions?`);
    }
    return new Bus(handle);
  }

  /** @param {SharedArrayBuffer|WebAssembly.Memory} handle */
  constructor(handle) {
    /** The bus memory when it is a WebAssembly.Memory, else null. */
    this.memory = isWasmMemory(handle) ? handle : null;
    /** The buffer this thread's views cover (a shared memory's buffer is renewed as it grows). */
    this.sab = this.memory ? this.memory.buffer : handle;
    this._views(this.sab.byteLength);
    const h = this.i32;
    this.id = h[HEADER.BUS_ID];
    this.procOff = h[HEADER.PROC_OFF];
    this.nodeOff = h[HEADER.NODE_OFF];
    this.epOff = h[HEADER.EP_OFF];
    this.linkOff = h[HEADER.LINK_OFF];
    this.procCap = h[HEADER.PROC_CAP];
    this.nodeCap = h[HEADER.NODE_CAP];
    this.epCap = h[HEADER.EP_CAP];
    this.linkCap = h[HEADER.LINK_CAP];
    this.maxMessage = h[HEADER.MAX_MESSAGE];
    this.maxBytes = h[HEADER.MAX_BYTES_MB] * 1024 * 1024;
    this.growable = this.memory !== null || !!this.sab.growable;
    /**
     * A test's fault point (bus/faults.mjs), called with a point's name at
     * each named point of this thread's bus operations; null (always, but
     * in the fault tests).
     * @type {?function(string): void}
     */
    this.faultPoint = null;
    /**
     * What this thread repaired when it last stole the registry lock from a
     * dead owner (bus/recovery.mjs), or null.
     * @type {?{pid: number, ok: boolean, blocks: number, leaked: number, orphans: number, slots: number}}
     */
    this.lastRecovery = null;
  }

  /** What another thread passes to Bus.attach(): the memory or the buffer. */
  get handle() {
    return this.memory || this.sab;
  }

  /** The current size of the bus in bytes (it may have grown in another thread). */
  byteLength() {
    if (this.memory !== null) this.sab = this.memory.buffer;
    return this.sab.byteLength;
  }

  // Fixed-length views: V8 accesses length-tracking views of a growable
  // SharedArrayBuffer about 5x slower, so each thread keeps views of the size
  // it last saw and renews them when it meets an offset beyond them.
  _views(len) {
    this.i32 = new Int32Array(this.sab, 0, len >> 2);
    this.u8 = new Uint8Array(this.sab, 0, len);
    this.f64 = new Float64Array(this.sab, 0, len >> 3);
  }

  /**
   * Make sure the views cover the whole (possibly grown) buffer.
   * @returns {boolean} true when they were renewed
   */
  refreshViews() {
    const len = this.byteLength();
    if (this.u8.length === len) return false;
    this._views(len);
    return true;
  }

  /** Word index of process record `pid`. */
  proc(pid) { return this.procOff + pid * PROCESS.WORDS; }
  /** Word index of node record `i`. */
  node(i) { return this.nodeOff + i * NODE.WORDS; }
  /** Word index of endpoint record `i`. */
  ep(i) { return this.epOff + i * ENDPOINT.WORDS; }
  /** Word index of link record `i`. */
  link(i) { return this.linkOff + i * LINK.WORDS; }

  /** The graph version (bumped by every registry change). */
  graphVersion() { return Atomics.load(this.i32, HEADER.GRAPH_VERSION); }

  // ---------------------------------------------------------------- lock

  /**
   * Take the registry lock, blocking (workers only).
   *
   * Workers never steal the lock: when its owner dies, the runtime's cleanup
   * steals it and its unlock() wakes us. A thread whose own process was
   * declared dead (its worker is being terminated) cannot take it.
   * @param {number} pid the caller's process id
   */
  lock(pid) {
    lock(this.i32, HEADER.LOCK, pid);
    if (Atomics.load(this.i32, this.proc(pid) + PROCESS.STATE) !== PROC_ALIVE) {
      this.unlock(pid);
      throw new BusError(Code.ERROR, `process ${pid} was declared dead by the runtime (its worker is being stopped)`);
    }
  }

  /**
   * Try to take the registry lock without blocking; also steals it from a dead
   * owner, then repairs the arena (bus/recovery.mjs) before returning.
   * @param {number} pid
   * @returns {boolean}
   */
  tryLock(pid) {
    if (tryLock(this.i32, HEADER.LOCK, pid)) return true;
    const v = Atomics.load(this.i32, HEADER.LOCK);
    return v !== 0 && this._stealIfOwnerDead(v, pid | LOCK_CONTENDED);
  }

  /**
   * Take the registry lock without ever blocking the calling thread (page main thread).
   * @param {number} pid
   * @returns {Promise<void>}
   */
  async lockAsync(pid) {
    if (this.tryLock(pid)) return;
    const i32 = this.i32;
    for (;;) {
      const v = Atomics.load(i32, HEADER.LOCK);
      if (v !== 0 && this._stealIfOwnerDead(v, pid | LOCK_CONTENDED)) return;
      const held = lockStep(i32, HEADER.LOCK, pid);
      if (held === 0) return;
      // bounded: re-check now and then whether the owner died holding the lock
      await waitAsyncAlive(i32, HEADER.LOCK, held, LOCK_RECHECK_MS);
    }
  }

  /**
   * Give a dead process that holds the lock `ms` to release it (a terminated
   * worker, or one of its pthreads, may still be finishing a mutation), without
   * blocking. Then lockAsync() steals it if it is still held.
   * @param {number} pid the dead process
   * @param {number} ms
   */
  async releaseGrace(pid, ms) {
    const deadline = now() + ms;
    for (;;) {
      const v = Atomics.load(this.i32, HEADER.LOCK);
      const left = deadline - now();
      if ((v & LOCK_OWNER_MASK) !== pid || left <= 0) return;
      await waitAsyncAlive(this.i32, HEADER.LOCK, v, left);
    }
  }

  _stealIfOwnerDead(v, newValue) {
    const owner = v & LOCK_OWNER_MASK;
    if (owner <= 0 || owner >= this.procCap) return false;
    const st = Atomics.load(this.i32, this.proc(owner) + PROCESS.STATE);
    if (st === PROC_ALIVE) return false;
    if (Atomics.compareExchange(this.i32, HEADER.LOCK, v, newValue) !== v) return false;
    // The dead owner may have stopped in the middle of its critical section.
    this.lastRecovery = { pid: owner, ...recoverArena(this, owner) };
    return true;
  }

  /**
   * Release the registry lock (only if the caller still holds it).
   * @param {number} pid
   */
  unlock(pid) {
    if (!unlock(this.i32, HEADER.LOCK, pid)) {
      // Stolen: the runtime declared us dead. Leave the new owner's lock alone.
      throw new BusError(Code.ERROR, `registry lock released by process ${pid} but held by ${lockOwner(this.i32, HEADER.LOCK)} (this process was declared dead)`);
    }
  }

  /** Commit a registry change: bump the graph version and wake graph waiters. */
  bumpGraph() {
    Atomics.add(this.i32, HEADER.GRAPH_VERSION, 1);
    Atomics.notify(this.i32, HEADER.GRAPH_VERSION);
  }

  // ---------------------------------------------------------------- doorbells

  /**
   * Ring the doorbell of process `pid`, after committing what its waits check.
   *
   * Touches the doorbell only when a thread of `pid` counts itself as a
   * sleeper. Waiters register as sleepers before they read the doorbell and
   * check (BusClient.wait), so with seq-cst operations either this load sees
   * the registration, or the registration (and the check after it) comes
   * after our commit and sees it: no wake-up is lost.
   * @param {number} pid
   */
  ring(pid) {
    const i32 = this.i32;
    const base = this.proc(pid);
    if (Atomics.load(i32, base + PROCESS.SLEEPERS) > 0) {
      Atomics.add(i32, base + PROCESS.BELL, 1);
      Atomics.notify(i32, base + PROCESS.BELL);
    }
  }

  /** Ring every live process. */
  ringAll() {
    const hwm = Atomics.load(this.i32, HEADER.PROC_HWM);
    for (let pid = 1; pid < hwm; pid++) {
      if (Atomics.load(this.i32, this.proc(pid) + PROCESS.STATE) !== PROC_FREE) this.ring(pid);
    }
  }

  /** Declare process `pid` dead (before its cleanup): its threads can no longer take the lock. */
  markDead(pid) {
    Atomics.store(this.i32, this.proc(pid) + PROCESS.STATE, PROC_DEAD);
  }

  /**
   * Atomics.waitAsync on the graph version while it is `version` (main thread).
   * @returns {{async: boolean, value: Promise<string>|string}}
   */
  waitGraphAsync(version) {
    return Atomics.waitAsync(this.i32, HEADER.GRAPH_VERSION, version);
  }

  /** True while process `pid` is alive. */
  processAlive(pid) {
    return pid > 0 && pid < this.procCap && Atomics.load(this.i32, this.proc(pid) + PROCESS.STATE) === PROC_ALIVE;
  }

  // ------------------------------------------------ arena (bus/arena.mjs)

  /**
   * Allocate an arena block of at least `bytes` bytes (registry lock held).
   * @param {number} bytes
   * @param {number} owner pid, recorded in the block header
   * @returns {number} payload byte offset, or 0 when the bus is full
   */
  alloc(bytes, owner) { return arena.alloc(this, bytes, owner); }

  /** Payload capacity of the block at `off`. */
  blockCapacity(off) { return arena.blockCapacity(this, off); }

  /** Free a block (registry lock held); it is reused after GRACE_MS. */
  free(off) { arena.free(this, off); }

  /**
   * Give the ring slot at word `slot` a new block of at least `bytes` bytes
   * (takes the registry lock).
   * @returns {number} the block, or 0 when the bus is full
   */
  renewSlotBlock(slot, bytes, owner) { return arena.renewSlotBlock(this, slot, bytes, owner); }

  /** Bytes of arena in use and the current / maximum buffer size (diagnostics). */
  memoryUsage() { return arena.memoryUsage(this); }

  /**
   * Allocate one block holding several UTF-8 strings back to back (lock held).
   * @returns {{off: number, lens: number[]}|null}
   */
  allocStrings(strings, owner) { return arena.allocStrings(this, strings, owner); }

  /** Decode `len` UTF-8 bytes at byte offset `off`. */
  readString(off, len) { return arena.readString(this, off, len); }

  // ------------------------------------------ registry (bus/registry.mjs)

  /**
   * Register a new process (lock held).
   * @param {number} kind PROC_KIND_*
   * @returns {number} pid, or 0 when the process table is full
   */
  allocProcess(kind) { return registry.allocProcess(this, kind); }

  /**
   * Create a node record (lock held).
   * @returns {{index: number, serial: number, nameTaken: boolean}}
   */
  createNode(spec) { return registry.createNode(this, spec); }

  /** Remove a node record and its endpoints (lock held). Idempotent. */
  removeNode(index) { registry.removeNode(this, index); }

  /**
   * Create an endpoint and match it with its peers (lock held); see registry.createEndpoint.
   * @returns {{index: number, serial: number, touched: Set<number>}} touched: pids to ring
   */
  createEndpoint(spec) { return registry.createEndpoint(this, spec); }

  /**
   * Remove an endpoint from the graph (lock held). Idempotent.
   * @returns {Set<number>} pids of the peers that lost a match (to ring)
   */
  removeEndpoint(index) { return registry.removeEndpoint(this, index); }

  /** Drop links from zombie writers that their readers have drained (lock held). */
  reapDrainedLinks(links) { registry.reapDrainedLinks(this, links); }

  /** Remove everything a dead process owned (lock held). Idempotent. */
  cleanupProcess(pid) { registry.cleanupProcess(this, pid); }

  /** Return a dead process' record to the free pool (lock held). */
  releaseProcess(pid) { registry.releaseProcess(this, pid); }

  /**
   * The 16-byte gid of an entity: bus id, pid, (kind << 24 | index), serial.
   * @returns {Int32Array}
   */
  gidWords(kind, index) { return registry.gidWords(this, kind, index); }

  /** Find the endpoint a gid names (four words), or -1 if it is gone. */
  endpointOfGid(w) { return registry.endpointOfGid(this, w); }

  // ------------------------------------------------ graph (bus/graph.mjs)

  /**
   * A consistent snapshot of the graph.
   * @param {object} [filter]
   * @param {number} [filter.domain] only this domain
   * @returns {{version: number, nodes: object[], endpoints: object[]}}
   */
  snapshot(filter = {}) { return snapshot(this, filter); }
}

export {
  KIND_CLIENT, KIND_NODE, KIND_PUBLISHER, KIND_SERVICE, KIND_SUBSCRIPTION, PROC_ALIVE, PROC_DEAD,
  PROC_FREE, REC_DYING, REC_ZOMBIE, nextPow2,
};
