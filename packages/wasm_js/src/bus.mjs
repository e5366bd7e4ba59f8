// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * The bus: shared memory, the registry of processes, nodes, endpoints and
 * links, the arena allocator and the registry lock. Every thread of every
 * node attaches a `Bus` to the same SharedArrayBuffer.
 *
 * Registry mutations happen under one short lock that records its owner's
 * process id; each record is committed by a final store of its STATE word
 * and retracted by clearing it first, and every committed change bumps the
 * graph version (which is also the graph doorbell). The page's main thread
 * never blocks on the lock: it uses `lockAsync()`.
 *
 * @module bus
 */

import { BLOCK, BLOCK_FREE, BLOCK_HEADER_BYTES, BLOCK_QUARANTINE, BLOCK_USED, DEFAULTS, ENDPOINT, EP_FLAG_IGNORE_LOCAL, GRACE_MS, HEADER, HEADER_WORDS, KIND_CLIENT, KIND_NODE, KIND_PUBLISHER, KIND_SERVICE, KIND_SUBSCRIPTION, LAYOUT_VERSION, LINK, LINK_BEST_EFFORT, LINK_BLOCKING, LINK_TARGETED, LOCK_CONTENDED, LOCK_OWNER_MASK, MAGIC, MIN_CLASS_SHIFT, NODE, PROC_ALIVE, PROC_DEAD, PROC_FREE, PROCESS, QOS, REC_ALIVE, REC_FREE, SIZE_CLASSES, SLOT,
} from './layout.mjs';
import { Code } from './abi/bus_abi.mjs';
import { multiMemorySupported } from './copier.mjs';
import { checkCompatible, decodeQos, Durability, durationMs, History, Reliability } from './qos.mjs';

/** Status codes; the numbers equal wasm_cpp::Code (abi/bus_abi.mjs). */
export { Code };

/** An error of a bus operation, with a wasm_cpp::Code. */
export class BusError extends Error {
  /**
   * @param {number} code one of Code
   * @param {string} message what failed, where, and what to do
   */
  constructor(code, message) {
    super(message);
    this.name = 'BusError';
    this.code = code;
  }
}

export const REC_DYING = 2;
/** A removed writer whose ring is kept until its readers drained it. */
export const REC_ZOMBIE = 3;

const encoder = new TextEncoder();
const decoder = new TextDecoder();

/** How often lockAsync() re-checks whether the lock's owner died (ms). */
const LOCK_RECHECK_MS = 50;
/** WebAssembly page size: a bus that is a WebAssembly.Memory grows by whole pages. */
const PAGE = 65536;

/** True when `handle` is a WebAssembly.Memory (a bus handle is that or a SharedArrayBuffer). */
function isWasmMemory(handle) {
  return typeof WebAssembly === 'object' && handle instanceof WebAssembly.Memory;
}

/**
 * Atomics.waitAsync for at most `ms`, with a timer beside it: a pending
 * waitAsync does not keep Node.js's event loop alive, so a process whose
 * only pending work is this wait would otherwise quit in the middle of it
 * (exit code 13). The timer also bounds the wait where the notify never
 * comes (an owner that died holding the lock).
 * @param {Int32Array} i32
 * @param {number} index
 * @param {number} value
 * @param {number} ms
 * @returns {Promise<void>}
 */
export async function waitAsyncAlive(i32, index, value, ms) {
  const r = Atomics.waitAsync(i32, index, value, ms);
  if (!r.async) return;
  let timer;
  const alive = new Promise((resolve) => {
    timer = setTimeout(resolve, ms + 1);
  });
  try {
    await Promise.race([r.value, alive]);
  } finally {
    clearTimeout(timer);
  }
}

// The Performance object, looked up once: in a Chromium worker the global
// `performance` getter alone costs ~100-200 ns per read (a clock read with
// it: 210-340 ns, without it: 90-120 ns), and publish reads the clock for
// every message.
const PERF = typeof performance !== 'undefined' ? performance : null;
const ORIGIN = (PERF && PERF.timeOrigin) || 0;
/** Wall-clock milliseconds since the epoch with sub-millisecond resolution. */
export const now = ORIGIN ? () => ORIGIN + PERF.now() : () => Date.now();

function fnv1a(bytes) {
  let h = 0x811c9dc5;
  for (let i = 0; i < bytes.length; i++) {
    h ^= bytes[i];
    h = Math.imul(h, 0x01000193);
  }
  return h | 0;
}

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
    const i32 = this.i32;
    let acquired = false;
    for (let spin = 0; spin < 64 && !acquired; spin++) {
      acquired = Atomics.compareExchange(i32, HEADER.LOCK, 0, pid) === 0;
    }
    while (!acquired) {
      let v = Atomics.load(i32, HEADER.LOCK);
      if (v === 0) {
        acquired = Atomics.compareExchange(i32, HEADER.LOCK, 0, pid | LOCK_CONTENDED) === 0;
        continue;
      }
      if (!(v & LOCK_CONTENDED)) {
        if (Atomics.compareExchange(i32, HEADER.LOCK, v, v | LOCK_CONTENDED) !== v) continue;
        v |= LOCK_CONTENDED;
      }
      Atomics.wait(i32, HEADER.LOCK, v);
    }
    this._checkAliveOwner(pid);
  }

  _checkAliveOwner(pid) {
    const st = Atomics.load(this.i32, this.proc(pid) + PROCESS.STATE);
    if (st !== PROC_ALIVE) {
      this.unlock(pid);
      throw new BusError(Code.ERROR, `process ${pid} was declared dead by the runtime (its worker is being stopped)`);
    }
  }

  /**
   * Try to take the registry lock without blocking; also steals it from a dead owner.
   * @param {number} pid
   * @returns {boolean}
   */
  tryLock(pid) {
    if (Atomics.compareExchange(this.i32, HEADER.LOCK, 0, pid) === 0) return true;
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
      let v = Atomics.load(i32, HEADER.LOCK);
      // Once we may have waited, take the lock marked contended, like lock():
      // other waiters may still sleep, and our unlock() must wake one of them.
      if (v === 0) {
        if (Atomics.compareExchange(i32, HEADER.LOCK, 0, pid | LOCK_CONTENDED) === 0) return;
        continue;
      }
      if (this._stealIfOwnerDead(v, pid | LOCK_CONTENDED)) return;
      if (!(v & LOCK_CONTENDED)) {
        if (Atomics.compareExchange(i32, HEADER.LOCK, v, v | LOCK_CONTENDED) !== v) continue;
        v |= LOCK_CONTENDED;
      }
      // bounded: re-check now and then whether the owner died holding the lock
      await waitAsyncAlive(i32, HEADER.LOCK, v, LOCK_RECHECK_MS);
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
    return Atomics.compareExchange(this.i32, HEADER.LOCK, v, newValue) === v;
  }

  /**
   * Release the registry lock (only if the caller still holds it).
   * @param {number} pid
   */
  unlock(pid) {
    const i32 = this.i32;
    for (;;) {
      const v = Atomics.load(i32, HEADER.LOCK);
      if ((v & LOCK_OWNER_MASK) !== pid) {
        // Stolen: the runtime declared us dead. Leave the new owner's lock alone.
        throw new BusError(Code.ERROR, `registry lock released by process ${pid} but held by ${v & LOCK_OWNER_MASK} (this process was declared dead)`);
      }
      if (Atomics.compareExchange(i32, HEADER.LOCK, v, 0) !== v) continue; // a waiter marked it contended
      if (v & LOCK_CONTENDED) Atomics.notify(i32, HEADER.LOCK, 1);
      return;
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

  /** True while process `pid` is alive. */
  processAlive(pid) {
    return pid > 0 && pid < this.procCap && Atomics.load(this.i32, this.proc(pid) + PROCESS.STATE) === PROC_ALIVE;
  }

  // ---------------------------------------------------------------- arena

  /**
   * Allocate an arena block of at least `bytes` bytes (registry lock held).
   * @param {number} bytes
   * @param {number} owner pid, recorded in the block header
   * @returns {number} payload byte offset, or 0 when the bus is full
   */
  alloc(bytes, owner) {
    this._releaseQuarantine();
    let shift = MIN_CLASS_SHIFT;
    while ((1 << shift) < bytes && shift < 31) shift++;
    if ((2 ** shift) < bytes) return 0;
    const cls = shift - MIN_CLASS_SHIFT;
    if (cls >= SIZE_CLASSES) return 0;
    const i32 = this.i32;
    const head = i32[HEADER.FREE_BASE + cls];
    if (head !== 0) {
      const hw = (head - BLOCK_HEADER_BYTES) >> 2;
      i32[HEADER.FREE_BASE + cls] = i32[hw + BLOCK.NEXT];
      i32[hw + BLOCK.STATE] = BLOCK_USED;
      i32[hw + BLOCK.OWNER] = owner;
      i32[hw + BLOCK.NEXT] = 0;
      i32[HEADER.ARENA_USED] += 2 ** shift;
      return head;
    }
    const top = i32[HEADER.ARENA_TOP];
    const end = top + BLOCK_HEADER_BYTES + 2 ** shift;
    if (end > this.byteLength() && !this._grow(end)) return 0;
    const ri32 = this.i32;
    const hw = top >> 2;
    ri32[hw + BLOCK.CLASS] = cls;
    ri32[hw + BLOCK.STATE] = BLOCK_USED;
    ri32[hw + BLOCK.OWNER] = owner;
    ri32[hw + BLOCK.NEXT] = 0;
    ri32[HEADER.ARENA_TOP] = end; // commit
    ri32[HEADER.ARENA_USED] += 2 ** shift;
    return top + BLOCK_HEADER_BYTES;
  }

  /** Payload capacity of the block at `off`. */
  blockCapacity(off) {
    return 2 ** (this.i32[((off - BLOCK_HEADER_BYTES) >> 2) + BLOCK.CLASS] + MIN_CLASS_SHIFT);
  }

  /**
   * Free a block (registry lock held). It is reused only after GRACE_MS,
   * since a reader may still be copying from it (readers re-validate).
   * @param {number} off payload byte offset
   */
  free(off) {
    if (!off) return;
    const i32 = this.i32;
    const hw = (off - BLOCK_HEADER_BYTES) >> 2;
    if (i32[hw + BLOCK.STATE] !== BLOCK_USED) return;
    i32[hw + BLOCK.STATE] = BLOCK_QUARANTINE;
    i32[hw + BLOCK.NEXT] = 0;
    this.f64[(hw + BLOCK.FREED_F64) >> 1] = now();
    i32[HEADER.ARENA_USED] -= 2 ** (i32[hw + BLOCK.CLASS] + MIN_CLASS_SHIFT);
    const tail = i32[HEADER.QUAR_TAIL];
    if (tail) i32[((tail - BLOCK_HEADER_BYTES) >> 2) + BLOCK.NEXT] = off;
    else i32[HEADER.QUAR_HEAD] = off;
    i32[HEADER.QUAR_TAIL] = off;
  }

  _releaseQuarantine() {
    const i32 = this.i32;
    let head = i32[HEADER.QUAR_HEAD];
    if (!head) return;
    const t = now();
    while (head) {
      const hw = (head - BLOCK_HEADER_BYTES) >> 2;
      if (t - this.f64[(hw + BLOCK.FREED_F64) >> 1] < GRACE_MS) break;
      const next = i32[hw + BLOCK.NEXT];
      i32[HEADER.QUAR_HEAD] = next;
      if (!next) i32[HEADER.QUAR_TAIL] = 0;
      const cls = i32[hw + BLOCK.CLASS];
      i32[hw + BLOCK.STATE] = BLOCK_FREE;
      i32[hw + BLOCK.NEXT] = i32[HEADER.FREE_BASE + cls];
      i32[HEADER.FREE_BASE + cls] = head;
      head = next;
    }
  }

  _grow(end) {
    if (!this.growable || end > this.maxBytes) return false;
    const len = this.byteLength();
    let target = Math.max(end, Math.min(this.maxBytes, len + Math.max(len >> 1, 8 * 1024 * 1024)));
    // Whole pages (maxBytes is whole MiB), as a WebAssembly.Memory grows.
    target = Math.min(this.maxBytes, Math.ceil(target / PAGE) * PAGE);
    if (target < end) return false;
    try {
      if (this.memory !== null) {
        this.memory.grow((target - len) / PAGE);
        this.sab = this.memory.buffer;
      } else {
        this.sab.grow(target);
      }
    } catch (e) {
      return false;
    }
    this.refreshViews();
    return true;
  }

  /** Bytes of arena in use and the current / maximum buffer size (diagnostics). */
  memoryUsage() {
    return {
      arenaUsed: Atomics.load(this.i32, HEADER.ARENA_USED),
      bufferBytes: this.byteLength(),
      maxBytes: this.maxBytes,
    };
  }

  // ---------------------------------------------------------------- strings

  /**
   * Allocate one block holding several UTF-8 strings back to back (lock held).
   * @param {string[]} strings
   * @param {number} owner
   * @returns {{off: number, lens: number[]}|null}
   */
  allocStrings(strings, owner) {
    const encoded = strings.map((s) => encoder.encode(s));
    const total = encoded.reduce((a, b) => a + b.length, 0);
    const off = this.alloc(Math.max(total, 1), owner);
    if (!off) return null;
    let p = off;
    for (const b of encoded) {
      this.u8.set(b, p);
      p += b.length;
    }
    return { off, lens: encoded.map((b) => b.length) };
  }

  /** Decode `len` UTF-8 bytes at byte offset `off`. */
  readString(off, len) {
    if (len === 0) return '';
    return decoder.decode(this.u8.slice(off, off + len));
  }

  _bytesEqual(off, bytes) {
    const u8 = this.u8;
    for (let i = 0; i < bytes.length; i++) if (u8[off + i] !== bytes[i]) return false;
    return true;
  }

  // ---------------------------------------------------------------- processes

  /**
   * Register a new process (lock held).
   * @param {number} kind PROC_KIND_*
   * @returns {number} pid, or 0 when the process table is full
   */
  allocProcess(kind) {
    const i32 = this.i32;
    const idx = this._findFree(HEADER.PROC_HINT, HEADER.PROC_HWM, this.procCap, (i) => this.proc(i) + PROCESS.STATE, 1);
    if (idx < 0) return 0;
    const base = this.proc(idx);
    i32[base + PROCESS.KIND] = kind;
    i32[base + PROCESS.SLEEPERS] = 0;
    Atomics.add(i32, base + PROCESS.GEN, 1);
    Atomics.store(i32, base + PROCESS.STATE, PROC_ALIVE);
    return idx;
  }

  _findFree(hintWord, hwmWord, cap, stateWordOf, first = 0) {
    const i32 = this.i32;
    const hint = i32[hintWord] || first;
    for (let n = 0; n < cap; n++) {
      let i = hint + n;
      if (i >= cap) i = first + ((i - first) % (cap - first));
      if (Atomics.load(i32, stateWordOf(i)) === REC_FREE) {
        i32[hintWord] = i + 1 < cap ? i + 1 : first;
        if (i + 1 > i32[hwmWord]) i32[hwmWord] = i + 1;
        return i;
      }
    }
    return -1;
  }

  // ---------------------------------------------------------------- nodes

  /**
   * Create a node record (lock held).
   * @returns {{index: number, serial: number, nameTaken: boolean}}
   */
  createNode({ pid, domain, context, name, namespace, enclave }) {
    const i32 = this.i32;
    let nameTaken = false;
    const nameBytes = encoder.encode(name);
    const nsBytes = encoder.encode(namespace);
    const hwm = i32[HEADER.NODE_HWM];
    for (let i = 0; i < hwm; i++) {
      const b = this.node(i);
      if (Atomics.load(i32, b + NODE.STATE) !== REC_ALIVE || i32[b + NODE.DOMAIN] !== domain) continue;
      if (i32[b + NODE.NAME_LEN] === nameBytes.length && i32[b + NODE.NS_LEN] === nsBytes.length &&
          this._bytesEqual(i32[b + NODE.STR_OFF], nameBytes) &&
          this._bytesEqual(i32[b + NODE.STR_OFF] + nameBytes.length, nsBytes)) {
        nameTaken = true;
        break;
      }
    }
    const idx = this._findFree(HEADER.NODE_HINT, HEADER.NODE_HWM, this.nodeCap, (i) => this.node(i) + NODE.STATE);
    if (idx < 0) {
      throw new BusError(Code.BAD_ALLOC, `cannot create node '${name}': the bus node table is full (${this.nodeCap} nodes); start the Runtime with a larger maxNodes`);
    }
    const strs = this.allocStrings([name, namespace, enclave], pid);
    if (!strs) throw this._fullError(`node '${name}'`);
    const b = this.node(idx);
    const serial = Atomics.add(i32, HEADER.SERIAL, 1) + 1;
    i32[b + NODE.PID] = pid;
    i32[b + NODE.DOMAIN] = domain;
    i32[b + NODE.CONTEXT] = context;
    i32[b + NODE.SERIAL] = serial;
    i32[b + NODE.STR_OFF] = strs.off;
    i32[b + NODE.NAME_LEN] = strs.lens[0];
    i32[b + NODE.NS_LEN] = strs.lens[1];
    i32[b + NODE.ENCLAVE_LEN] = strs.lens[2];
    Atomics.store(i32, b + NODE.STATE, REC_ALIVE);
    return { index: idx, serial, nameTaken };
  }

  /** Remove a node record and its endpoints (lock held). Idempotent. */
  removeNode(index) {
    const i32 = this.i32;
    const b = this.node(index);
    const st = Atomics.load(i32, b + NODE.STATE);
    if (st === REC_FREE) return;
    Atomics.store(i32, b + NODE.STATE, REC_DYING);
    const hwm = i32[HEADER.EP_HWM];
    for (let e = 0; e < hwm; e++) {
      const eb = this.ep(e);
      if (Atomics.load(i32, eb + ENDPOINT.STATE) !== REC_FREE && i32[eb + ENDPOINT.NODE] === index &&
          i32[eb + ENDPOINT.PID] === i32[b + NODE.PID]) {
        this.removeEndpoint(e);
      }
    }
    this.free(i32[b + NODE.STR_OFF]);
    Atomics.store(i32, b + NODE.STATE, REC_FREE);
  }

  _fullError(what) {
    const u = this.memoryUsage();
    return new BusError(Code.BAD_ALLOC,
      `cannot create ${what}: bus memory exhausted (${u.arenaUsed} bytes in use, buffer ${u.bufferBytes} of at most ${u.maxBytes} bytes); start the Runtime with a larger maxBytes`);
  }

  // ---------------------------------------------------------------- endpoints

  /**
   * Create an endpoint and match it with its peers (lock held).
   * @param {object} spec
   * @param {number} spec.kind KIND_*
   * @param {number} spec.pid
   * @param {number} spec.node node index
   * @param {string} spec.name topic or service name
   * @param {string} spec.type type name
   * @param {Int32Array|number[]} spec.qos resolved wire QoS
   * @param {number} spec.flags EP_FLAG_*
   * @param {number} spec.ringSlots ring size for writers (power of two), 0 for plain readers
   * @returns {{index: number, serial: number, touched: Set<number>}} touched: pids to ring
   */
  createEndpoint(spec) {
    const i32 = this.i32;
    const nb = this.node(spec.node);
    if (Atomics.load(i32, nb + NODE.STATE) !== REC_ALIVE || i32[nb + NODE.PID] !== spec.pid) {
      throw new BusError(Code.INVALID_ARGUMENT, `cannot create endpoint '${spec.name}': its node (index ${spec.node}) does not exist on the bus`);
    }
    const idx = this._findFree(HEADER.EP_HINT, HEADER.EP_HWM, this.epCap, (i) => this.ep(i) + ENDPOINT.STATE);
    if (idx < 0) {
      throw new BusError(Code.BAD_ALLOC, `cannot create endpoint '${spec.name}': the bus endpoint table is full (${this.epCap} endpoints); start the Runtime with a larger maxEndpoints`);
    }
    const strs = this.allocStrings([spec.name, spec.type], spec.pid);
    if (!strs) throw this._fullError(`endpoint '${spec.name}'`);
    let ring = 0;
    if (spec.ringSlots) {
      ring = this.alloc(spec.ringSlots * SLOT.WORDS * 4, spec.pid);
      if (!ring) {
        this.free(strs.off);
        throw this._fullError(`endpoint '${spec.name}' (ring of ${spec.ringSlots} slots)`);
      }
      this.i32.fill(0, ring >> 2, (ring >> 2) + spec.ringSlots * SLOT.WORDS);
    }
    const r32 = this.i32;
    const f64 = this.f64;
    const b = this.ep(idx);
    r32.fill(0, b + 1, b + ENDPOINT.WORDS);
    const serial = Atomics.add(r32, HEADER.SERIAL, 1) + 1;
    const t = now();
    r32[b + ENDPOINT.KIND] = spec.kind;
    r32[b + ENDPOINT.PID] = spec.pid;
    r32[b + ENDPOINT.NODE] = spec.node;
    r32[b + ENDPOINT.DOMAIN] = r32[nb + NODE.DOMAIN];
    r32[b + ENDPOINT.CONTEXT] = r32[nb + NODE.CONTEXT];
    r32[b + ENDPOINT.SERIAL] = serial;
    r32[b + ENDPOINT.FLAGS] = spec.flags | 0;
    r32[b + ENDPOINT.STR_OFF] = strs.off;
    r32[b + ENDPOINT.NAME_LEN] = strs.lens[0];
    r32[b + ENDPOINT.TYPE_LEN] = strs.lens[1];
    r32[b + ENDPOINT.NAME_HASH] = fnv1a(encoder.encode(spec.name));
    for (let q = 0; q < QOS.WORDS; q++) r32[b + ENDPOINT.QOS + q] = spec.qos[q];
    const qw = (k) => r32[b + ENDPOINT.QOS + k];
    f64[(b + ENDPOINT.DEADLINE_MS_F64) >> 1] = durationMs(qw(QOS.DEADLINE_LO), qw(QOS.DEADLINE_HI));
    f64[(b + ENDPOINT.LIFESPAN_MS_F64) >> 1] = durationMs(qw(QOS.LIFESPAN_LO), qw(QOS.LIFESPAN_HI));
    f64[(b + ENDPOINT.LEASE_MS_F64) >> 1] = durationMs(qw(QOS.LEASE_LO), qw(QOS.LEASE_HI));
    r32[b + ENDPOINT.RING_OFF] = ring;
    r32[b + ENDPOINT.RING_SLOTS] = spec.ringSlots | 0;
    f64[(b + ENDPOINT.LAST_PUB_F64) >> 1] = t;
    f64[(b + ENDPOINT.LAST_ASSERT_F64) >> 1] = t;
    f64[(b + ENDPOINT.CREATED_F64) >> 1] = t;
    f64[(b + ENDPOINT.DEADLINE_ACCT_BASE_F64) >> 1] = t;
    f64[(b + ENDPOINT.LIVE_LOST_BASE_F64) >> 1] = t;
    const touched = new Set([spec.pid]);
    Atomics.store(r32, b + ENDPOINT.STATE, REC_ALIVE);
    try {
      this._match(idx, touched);
    } catch (e) {
      this.removeEndpoint(idx);
      throw e;
    }
    return { index: idx, serial, touched };
  }

  /** True when endpoint `a` and `b` use the same name (byte compare). */
  _sameName(a, b) {
    const i32 = this.i32;
    const ab = this.ep(a);
    const bb = this.ep(b);
    if (i32[ab + ENDPOINT.NAME_HASH] !== i32[bb + ENDPOINT.NAME_HASH] || i32[ab + ENDPOINT.NAME_LEN] !== i32[bb + ENDPOINT.NAME_LEN]) return false;
    const ao = i32[ab + ENDPOINT.STR_OFF];
    const bo = i32[bb + ENDPOINT.STR_OFF];
    const u8 = this.u8;
    for (let i = 0, n = i32[ab + ENDPOINT.NAME_LEN]; i < n; i++) if (u8[ao + i] !== u8[bo + i]) return false;
    return true;
  }

  _sameType(a, b) {
    const i32 = this.i32;
    const ab = this.ep(a);
    const bb = this.ep(b);
    const n = i32[ab + ENDPOINT.TYPE_LEN];
    if (n !== i32[bb + ENDPOINT.TYPE_LEN]) return false;
    const ao = i32[ab + ENDPOINT.STR_OFF] + i32[ab + ENDPOINT.NAME_LEN];
    const bo = i32[bb + ENDPOINT.STR_OFF] + i32[bb + ENDPOINT.NAME_LEN];
    const u8 = this.u8;
    for (let i = 0; i < n; i++) if (u8[ao + i] !== u8[bo + i]) return false;
    return true;
  }

  _qos(idx) {
    const b = this.ep(idx) + ENDPOINT.QOS;
    return this.i32.subarray(b, b + QOS.WORDS);
  }

  _match(idx, touched) {
    const i32 = this.i32;
    const b = this.ep(idx);
    const kind = i32[b + ENDPOINT.KIND];
    const domain = i32[b + ENDPOINT.DOMAIN];
    const hwm = i32[HEADER.EP_HWM];
    for (let o = 0; o < hwm; o++) {
      if (o === idx) continue;
      const ob = this.ep(o);
      if (Atomics.load(i32, ob + ENDPOINT.STATE) !== REC_ALIVE || i32[ob + ENDPOINT.DOMAIN] !== domain) continue;
      const okind = i32[ob + ENDPOINT.KIND];
      let writer;
      let reader;
      if (kind === KIND_PUBLISHER && okind === KIND_SUBSCRIPTION) [writer, reader] = [idx, o];
      else if (kind === KIND_SUBSCRIPTION && okind === KIND_PUBLISHER) [writer, reader] = [o, idx];
      else if ((kind === KIND_CLIENT && okind === KIND_SERVICE) ||
               (kind === KIND_SERVICE && okind === KIND_CLIENT)) {
        if (!this._sameName(idx, o) || !this._sameType(idx, o)) continue;
        const client = kind === KIND_CLIENT ? idx : o;
        const service = kind === KIND_CLIENT ? o : idx;
        if (!checkCompatible(this._qos(client), this._qos(service)).ok ||
            !checkCompatible(this._qos(service), this._qos(client)).ok) continue;
        this._addLink(client, service, LINK_BLOCKING);
        this._addLink(service, client, LINK_BLOCKING | LINK_TARGETED);
        touched.add(i32[ob + ENDPOINT.PID]);
        continue;
      } else continue;
      if (!this._sameName(idx, o) || !this._sameType(idx, o)) continue;
      const wb = this.ep(writer);
      const rb = this.ep(reader);
      if ((i32[rb + ENDPOINT.FLAGS] & EP_FLAG_IGNORE_LOCAL) && i32[rb + ENDPOINT.CONTEXT] === i32[wb + ENDPOINT.CONTEXT]) continue;
      const c = checkCompatible(this._qos(writer), this._qos(reader));
      touched.add(i32[ob + ENDPOINT.PID]);
      if (!c.ok) {
        for (const e of [wb, rb]) {
          Atomics.add(i32, e + ENDPOINT.INCOMPAT_TOTAL, 1);
          Atomics.store(i32, e + ENDPOINT.INCOMPAT_POLICY, c.policy);
        }
        continue;
      }
      const rq = this._qos(reader);
      let flags = 0;
      if (rq[QOS.RELIABILITY] === Reliability.RELIABLE && rq[QOS.HISTORY] === History.KEEP_ALL) flags |= LINK_BLOCKING;
      if (rq[QOS.RELIABILITY] === Reliability.BEST_EFFORT) flags |= LINK_BEST_EFFORT;
      this._addLink(writer, reader, flags);
    }
  }

  _addLink(writer, reader, flags) {
    const i32 = this.i32;
    const idx = this._findFree(HEADER.LINK_HINT, HEADER.LINK_HWM, this.linkCap, (i) => this.link(i) + LINK.STATE);
    if (idx < 0) {
      throw new BusError(Code.BAD_ALLOC, `cannot match endpoints: the bus link table is full (${this.linkCap} matched pairs); start the Runtime with a larger maxLinks`);
    }
    const wb = this.ep(writer);
    const rb = this.ep(reader);
    const wq = this._qos(writer);
    const rq = this._qos(reader);
    const readerDepth = rq[QOS.HISTORY] === History.KEEP_LAST ? rq[QOS.DEPTH] : 0;
    const head = Atomics.load(i32, wb + ENDPOINT.HEAD);
    let cursor = head;
    if (wq[QOS.DURABILITY] === Durability.TRANSIENT_LOCAL && rq[QOS.DURABILITY] === Durability.TRANSIENT_LOCAL) {
      // A late joiner gets the writer's retained history, as much as its own depth holds.
      const published = i32[wb + ENDPOINT.HEAD_HI] > 0 ? 0x7fffffff : (head >>> 0);
      let retained = wq[QOS.HISTORY] === History.KEEP_LAST ? wq[QOS.DEPTH] : i32[wb + ENDPOINT.RING_SLOTS];
      retained = Math.min(retained, i32[wb + ENDPOINT.RING_SLOTS], published);
      if (readerDepth) retained = Math.min(retained, readerDepth);
      cursor = (head - retained) | 0;
    }
    const lb = this.link(idx);
    i32[lb + LINK.WRITER] = writer;
    i32[lb + LINK.READER] = reader;
    i32[lb + LINK.CURSOR] = cursor;
    i32[lb + LINK.FLAGS] = flags;
    i32[lb + LINK.DEPTH] = (flags & LINK_TARGETED) ? 0 : readerDepth;
    i32[lb + LINK.WRITER_SERIAL] = i32[wb + ENDPOINT.SERIAL];
    i32[lb + LINK.READER_SERIAL] = i32[rb + ENDPOINT.SERIAL];
    Atomics.store(i32, lb + LINK.STATE, REC_ALIVE);
  }

  /**
   * Remove an endpoint from the graph (lock held). Idempotent.
   *
   * A writer whose ring still holds messages some live reader has not taken
   * becomes a ZOMBIE: gone from the graph and from matching, but its ring
   * stays readable through the remaining links until they are drained (a
   * message published before the writer went away is delivered, as with
   * DDS reader caches). Otherwise the ring and its blocks are freed.
   * @param {number} index
   * @returns {Set<number>} pids of the peers that lost a match (to ring)
   */
  removeEndpoint(index) {
    const i32 = this.i32;
    const b = this.ep(index);
    const peers = new Set();
    const st = Atomics.load(i32, b + ENDPOINT.STATE);
    if (st === REC_FREE || st === REC_ZOMBIE) return peers;
    Atomics.store(i32, b + ENDPOINT.STATE, REC_DYING);
    const head = Atomics.load(i32, b + ENDPOINT.HEAD);
    const zombies = new Set();
    let kept = 0;
    const hwm = i32[HEADER.LINK_HWM];
    for (let l = 0; l < hwm; l++) {
      const lb = this.link(l);
      if (Atomics.load(i32, lb + LINK.STATE) !== REC_ALIVE) continue;
      const w = i32[lb + LINK.WRITER];
      const r = i32[lb + LINK.READER];
      if (w !== index && r !== index) continue;
      const other = w === index ? r : w;
      const ob = this.ep(other);
      peers.add(i32[ob + ENDPOINT.PID]);
      if (w === index && Atomics.load(i32, ob + ENDPOINT.STATE) === REC_ALIVE &&
          ((head - Atomics.load(i32, lb + LINK.CURSOR)) | 0) > 0) {
        kept++;
        continue;
      }
      Atomics.store(i32, lb + LINK.STATE, REC_FREE);
      if (Atomics.load(i32, ob + ENDPOINT.STATE) === REC_ZOMBIE) zombies.add(other);
    }
    for (const z of zombies) this._freeZombieIfDrained(z);
    if (kept) {
      Atomics.store(i32, b + ENDPOINT.STATE, REC_ZOMBIE);
      return peers;
    }
    this._freeEndpoint(index);
    return peers;
  }

  _freeEndpoint(index) {
    const i32 = this.i32;
    const b = this.ep(index);
    const ring = i32[b + ENDPOINT.RING_OFF];
    if (ring) {
      const slots = i32[b + ENDPOINT.RING_SLOTS];
      for (let s = 0; s < slots; s++) {
        const sw = (ring >> 2) + s * SLOT.WORDS;
        Atomics.store(i32, sw + SLOT.COMMIT, 0);
        this.free(i32[sw + SLOT.BLOCK]);
      }
      this.free(ring);
    }
    this.free(i32[b + ENDPOINT.STR_OFF]);
    Atomics.store(i32, b + ENDPOINT.STATE, REC_FREE);
  }

  /** Free a zombie writer once no link reads from it (lock held). */
  _freeZombieIfDrained(index) {
    const i32 = this.i32;
    if (Atomics.load(i32, this.ep(index) + ENDPOINT.STATE) !== REC_ZOMBIE) return;
    const hwm = i32[HEADER.LINK_HWM];
    for (let l = 0; l < hwm; l++) {
      const lb = this.link(l);
      if (Atomics.load(i32, lb + LINK.STATE) === REC_ALIVE && i32[lb + LINK.WRITER] === index) return;
    }
    this._freeEndpoint(index);
  }

  /**
   * Drop links from zombie writers that their readers have drained (lock held).
   * @param {number[]} links
   */
  reapDrainedLinks(links) {
    const i32 = this.i32;
    const writers = new Set();
    for (const l of links) {
      const lb = this.link(l);
      if (Atomics.load(i32, lb + LINK.STATE) !== REC_ALIVE) continue;
      const w = i32[lb + LINK.WRITER];
      const wb = this.ep(w);
      if (Atomics.load(i32, wb + ENDPOINT.STATE) !== REC_ZOMBIE) continue;
      if (((Atomics.load(i32, wb + ENDPOINT.HEAD) - Atomics.load(i32, lb + LINK.CURSOR)) | 0) > 0) continue;
      Atomics.store(i32, lb + LINK.STATE, REC_FREE);
      writers.add(w);
    }
    for (const w of writers) this._freeZombieIfDrained(w);
  }

  /**
   * Remove everything a dead process owned (lock held). Idempotent.
   * @param {number} pid
   */
  cleanupProcess(pid) {
    const i32 = this.i32;
    const pb = this.proc(pid);
    Atomics.store(i32, pb + PROCESS.STATE, PROC_DEAD);
    const hwm = i32[HEADER.EP_HWM];
    for (let e = 0; e < hwm; e++) {
      const eb = this.ep(e);
      if (Atomics.load(i32, eb + ENDPOINT.STATE) !== REC_FREE && i32[eb + ENDPOINT.PID] === pid) this.removeEndpoint(e);
    }
    const nhwm = i32[HEADER.NODE_HWM];
    for (let n = 0; n < nhwm; n++) {
      const nb = this.node(n);
      if (Atomics.load(i32, nb + NODE.STATE) !== REC_FREE && i32[nb + NODE.PID] === pid) this.removeNode(n);
    }
    // The record stays DEAD until nobody can be sleeping on its doorbell.
    Atomics.add(i32, pb + PROCESS.BELL, 1);
    Atomics.notify(i32, pb + PROCESS.BELL);
  }

  /**
   * Return a dead process' record to the free pool (lock held).
   * @param {number} pid
   */
  releaseProcess(pid) {
    const pb = this.proc(pid);
    if (Atomics.load(this.i32, pb + PROCESS.STATE) === PROC_DEAD) Atomics.store(this.i32, pb + PROCESS.STATE, PROC_FREE);
  }

  // ---------------------------------------------------------------- gids

  /**
   * The 16-byte gid of an entity: bus id, pid, (kind << 24 | index), serial.
   * @returns {Int32Array}
   */
  gidWords(kind, index) {
    const i32 = this.i32;
    const b = kind === KIND_NODE ? this.node(index) : this.ep(index);
    const serial = kind === KIND_NODE ? i32[b + NODE.SERIAL] : i32[b + ENDPOINT.SERIAL];
    const pid = kind === KIND_NODE ? i32[b + NODE.PID] : i32[b + ENDPOINT.PID];
    return Int32Array.of(this.id, pid, (kind << 24) | index, serial);
  }

  /**
   * Find the endpoint a gid names, or -1 if it is gone.
   * @param {ArrayLike<number>} w four gid words
   */
  endpointOfGid(w) {
    if (w[0] !== this.id) return -1;
    const index = w[2] & 0xffffff;
    const kind = w[2] >>> 24;
    if (kind === KIND_NODE || index >= this.epCap) return -1;
    const b = this.ep(index);
    if (Atomics.load(this.i32, b + ENDPOINT.STATE) !== REC_ALIVE || this.i32[b + ENDPOINT.SERIAL] !== w[3]) return -1;
    return index;
  }

  // ---------------------------------------------------------------- graph

  /**
   * A consistent snapshot of the graph.
   * @param {object} [filter]
   * @param {number} [filter.domain] only this domain
   * @returns {{version: number, nodes: object[], endpoints: object[]}}
   */
  snapshot(filter = {}) {
    for (let attempt = 0; ; attempt++) {
      const v1 = this.graphVersion();
      const snap = this._readGraph(filter);
      const v2 = this.graphVersion();
      if (v1 === v2 || attempt > 100) {
        snap.version = v2;
        return snap;
      }
    }
  }

  _readGraph(filter) {
    this.refreshViews();
    const i32 = this.i32;
    const nodes = [];
    const byIndex = new Map();
    const nhwm = Atomics.load(i32, HEADER.NODE_HWM);
    for (let n = 0; n < nhwm; n++) {
      const b = this.node(n);
      if (Atomics.load(i32, b + NODE.STATE) !== REC_ALIVE) continue;
      const domain = i32[b + NODE.DOMAIN];
      if (filter.domain !== undefined && domain !== filter.domain) continue;
      const off = i32[b + NODE.STR_OFF];
      const nl = i32[b + NODE.NAME_LEN];
      const sl = i32[b + NODE.NS_LEN];
      const node = {
        index: n,
        name: this.readString(off, nl),
        namespace: this.readString(off + nl, sl),
        enclave: this.readString(off + nl + sl, i32[b + NODE.ENCLAVE_LEN]),
        domain,
        pid: i32[b + NODE.PID],
        gid: this.gidWords(KIND_NODE, n),
      };
      nodes.push(node);
      byIndex.set(n, node);
    }
    const endpoints = [];
    const ehwm = Atomics.load(i32, HEADER.EP_HWM);
    const kinds = { 1: 'publisher', 2: 'subscription', 3: 'service', 4: 'client' };
    for (let e = 0; e < ehwm; e++) {
      const b = this.ep(e);
      if (Atomics.load(i32, b + ENDPOINT.STATE) !== REC_ALIVE) continue;
      const domain = i32[b + ENDPOINT.DOMAIN];
      if (filter.domain !== undefined && domain !== filter.domain) continue;
      const node = byIndex.get(i32[b + ENDPOINT.NODE]);
      if (!node) continue;
      const off = i32[b + ENDPOINT.STR_OFF];
      const nl = i32[b + ENDPOINT.NAME_LEN];
      const qos = Int32Array.from(this._qos(e));
      endpoints.push({
        index: e,
        kind: i32[b + ENDPOINT.KIND],
        kindName: kinds[i32[b + ENDPOINT.KIND]],
        name: this.readString(off, nl),
        type: this.readString(off + nl, i32[b + ENDPOINT.TYPE_LEN]),
        node: node.name,
        namespace: node.namespace,
        domain,
        pid: i32[b + ENDPOINT.PID],
        gid: this.gidWords(i32[b + ENDPOINT.KIND], e),
        qosWords: qos,
        qos: decodeQos(qos),
      });
    }
    return { nodes, endpoints };
  }
}

export {
  KIND_CLIENT, KIND_NODE, KIND_PUBLISHER, KIND_SERVICE, KIND_SUBSCRIPTION, PROC_ALIVE, PROC_DEAD,
  PROC_FREE, nextPow2,
};
