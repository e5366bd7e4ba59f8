// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * BusClient: the operations of one bus process, used by one thread.
 *
 * Every thread of a bus process (the node's worker, each of its pthreads,
 * the tools worker) has its own BusClient over the same Bus and process id.
 * Everything shared lives in the bus; a BusClient only caches, per graph
 * version, which links its endpoints have.
 *
 * Data path: a writer commits a message into a slot of its ring (seqlock:
 * COMMIT = ~(n+1) while writing, n+1 when done), advances HEAD, then rings
 * the doorbell of each matched reader process (Atomics.notify only when that
 * process has sleepers). A reader copies the bytes straight to their
 * destination, re-validates COMMIT, and advances its cursor with a CAS, so
 * several threads can take from one reader and the writer never waits for
 * KEEP_LAST readers.
 *
 * No lost wake-ups: a waiter counts itself as a sleeper, reads its doorbell,
 * checks its entities and sleeps only while the doorbell still holds the
 * value it read; a writer commits, then reads the sleeper count and, if
 * there is one, increments the doorbell and notifies (all seq-cst). Either
 * the writer sees the sleeper (then the increment precedes the waiter's
 * Atomics.wait, which returns at once, or follows it and wakes it), or the
 * registration follows the writer's load, hence its commit, and the waiter's
 * check sees the message. Writers pay one load per reader process when
 * nobody sleeps.
 *
 * @module bus_client
 */

import { Bus, BusError, Code, KIND_CLIENT, KIND_NODE, KIND_PUBLISHER, KIND_SERVICE, KIND_SUBSCRIPTION, MAX_RING_SLOTS, nextPow2, now, REC_DYING, REC_ZOMBIE,
} from './bus.mjs';
import { ENDPOINT, EP_FLAG_IGNORE_LOCAL, HEADER, LINK, LINK_BEST_EFFORT, LINK_BLOCKING, LINK_TARGETED, NODE, PROC_KIND_NODE, PROCESS, QOS, REC_ALIVE, SLOT,
} from './layout.mjs';
import { EventType, TakeMode, WAIT_ITEM_WORDS, WaitKind } from './abi/bus_abi.mjs';
import { heapCopier } from './copier.mjs';
import { encodeQos, History, Liveliness, resolveQos, validateQos } from './qos.mjs';

/** Event kinds, wait item kinds, take modes: abi/bus_abi.mjs (shared with wasm_cpp). */
export { EventType, TakeMode, WAIT_ITEM_WORDS, WaitKind };

// A ROS name ('/chatter', '/ns/topic'), or a native one without the leading
// slash ('chatter'): rmw_wasm_cpp passes those for avoid_ros_namespace_conventions,
// as DDS middlewares use the name as given; the two never match each other.
const NAME_RE = /^\/?[A-Za-z_~{}][A-Za-z0-9_~{}]*(?:\/[A-Za-z_~{}][A-Za-z0-9_~{}]*)*$/;
const NODE_NAME_RE = /^[A-Za-z_][A-Za-z0-9_]*$/;
const NAMESPACE_RE = /^\/(?:[A-Za-z_][A-Za-z0-9_]*(?:\/[A-Za-z_][A-Za-z0-9_]*)*)?$/;
const TYPE_RE = /^[A-Za-z_][A-Za-z0-9_]*(?:\/[A-Za-z_][A-Za-z0-9_]*)*$/;

/** A writer blocked on a full ring looks again at least this often (ms). */
const ACK_RECHECK_MS = 1;

const KIND_NAMES = { 1: 'publisher', 2: 'subscription', 3: 'service', 4: 'client' };
const EMPTY = new Int32Array(0);
const LISTEN_KEY = 0x100000;

/**
 * Messages up to this size are copied with a loop: no view object, no
 * garbage. Word by word, a loop beats TypedArray.set() (which needs a
 * subarray) up to ~512 bytes; byte by byte it is 4-10x slower.
 */
const SMALL_COPY = 512;

// Int32Array views of the last two byte arrays copied (the bus and the wasm
// heap), for word copies without a new view per message.
let wordsOf1 = null;
let words1 = null;
let wordsOf2 = null;
let words2 = null;

/** An Int32Array over the same bytes as `u8`, or null when it is not word-aligned. */
function wordsOf(u8) {
  if (u8 === wordsOf1) return words1;
  if (u8 === wordsOf2) return words2;
  const w = (u8.byteOffset & 3) === 0 ? new Int32Array(u8.buffer, u8.byteOffset, u8.length >> 2) : null;
  wordsOf2 = wordsOf1;
  words2 = words1;
  wordsOf1 = u8;
  words1 = w;
  return w;
}

/** Copy len bytes; small copies allocate nothing (views would feed the GC per message). */
function copyBytes(dst, dstOff, src, srcOff, len) {
  if (len > SMALL_COPY) {
    dst.set(srcOff === 0 && len === src.length ? src : src.subarray(srcOff, srcOff + len), dstOff);
    return;
  }
  let i = 0;
  if (((dstOff | srcOff) & 3) === 0 && len >= 16) {
    const d = wordsOf(dst);
    const s = wordsOf(src);
    if (d !== null && s !== null) {
      const n = len >> 2;
      const db = dstOff >> 2;
      const sb = srcOff >> 2;
      for (let k = 0; k < n; k++) d[db + k] = s[sb + k];
      i = n << 2;
    }
  }
  for (; i < len; i++) dst[dstOff + i] = src[srcOff + i];
}

function describeValue(v) {
  if (v === null) return 'null';
  if (ArrayBuffer.isView(v)) return v.constructor.name;
  return typeof v === 'object' ? Object.prototype.toString.call(v) : typeof v;
}

/**
 * The bus operations of one thread of one bus process.
 */
export class BusClient {
  /**
   * Create a bus and a client of a new process on it (standalone executables, tests).
   * @param {object} [options] Bus.create() options
   * @returns {BusClient}
   */
  static createPrivate(options = {}) {
    const bus = Bus.create(options);
    // A new bus: nobody else can hold the lock (pid 1 becomes the runtime's).
    if (!bus.tryLock(1)) throw new BusError(Code.ERROR, 'a new bus is already locked');
    const runtimePid = bus.allocProcess(1);
    const pid = bus.allocProcess(PROC_KIND_NODE);
    bus.unlock(runtimePid);
    return new BusClient(bus, pid);
  }

  /**
   * Attach a client to an existing bus.
   * @param {SharedArrayBuffer|WebAssembly.Memory} handle the bus' `handle`
   * @param {number} pid the process id the runtime assigned
   * @returns {BusClient}
   */
  static attach(handle, pid) {
    return new BusClient(Bus.attach(handle), pid);
  }

  /**
   * @param {Bus} bus
   * @param {number} pid
   */
  constructor(bus, pid) {
    if (!Number.isInteger(pid) || pid <= 0 || pid >= bus.procCap) {
      throw new BusError(Code.INVALID_ARGUMENT, `invalid bus process id ${pid}`);
    }
    this.bus = bus;
    this.pid = pid;
    this.bellIndex = bus.proc(pid) + PROCESS.BELL;
    this.sleepersIndex = bus.proc(pid) + PROCESS.SLEEPERS;
    this._cacheVersion = -1;
    /** @type {Map<number, {links: Int32Array, blocking: Int32Array, pids: Int32Array}>} */
    this._writers = new Map();
    /** @type {Map<number, Int32Array>} */
    this._readers = new Map();
    /** State of the take in progress (begin/copy). */
    this._t = {
      link: 0, cursor: 0, slot: 0, commit: 0, block: 0, len: 0, writer: 0, reader: 0, mode: 0,
    };
    /** Info of the last message taken. */
    this.info = {
      sourceTime: 0, receivedTime: 0, pubSeqLo: 0, pubSeqHi: 0, recvSeqLo: 0, recvSeqHi: 0,
      gid: new Int32Array(4), reqLo: 0, reqHi: 0, sameProcess: false, len: 0,
    };
    /** Per-reader "arrivals seen" marks of the listener (link index -> head). */
    this._listenMarks = new Map();
    this._nextExpiry = Infinity;
    /**
     * Called after reading the doorbell and before checking, in every wait of
     * this thread. The main thread of a pthread program sets it to run the
     * calls other threads proxied to it (their printf, ...): those threads
     * ring the doorbell when they queue a call, so running the queue there
     * keeps the no-lost-wake-up argument intact.
     * @type {?function(): void}
     */
    this.service = null;
    /** Called once, before this thread first sleeps on the bus (see beforeFirstSleep). */
    this._beforeSleep = null;
    /**
     * memory.copy between this thread's wasm heap and the bus (useHeapMemory),
     * or null: publishFrom(ep, null, ...) and takeCopy(null, ...) need it.
     * @type {?{toBus: function(number, number, number): void, fromBus: function(number, number, number): void}}
     */
    this.heapCopier = null;
  }

  /**
   * Copy to and from `heap` (this thread's wasm memory) with memory.copy
   * where the engine and the bus allow it (see copier.mjs).
   * @param {WebAssembly.Memory} heap
   * @returns {boolean} true when publishFrom(ep, null, ...) and takeCopy(null, ...) may be used
   */
  useHeapMemory(heap) {
    this.heapCopier = this.bus.memory === null ? null : heapCopier(heap, this.bus.memory);
    return this.heapCopier !== null;
  }

  /** The bus' largest message in bytes. */
  get maxMessageBytes() { return this.bus.maxMessage; }

  // ------------------------------------------------------------ graph cache

  _refresh() {
    // A plain read: a stale version only delays the cache refresh.
    const v = this.bus.i32[HEADER.GRAPH_VERSION];
    if (v !== this._cacheVersion) {
      this._cacheVersion = v;
      this._writers.clear();
      this._readers.clear();
      // New endpoints (rings) may lie beyond this thread's views.
      this.bus.refreshViews();
    }
  }

  _writerInfo(ep) {
    let w = this._writers.get(ep);
    if (w) return w;
    const bus = this.bus;
    const i32 = bus.i32;
    const links = [];
    const blocking = [];
    const pids = new Set();
    const hwm = Atomics.load(i32, HEADER.LINK_HWM);
    for (let l = 0; l < hwm; l++) {
      const lb = bus.link(l);
      if (Atomics.load(i32, lb + LINK.STATE) !== REC_ALIVE || i32[lb + LINK.WRITER] !== ep) continue;
      links.push(l);
      if (i32[lb + LINK.FLAGS] & LINK_BLOCKING) blocking.push(l);
      pids.add(i32[bus.ep(i32[lb + LINK.READER]) + ENDPOINT.PID]);
    }
    w = { links: Int32Array.from(links), blocking: Int32Array.from(blocking), pids: Int32Array.from(pids), floor: 0, floorValid: false };
    this._writers.set(ep, w);
    return w;
  }

  _readerLinks(ep) {
    let r = this._readers.get(ep);
    if (r) return r;
    const bus = this.bus;
    const i32 = bus.i32;
    const links = [];
    const hwm = Atomics.load(i32, HEADER.LINK_HWM);
    for (let l = 0; l < hwm; l++) {
      const lb = bus.link(l);
      if (Atomics.load(i32, lb + LINK.STATE) === REC_ALIVE && i32[lb + LINK.READER] === ep) links.push(l);
    }
    r = links.length ? Int32Array.from(links) : EMPTY;
    this._readers.set(ep, r);
    return r;
  }

  // ------------------------------------------------------------ registry

  _mutate(fn) {
    const bus = this.bus;
    bus.lock(this.pid);
    let result;
    try {
      result = fn();
    } finally {
      bus.bumpGraph();
      bus.unlock(this.pid);
    }
    bus.ringAll();
    return result;
  }

  /** A bus-wide unique context id. */
  createContext() {
    return Atomics.add(this.bus.i32, HEADER.SERIAL, 1) + 1;
  }

  /**
   * Create a node.
   * @returns {{index: number, gid: Int32Array, nameTaken: boolean}}
   */
  createNode({ domain = 0, context = 0, name, namespace = '/', enclave = '/' }) {
    if (typeof name !== 'string' || !NODE_NAME_RE.test(name) || name.length > 255) {
      throw new BusError(Code.INVALID_ARGUMENT,
        `invalid node name ${JSON.stringify(name)}: must start with a letter or '_' and contain only letters, digits and '_'`);
    }
    if (typeof namespace !== 'string' || !NAMESPACE_RE.test(namespace) || namespace.length > 255) {
      throw new BusError(Code.INVALID_ARGUMENT,
        `invalid namespace ${JSON.stringify(namespace)} for node '${name}': must be '/' or absolute like '/robot1', with tokens of letters, digits and '_'`);
    }
    if (!Number.isInteger(domain) || domain < 0 || domain > 0x7fffffff) {
      throw new BusError(Code.INVALID_ARGUMENT, `invalid domain id ${domain} for node '${name}'`);
    }
    const r = this._mutate(() => this.bus.createNode({
      pid: this.pid, domain, context, name, namespace, enclave: enclave || '/',
    }));
    return { index: r.index, gid: this.bus.gidWords(KIND_NODE, r.index), nameTaken: r.nameTaken };
  }

  /** Remove a node (and its endpoints). */
  destroyNode(index) {
    this._checkNode(index);
    this._mutate(() => this.bus.removeNode(index));
  }

  _checkNode(index) {
    const b = this.bus.node(index);
    if (!Number.isInteger(index) || index < 0 || index >= this.bus.nodeCap ||
        Atomics.load(this.bus.i32, b + NODE.STATE) !== REC_ALIVE || this.bus.i32[b + NODE.PID] !== this.pid) {
      throw new BusError(Code.INVALID_ARGUMENT, `node handle ${index} does not name a live node of this process`);
    }
  }

  /**
   * Create a publisher, subscription, service or client.
   * @param {object} spec
   * @param {number} spec.kind KIND_PUBLISHER / KIND_SUBSCRIPTION / KIND_SERVICE / KIND_CLIENT
   * @param {number} spec.node node index
   * @param {string} spec.name fully qualified topic or service name
   * @param {string} spec.type type name, e.g. 'std_msgs/msg/String'
   * @param {Int32Array|object} [spec.qos] wire QoS words or a QosProfile object
   * @param {boolean} [spec.ignoreLocal] subscriptions: skip publishers of the same context
   * @param {number} [spec.keepAllDepth=1000] ring size of KEEP_ALL writers
   * @returns {{index: number, gid: Int32Array, qos: Int32Array}}
   */
  createEndpoint(spec) {
    const kind = spec.kind;
    const what = KIND_NAMES[kind];
    if (!what) throw new BusError(Code.INVALID_ARGUMENT, `invalid endpoint kind ${kind}`);
    const name = spec.name;
    if (typeof name !== 'string' || name.length > 1024 || !NAME_RE.test(name) || name === '/') {
      const noun = kind === KIND_SERVICE || kind === KIND_CLIENT ? 'service' : 'topic';
      throw new BusError(Code.INVALID_ARGUMENT,
        `cannot create ${what}: invalid ${noun} name ${JSON.stringify(name)} (must be like '/chatter', or 'chatter' for a native name: tokens of letters, digits and '_' not starting with a digit)`);
    }
    if (typeof spec.type !== 'string' || !TYPE_RE.test(spec.type) || spec.type.length > 1024) {
      throw new BusError(Code.INVALID_ARGUMENT,
        `cannot create ${what} on '${name}': invalid type name ${JSON.stringify(spec.type)} (expected e.g. 'std_msgs/msg/String')`);
    }
    this._checkNode(spec.node);
    const qos = spec.qos instanceof Int32Array ? Int32Array.from(spec.qos) : encodeQos(spec.qos || {});
    const bad = validateQos(qos);
    if (bad) throw new BusError(Code.INVALID_ARGUMENT, `cannot create ${what} on '${name}': ${bad}`);
    resolveQos(qos);
    let ringSlots = 0;
    if (kind !== KIND_SUBSCRIPTION) {
      const keepAll = spec.keepAllDepth === undefined ? 1000 : spec.keepAllDepth;
      const depth = qos[QOS.HISTORY] === History.KEEP_ALL ? keepAll : qos[QOS.DEPTH];
      if (!(depth >= 1) || depth > MAX_RING_SLOTS) {
        throw new BusError(Code.INVALID_ARGUMENT,
          `cannot create ${what} on '${name}': history depth ${depth} is out of range 1..${MAX_RING_SLOTS}`);
      }
      ringSlots = nextPow2(depth);
    }
    const flags = spec.ignoreLocal ? EP_FLAG_IGNORE_LOCAL : 0;
    const r = this._mutate(() => this.bus.createEndpoint({
      kind, pid: this.pid, node: spec.node, name, type: spec.type, qos, flags, ringSlots,
    }));
    return { index: r.index, gid: this.bus.gidWords(kind, r.index), qos };
  }

  /** Remove an endpoint. */
  destroyEndpoint(index) {
    this._checkEndpoint(index, 0, 'destroy');
    this._mutate(() => this.bus.removeEndpoint(index));
  }

  _checkEndpoint(index, kind, op) {
    const bus = this.bus;
    if (!Number.isInteger(index) || index < 0 || index >= bus.epCap) {
      throw new BusError(Code.INVALID_ARGUMENT, `${op}: invalid endpoint handle ${index}`);
    }
    const b = bus.ep(index);
    const i32 = bus.i32;
    if (i32[b + ENDPOINT.STATE] !== REC_ALIVE || i32[b + ENDPOINT.PID] !== this.pid || (kind && i32[b + ENDPOINT.KIND] !== kind)) {
      throw new BusError(Code.INVALID_ARGUMENT,
        `${op}: endpoint handle ${index} does not name a live ${kind ? KIND_NAMES[kind] : 'endpoint'} of this process`);
    }
    return b;
  }

  /** The topic/service name of an endpoint (for messages). */
  endpointName(index) {
    const bus = this.bus;
    const b = bus.ep(index);
    return bus.readString(bus.i32[b + ENDPOINT.STR_OFF], bus.i32[b + ENDPOINT.NAME_LEN]);
  }

  // ------------------------------------------------------------ writer

  _wlock(b) {
    const i32 = this.bus.i32;
    const w = b + ENDPOINT.WLOCK;
    if (Atomics.compareExchange(i32, w, 0, 1) === 0) return;
    for (;;) {
      if (Atomics.exchange(i32, w, 2) === 0) return;
      Atomics.wait(i32, w, 2);
    }
  }

  _wunlock(b) {
    const i32 = this.bus.i32;
    if (Atomics.exchange(i32, b + ENDPOINT.WLOCK, 0) === 2) Atomics.notify(i32, b + ENDPOINT.WLOCK, 1);
  }

  /**
   * Publish bytes (publisher) or send a request (client).
   * @param {number} ep writer endpoint
   * @param {Uint8Array} src payload (may be a view of a wasm heap)
   * @param {number} timeoutMs how long to block on a full KEEP_ALL reader (< 0: forever)
   * @returns {number} the message's sequence number (1, 2, ...)
   */
  publish(ep, src, timeoutMs = -1) {
    if (!(src instanceof Uint8Array)) this._badPayload(ep, src, 'publish');
    return this._write(ep, src, 0, src.length, timeoutMs, 0, 0, 0, 0, 'publish');
  }

  /**
   * Publish `len` bytes at `offset` of `heap` (e.g. a wasm heap) without
   * creating a view of them; `heap` null: of the memory given to
   * useHeapMemory(), copied with memory.copy.
   * @returns {number} the message's sequence number
   */
  publishFrom(ep, heap, offset, len, timeoutMs = -1) {
    return this._write(ep, heap, offset, len, timeoutMs, 0, 0, 0, 0, 'publish');
  }

  _badPayload(ep, src, op) {
    this._checkEndpoint(ep, 0, op);
    throw new BusError(Code.INVALID_ARGUMENT,
      `${op} on '${this.endpointName(ep)}' failed: the payload must be a Uint8Array, got ${describeValue(src)}`);
  }

  /**
   * Send a response (service) to the client named by `gid`.
   * @param {number} ep service endpoint
   * @param {ArrayLike<number>} gid the request id's client gid (4 words)
   * @param {number} seqLo request sequence number, low word
   * @param {number} seqHi request sequence number, high word
   * @param {Uint8Array} src payload
   * @param {number} timeoutMs
   * @returns {boolean} false when the client is gone (response dropped)
   */
  sendResponse(ep, gid, seqLo, seqHi, src, timeoutMs = -1) {
    this._checkEndpoint(ep, KIND_SERVICE, 'send_response');
    const target = this.bus.endpointOfGid(gid);
    if (target < 0) return false;
    if (!(src instanceof Uint8Array)) this._badPayload(ep, src, 'send_response');
    const serial = this.bus.i32[this.bus.ep(target) + ENDPOINT.SERIAL];
    this._write(ep, src, 0, src.length, timeoutMs, target + 1, serial, seqLo, seqHi, 'send_response');
    return true;
  }

  _write(ep, src, srcOff, len, timeoutMs, target, targetSerial, reqLo, reqHi, op) {
    const bus = this.bus;
    const b = this._checkEndpoint(ep, 0, op);
    if (len > bus.maxMessage) {
      throw new BusError(Code.BAD_ALLOC,
        `${op} on '${this.endpointName(ep)}' failed: message of ${len} bytes exceeds the bus maximum of ${bus.maxMessage} bytes (Runtime option maxMessageBytes)`);
    }
    this._refresh();
    const w = this._writerInfo(ep);
    let i32 = bus.i32;
    const slots = i32[b + ENDPOINT.RING_SLOTS];
    const ring = i32[b + ENDPOINT.RING_OFF] >> 2;
    this._wlock(b);
    let seq;
    try {
      const n = i32[b + ENDPOINT.HEAD]; // only writers (under WLOCK) store it
      const sw = ring + (n & (slots - 1)) * SLOT.WORDS;
      // Before overwriting message n - slots, every blocking reader must have taken it.
      if (w.blocking.length && i32[sw + SLOT.COMMIT] === ((n - slots + 1) | 0) &&
          !this._takenByAll(w, (n - slots) | 0, n) && this._blockingReader(w, (n - slots) | 0, sw) >= 0) {
        this._awaitSlot(ep, b, w, n, slots, sw, timeoutMs, op);
      }
      i32 = bus.i32;
      Atomics.store(i32, sw + SLOT.COMMIT, ~(n + 1));
      let block = i32[sw + SLOT.BLOCK];
      if (i32[sw + SLOT.CAP] < len || block === 0) {
        bus.lock(this.pid);
        try {
          bus.free(block);
          block = bus.alloc(Math.max(len, 64), this.pid);
          i32 = bus.i32;
          i32[sw + SLOT.BLOCK] = block;
          i32[sw + SLOT.CAP] = block ? bus.blockCapacity(block) : 0;
        } finally {
          bus.unlock(this.pid);
        }
        if (!block) {
          const u = bus.memoryUsage();
          throw new BusError(Code.BAD_ALLOC,
            `${op} on '${this.endpointName(ep)}' failed: bus memory exhausted (${len} bytes needed, ${u.arenaUsed} in use, at most ${u.maxBytes}); start the Runtime with a larger maxBytes or use smaller histories`);
        }
      }
      if (block + len > bus.u8.length) bus.refreshViews();
      if (len) {
        if (src === null) this.heapCopier.toBus(block, srcOff, len);
        else copyBytes(bus.u8, block, src, srcOff, len);
      }
      const t = now();
      const hi = i32[b + ENDPOINT.HEAD_HI] + (((n + 1) | 0) === 0 ? 1 : 0);
      i32[sw + SLOT.LEN] = len;
      i32[sw + SLOT.SEQ_HI] = hi;
      i32[sw + SLOT.TARGET] = target;
      i32[sw + SLOT.TARGET_SERIAL] = targetSerial;
      i32[sw + SLOT.REQ_LO] = reqLo;
      i32[sw + SLOT.REQ_HI] = reqHi;
      bus.f64[(sw + SLOT.TIME_F64) >> 1] = t;
      Atomics.store(i32, sw + SLOT.COMMIT, (n + 1) | 0);
      if (((n + 1) | 0) === 0) i32[b + ENDPOINT.HEAD_HI] = hi;
      Atomics.store(i32, b + ENDPOINT.HEAD, (n + 1) | 0);
      bus.f64[(b + ENDPOINT.LAST_PUB_F64) >> 1] = t;
      bus.f64[(b + ENDPOINT.LAST_ASSERT_F64) >> 1] = t;
      seq = hi * 4294967296 + ((n + 1) >>> 0);
    } finally {
      this._wunlock(b);
    }
    const pids = w.pids;
    for (let i = 0; i < pids.length; i++) bus.ring(pids[i]);
    return seq;
  }

  /** Block until slot `sw` (about to hold message n) was taken by every blocking reader. */
  _awaitSlot(ep, b, w, n, slots, sw, timeoutMs, op) {
    const bus = this.bus;
    const deadline = timeoutMs < 0 ? Infinity : now() + timeoutMs;
    const old = (n - slots) | 0;
    let waiting = false;
    Atomics.add(bus.i32, this.sleepersIndex, 1);
    try {
      for (;;) {
        const i32 = bus.i32;
        const bell = Atomics.load(i32, this.bellIndex);
        if (this.service) this.service();
        // The slot holds message `old` only if it was committed (ring not yet wrapped otherwise).
        if (Atomics.load(i32, sw + SLOT.COMMIT) !== ((old + 1) | 0)) return;
        const blocker = this._blockingReader(w, old, sw);
        if (blocker < 0) return;
        if (!waiting) {
          Atomics.add(i32, b + ENDPOINT.ACK_WAITERS, 1);
          waiting = true;
          continue; // re-check after announcing ourselves (see module comment)
        }
        const t = now();
        if (t >= deadline) {
          const rb = bus.ep(i32[bus.link(blocker) + LINK.READER]);
          const rnode = bus.node(i32[rb + ENDPOINT.NODE]);
          const rname = bus.readString(i32[rnode + NODE.STR_OFF], i32[rnode + NODE.NAME_LEN]);
          throw new BusError(Code.TIMEOUT,
            `${op} on '${this.endpointName(ep)}' timed out after ${timeoutMs} ms: the ${KIND_NAMES[i32[rb + ENDPOINT.KIND]]} of node '${rname}' has not taken its oldest pending message and the writer's history of ${slots} messages is full (RELIABLE KEEP_ALL never drops); the message was not sent`);
        }
        // Readers ring only every eighth of the ring (_ringWaitingWriter): look again meanwhile.
        this.sleep(bell, Math.min(deadline - t, ACK_RECHECK_MS));
        this._refresh();
        w = this._writerInfo(ep);
      }
    } finally {
      if (waiting) Atomics.sub(bus.i32, b + ENDPOINT.ACK_WAITERS, 1);
      Atomics.sub(bus.i32, this.sleepersIndex, 1);
    }
  }

  /**
   * True when every blocking reader is known to have taken message `old`.
   * Readers' cursors only move forward, so the lowest cursor seen is a floor
   * that stays true; it is read again only when `old` reaches it (about once
   * per ring of messages), so the writer does not pull the readers' cursor
   * lines across cores on every publish.
   */
  _takenByAll(w, old, head) {
    if (w.floorValid && ((old - w.floor) | 0) < 0) return true;
    const bus = this.bus;
    const i32 = bus.i32;
    const blocking = w.blocking;
    let low = 0; // cursors relative to head: all <= 0
    for (let i = 0; i < blocking.length; i++) {
      const lb = bus.link(blocking[i]);
      const rel = (Atomics.load(i32, lb + LINK.CURSOR) - head) | 0;
      if (rel < low) low = rel;
    }
    w.floor = (head + low) | 0;
    w.floorValid = true;
    return ((old - w.floor) | 0) < 0;
  }

  /** The first blocking link that has not taken message `old` (in slot sw), or -1. */
  _blockingReader(w, old, sw) {
    const bus = this.bus;
    const i32 = bus.i32;
    const blocking = w.blocking;
    for (let i = 0; i < blocking.length; i++) {
      const lb = bus.link(blocking[i]);
      const c = Atomics.load(i32, lb + LINK.CURSOR);
      if (((old - c) | 0) < 0) continue; // taken
      if (Atomics.load(i32, lb + LINK.STATE) !== REC_ALIVE) continue;
      const reader = i32[lb + LINK.READER];
      const rb = bus.ep(reader);
      if ((i32[lb + LINK.FLAGS] & LINK_TARGETED) &&
          (i32[sw + SLOT.TARGET] !== reader + 1 || i32[sw + SLOT.TARGET_SERIAL] !== i32[rb + ENDPOINT.SERIAL])) continue;
      if (!bus.processAlive(i32[rb + ENDPOINT.PID])) continue;
      return blocking[i];
    }
    return -1;
  }

  /**
   * Block until every matched RELIABLE reader took every message so far.
   * @returns {boolean} false on timeout
   */
  waitForAllAcked(ep, timeoutMs) {
    const bus = this.bus;
    const b = this._checkEndpoint(ep, 0, 'wait_for_all_acked');
    const deadline = timeoutMs < 0 ? Infinity : now() + timeoutMs;
    Atomics.add(bus.i32, b + ENDPOINT.ACK_WAITERS, 1);
    Atomics.add(bus.i32, this.sleepersIndex, 1);
    try {
      for (;;) {
        const i32 = bus.i32;
        const bell = Atomics.load(i32, this.bellIndex);
        if (this.service) this.service();
        this._refresh();
        const w = this._writerInfo(ep);
        const head = Atomics.load(i32, b + ENDPOINT.HEAD);
        const slots = i32[b + ENDPOINT.RING_SLOTS];
        let pending = false;
        for (let i = 0; i < w.links.length && !pending; i++) {
          const lb = bus.link(w.links[i]);
          if (Atomics.load(i32, lb + LINK.STATE) !== REC_ALIVE) continue;
          if (i32[lb + LINK.FLAGS] & (LINK_BEST_EFFORT | LINK_TARGETED)) continue;
          if (!bus.processAlive(i32[bus.ep(i32[lb + LINK.READER]) + ENDPOINT.PID])) continue;
          const c = Atomics.load(i32, lb + LINK.CURSOR);
          // Messages the reader can no longer take (ring lapped, or beyond its depth) count as acked.
          let floor = (head - slots) | 0;
          const depth = i32[lb + LINK.DEPTH];
          if (depth && ((head - depth - floor) | 0) > 0) floor = (head - depth) | 0;
          const from = ((c - floor) | 0) > 0 ? c : floor;
          if (((head - from) | 0) > 0) pending = true;
        }
        if (!pending) return true;
        const t = now();
        if (t >= deadline) return false;
        this.sleep(bell, Math.min(deadline - t, ACK_RECHECK_MS));
      }
    } finally {
      Atomics.sub(bus.i32, b + ENDPOINT.ACK_WAITERS, 1);
      Atomics.sub(bus.i32, this.sleepersIndex, 1);
    }
  }

  /** Assert the liveliness of a publisher, or of every publisher of a node (ep = -1 - node). */
  assertLiveliness(ep) {
    const bus = this.bus;
    const t = now();
    if (ep >= 0) {
      const b = this._checkEndpoint(ep, 0, 'assert_liveliness');
      bus.f64[(b + ENDPOINT.LAST_ASSERT_F64) >> 1] = t;
    } else {
      const node = -1 - ep;
      this._checkNode(node);
      const i32 = bus.i32;
      const hwm = Atomics.load(i32, HEADER.EP_HWM);
      for (let e = 0; e < hwm; e++) {
        const b = bus.ep(e);
        if (Atomics.load(i32, b + ENDPOINT.STATE) === REC_ALIVE && i32[b + ENDPOINT.PID] === this.pid &&
            i32[b + ENDPOINT.NODE] === node) bus.f64[(b + ENDPOINT.LAST_ASSERT_F64) >> 1] = t;
      }
    }
    // Readers compute liveliness lazily: make them re-check.
    if (ep >= 0) {
      this._refresh();
      const pids = this._writerInfo(ep).pids;
      for (let i = 0; i < pids.length; i++) bus.ring(pids[i]);
    } else {
      bus.ringAll();
    }
  }

  // ------------------------------------------------------------ reader

  /**
   * Find the next message for reader `ep` and remember it for takeCopy().
   * Skips what the QoS says to skip (overwritten, beyond KEEP_LAST depth,
   * expired, addressed to another client) and counts lost messages.
   * @param {number} ep reader endpoint
   * @param {number} mode TakeMode
   * @returns {number} the message length, or -1 when there is none
   */
  takeBegin(ep, mode) {
    const bus = this.bus;
    this._refresh();
    const links = this._readerLinks(ep);
    const i32 = bus.i32;
    const f64 = bus.f64;
    const rb = bus.ep(ep);
    let drained = null;
    let bestLink = -1;
    let bestTime = Infinity;
    let bestCursor = 0;
    let bestSlot = 0;
    for (let i = 0; i < links.length; i++) {
      const l = links[i];
      const lb = bus.link(l);
      if (i32[lb + LINK.STATE] !== REC_ALIVE) continue;
      const writer = i32[lb + LINK.WRITER];
      const wb = bus.ep(writer);
      const wstate = i32[wb + ENDPOINT.STATE];
      if (wstate !== REC_ALIVE) {
        // DYING: another thread is removing the writer under the registry
        // lock. Its ring stays intact while this link holds untaken messages
        // (it becomes a ZOMBIE), so a reader told "ready" still takes them.
        if (wstate !== REC_ZOMBIE && wstate !== REC_DYING) continue;
        if (((Atomics.load(i32, wb + ENDPOINT.HEAD) - Atomics.load(i32, lb + LINK.CURSOR)) | 0) <= 0) {
          if (wstate === REC_ZOMBIE) (drained || (drained = [])).push(l);
          continue;
        }
      }
      const slots = i32[wb + ENDPOINT.RING_SLOTS];
      const ring = i32[wb + ENDPOINT.RING_OFF] >> 2;
      const flags = i32[lb + LINK.FLAGS];
      for (let guard = 0; guard < 1 << 22; guard++) {
        const head = Atomics.load(i32, wb + ENDPOINT.HEAD);
        const c = Atomics.load(i32, lb + LINK.CURSOR);
        const avail = (head - c) | 0;
        if (avail <= 0) break;
        let start = c;
        if (avail > slots) start = (head - slots) | 0;
        const depth = i32[lb + LINK.DEPTH];
        if (depth && ((head - start) | 0) > depth) start = (head - depth) | 0;
        if (start !== c) {
          if (Atomics.compareExchange(i32, lb + LINK.CURSOR, c, start) === c) {
            let lost;
            if (flags & LINK_BEST_EFFORT) lost = (start - c) | 0;
            else {
              // RELIABLE KEEP_LAST: only what the writer's ring dropped before the reader's depth.
              const ringFloor = (head - slots) | 0;
              const depthFloor = depth ? (head - depth) | 0 : ringFloor;
              const from = ((c - depthFloor) | 0) > 0 ? c : depthFloor;
              lost = Math.max(0, (ringFloor - from) | 0);
            }
            if (lost > 0 && !(flags & LINK_TARGETED)) Atomics.add(i32, rb + ENDPOINT.LOST_TOTAL, lost);
          }
          continue;
        }
        const sw = ring + (c & (slots - 1)) * SLOT.WORDS;
        const commit = Atomics.load(i32, sw + SLOT.COMMIT);
        if (commit !== ((c + 1) | 0)) {
          // Lapped while we looked: the writer is overwriting it. It is lost to us.
          if (Atomics.compareExchange(i32, lb + LINK.CURSOR, c, (c + 1) | 0) === c && !(flags & LINK_TARGETED)) {
            Atomics.add(i32, rb + ENDPOINT.LOST_TOTAL, 1);
          }
          continue;
        }
        if (flags & LINK_TARGETED) {
          const target = i32[sw + SLOT.TARGET];
          const tserial = i32[sw + SLOT.TARGET_SERIAL];
          if (Atomics.load(i32, sw + SLOT.COMMIT) !== commit) continue;
          if (target !== ep + 1 || tserial !== i32[rb + ENDPOINT.SERIAL]) {
            Atomics.compareExchange(i32, lb + LINK.CURSOR, c, (c + 1) | 0);
            continue;
          }
        }
        const t = f64[(sw + SLOT.TIME_F64) >> 1];
        const lifespan = f64[(wb + ENDPOINT.LIFESPAN_MS_F64) >> 1];
        if (lifespan !== Infinity && now() - t > lifespan) {
          if (Atomics.load(i32, sw + SLOT.COMMIT) === commit) {
            Atomics.compareExchange(i32, lb + LINK.CURSOR, c, (c + 1) | 0);
          }
          continue;
        }
        if (t < bestTime || bestLink < 0) {
          bestTime = t;
          bestLink = l;
          bestCursor = c;
          bestSlot = sw;
        }
        break;
      }
    }
    if (drained) this._reapDrained(drained);
    if (bestLink < 0) return -1;
    const st = this._t;
    const commit = (bestCursor + 1) | 0;
    st.link = bestLink;
    st.cursor = bestCursor;
    st.slot = bestSlot;
    st.commit = commit;
    st.block = i32[bestSlot + SLOT.BLOCK];
    st.len = i32[bestSlot + SLOT.LEN];
    st.reader = ep;
    st.mode = mode;
    st.writer = i32[bus.link(bestLink) + LINK.WRITER];
    if (Atomics.load(i32, bestSlot + SLOT.COMMIT) !== commit || st.len < 0 || st.len > bus.maxMessage) {
      // Torn read of a slot being overwritten: report "something may be there" with no length.
      st.len = 0;
      st.block = -1;
    }
    return st.len;
  }

  /** Remove links from writers that left and whose messages we took (rare). */
  _reapDrained(links) {
    const bus = this.bus;
    bus.lock(this.pid);
    try {
      bus.reapDrainedLinks(links);
      bus.bumpGraph();
    } finally {
      bus.unlock(this.pid);
    }
  }

  /**
   * Copy the message found by takeBegin() to `dst` at `dstOff`, validate it
   * and consume it. On false, call takeBegin() again (it was overwritten or
   * another thread took it).
   * @param {?Uint8Array} dst destination (e.g. the wasm heap); null: the
   *   memory given to useHeapMemory(), copied with memory.copy
   * @param {number} dstOff
   * @returns {boolean}
   */
  takeCopy(dst, dstOff) {
    const bus = this.bus;
    const st = this._t;
    const i32 = bus.i32;
    const sw = st.slot;
    if (st.block < 0) return false;
    const info = this.info;
    info.sourceTime = bus.f64[(sw + SLOT.TIME_F64) >> 1];
    info.pubSeqHi = i32[sw + SLOT.SEQ_HI];
    info.reqLo = i32[sw + SLOT.REQ_LO];
    info.reqHi = i32[sw + SLOT.REQ_HI];
    const len = st.len;
    if (len) {
      if (st.block + len > bus.u8.length && (!bus.refreshViews() || st.block + len > bus.u8.length)) {
        return false;
      }
      if (dst === null) this.heapCopier.fromBus(dstOff, st.block, len);
      else copyBytes(dst, dstOff, bus.u8, st.block, len);
    }
    if (Atomics.load(i32, sw + SLOT.COMMIT) !== st.commit) return false;
    const lb = bus.link(st.link);
    if (Atomics.compareExchange(i32, lb + LINK.CURSOR, st.cursor, (st.cursor + 1) | 0) !== st.cursor) return false;
    const rb = bus.ep(st.reader);
    const wb = bus.ep(st.writer);
    info.len = len;
    info.pubSeqLo = st.commit;
    // On the bus a message enters every matched reader's history when its
    // writer commits it (the slot's time), as a DDS sample's reception
    // timestamp is taken on arrival, not on take. This also spares a clock
    // read per take (a clock read costs 90-340 ns in a Chromium worker, see bus.mjs).
    info.receivedTime = info.sourceTime;
    const lo = Atomics.add(i32, rb + ENDPOINT.RECV_SEQ_LO, 1) + 1;
    if (lo === 0) Atomics.add(i32, rb + ENDPOINT.RECV_SEQ_HI, 1);
    info.recvSeqLo = lo;
    info.recvSeqHi = i32[rb + ENDPOINT.RECV_SEQ_HI];
    info.sameProcess = i32[wb + ENDPOINT.PID] === this.pid;
    const g = info.gid;
    if (st.mode === TakeMode.RESPONSE) {
      // The request id of a response is (this client's gid, the request's number).
      g[0] = bus.id; g[1] = this.pid; g[2] = (KIND_CLIENT << 24) | st.reader; g[3] = i32[rb + ENDPOINT.SERIAL];
    } else {
      g[0] = bus.id; g[1] = i32[wb + ENDPOINT.PID]; g[2] = (i32[wb + ENDPOINT.KIND] << 24) | st.writer; g[3] = i32[wb + ENDPOINT.SERIAL];
      info.reqLo = st.commit;
      info.reqHi = info.pubSeqHi;
    }
    if (Atomics.load(i32, wb + ENDPOINT.ACK_WAITERS) > 0) this._ringWaitingWriter(wb, (st.cursor + 1) | 0);
    return true;
  }

  /**
   * Wake the writer's threads that wait for room or for acknowledgements,
   * once this reader's cursor is `next`. Woken per message, a writer that is
   * faster than its reader would sleep and wake once per message (a futex
   * call on both sides each time); so the reader rings when it has taken
   * everything, or each time it has freed an eighth of the ring. A writer
   * also looks again every ACK_RECHECK_MS, for a reader that stops between.
   */
  _ringWaitingWriter(wb, next) {
    const i32 = this.bus.i32;
    const slots = i32[wb + ENDPOINT.RING_SLOTS];
    const step = slots >= 8 ? slots >> 3 : 1;
    if ((next & (step - 1)) === 0 || ((Atomics.load(i32, wb + ENDPOINT.HEAD) - next) | 0) <= 0) {
      this.bus.ring(i32[wb + ENDPOINT.PID]);
    }
  }

  /**
   * Take the next message as a new Uint8Array (JS callers).
   * @param {number} ep reader endpoint
   * @param {number} [mode] TakeMode
   * @returns {Uint8Array|null} null when there is none; this.info describes it
   */
  take(ep, mode = TakeMode.MESSAGE) {
    const kinds = [KIND_SUBSCRIPTION, KIND_SERVICE, KIND_CLIENT];
    this._checkEndpoint(ep, kinds[mode], 'take');
    for (;;) {
      const len = this.takeBegin(ep, mode);
      if (len < 0) return null;
      const out = new Uint8Array(len);
      if (this.takeCopy(out, 0)) return out;
    }
  }

  /** True when reader `ep` has a message to take now. */
  hasData(ep) {
    return this.takeBegin(ep, 0) >= 0;
  }

  /** Number of live matched peers (publisher: readers; subscription: writers). */
  matchedCount(ep) {
    const bus = this.bus;
    const i32 = bus.i32;
    const b = this._checkEndpoint(ep, 0, 'matched_count');
    this._refresh();
    const kind = i32[b + ENDPOINT.KIND];
    const links = kind === KIND_PUBLISHER || kind === KIND_CLIENT ? this._writerInfo(ep).links : this._readerLinks(ep);
    let n = 0;
    for (let i = 0; i < links.length; i++) {
      const lb = bus.link(links[i]);
      if (Atomics.load(i32, lb + LINK.STATE) !== REC_ALIVE) continue;
      const other = i32[lb + LINK.WRITER] === ep ? i32[lb + LINK.READER] : i32[lb + LINK.WRITER];
      const ob = bus.ep(other);
      if (Atomics.load(i32, ob + ENDPOINT.STATE) === REC_ALIVE && bus.processAlive(i32[ob + ENDPOINT.PID])) n++;
    }
    return n;
  }

  /** True when a client has at least one live matched server. */
  serverAvailable(ep) {
    this._checkEndpoint(ep, KIND_CLIENT, 'service_server_is_available');
    return this.matchedCount(ep) > 0;
  }

  // ------------------------------------------------------------ events

  _evlock(b) {
    const i32 = this.bus.i32;
    const w = b + ENDPOINT.EVLOCK;
    if (Atomics.compareExchange(i32, w, 0, 1) === 0) return;
    for (;;) {
      if (Atomics.exchange(i32, w, 2) === 0) return;
      Atomics.wait(i32, w, 2);
    }
  }

  _evunlock(b) {
    const i32 = this.bus.i32;
    if (Atomics.exchange(i32, b + ENDPOINT.EVLOCK, 0) === 2) Atomics.notify(i32, b + ENDPOINT.EVLOCK, 1);
  }

  /** Advance the deadline accounting of endpoint record b; returns the next expiry. */
  _accountDeadline(b, base) {
    const bus = this.bus;
    const i32 = bus.i32;
    const f64 = bus.f64;
    const period = f64[(b + ENDPOINT.DEADLINE_MS_F64) >> 1];
    if (period === Infinity || base <= 0) return Infinity;
    if (f64[(b + ENDPOINT.DEADLINE_ACCT_BASE_F64) >> 1] !== base) {
      f64[(b + ENDPOINT.DEADLINE_ACCT_BASE_F64) >> 1] = base;
      i32[b + ENDPOINT.DEADLINE_ACCT_N] = 0;
    }
    const k = Math.floor((now() - base) / period);
    const counted = i32[b + ENDPOINT.DEADLINE_ACCT_N];
    if (k > counted) {
      i32[b + ENDPOINT.DEADLINE_TOTAL] += k - counted;
      i32[b + ENDPOINT.DEADLINE_ACCT_N] = k;
    }
    return base + (Math.max(k, counted) + 1) * period;
  }

  /** Liveliness of the writers matched to reader ep: [alive, notAlive, nextExpiry]. */
  _liveliness(ep) {
    const bus = this.bus;
    const i32 = bus.i32;
    const f64 = bus.f64;
    const links = this._readerLinks(ep);
    let alive = 0;
    let notAlive = 0;
    let next = Infinity;
    const t = now();
    for (let i = 0; i < links.length; i++) {
      const lb = bus.link(links[i]);
      if (Atomics.load(i32, lb + LINK.STATE) !== REC_ALIVE) continue;
      const wb = bus.ep(i32[lb + LINK.WRITER]);
      if (Atomics.load(i32, wb + ENDPOINT.STATE) !== REC_ALIVE || !bus.processAlive(i32[wb + ENDPOINT.PID])) continue;
      const lease = f64[(wb + ENDPOINT.LEASE_MS_F64) >> 1];
      if (i32[wb + ENDPOINT.QOS + QOS.LIVELINESS] === Liveliness.MANUAL_BY_TOPIC && lease !== Infinity) {
        const until = f64[(wb + ENDPOINT.LAST_ASSERT_F64) >> 1] + lease;
        if (t <= until) {
          alive++;
          next = Math.min(next, until);
        } else notAlive++;
      } else alive++;
    }
    return [alive, notAlive, next];
  }

  /**
   * Compute (and with `take`, consume) the status of one event of endpoint ep.
   * @param {number} ep
   * @param {number} type EventType
   * @param {boolean} take reset the "change" fields
   * @returns {{changed: boolean, total: number, change: number, alive: number, notAlive: number,
   *            aliveChange: number, notAliveChange: number, policy: number, next: number}}
   */
  eventStatus(ep, type, take) {
    const bus = this.bus;
    const b = this._checkEndpoint(ep, 0, 'event');
    const i32 = bus.i32;
    const f64 = bus.f64;
    const kind = i32[b + ENDPOINT.KIND];
    const isWriter = kind === KIND_PUBLISHER;
    const isReader = kind === KIND_SUBSCRIPTION;
    const ok = isReader ? type <= 3 : (isWriter && type >= 4 && type <= 6);
    if (!ok) {
      throw new BusError(Code.INVALID_ARGUMENT, `event type ${type} does not apply to a ${KIND_NAMES[kind]}`);
    }
    this._refresh();
    const r = {
      changed: false, total: 0, change: 0, alive: 0, notAlive: 0, aliveChange: 0, notAliveChange: 0,
      policy: 0, next: Infinity,
    };
    this._evlock(b);
    try {
      let totalW = 0;
      let seenW = 0;
      switch (type) {
        case EventType.REQUESTED_QOS_INCOMPATIBLE:
        case EventType.OFFERED_QOS_INCOMPATIBLE:
          totalW = ENDPOINT.INCOMPAT_TOTAL; seenW = ENDPOINT.INCOMPAT_SEEN;
          r.policy = Atomics.load(i32, b + ENDPOINT.INCOMPAT_POLICY);
          break;
        case EventType.MESSAGE_LOST:
          totalW = ENDPOINT.LOST_TOTAL; seenW = ENDPOINT.LOST_SEEN;
          break;
        case EventType.OFFERED_DEADLINE_MISSED:
          r.next = this._accountDeadline(b, f64[(b + ENDPOINT.LAST_PUB_F64) >> 1] * (i32[b + ENDPOINT.HEAD] !== 0 || i32[b + ENDPOINT.HEAD_HI] !== 0 ? 1 : 0));
          totalW = ENDPOINT.DEADLINE_TOTAL; seenW = ENDPOINT.DEADLINE_SEEN;
          break;
        case EventType.REQUESTED_DEADLINE_MISSED: {
          let base = 0;
          const links = this._readerLinks(ep);
          for (let i = 0; i < links.length; i++) {
            const lb = bus.link(links[i]);
            if (Atomics.load(i32, lb + LINK.STATE) !== REC_ALIVE) continue;
            const wb = bus.ep(i32[lb + LINK.WRITER]);
            if (i32[wb + ENDPOINT.HEAD] === 0 && i32[wb + ENDPOINT.HEAD_HI] === 0) continue;
            base = Math.max(base, f64[(wb + ENDPOINT.LAST_PUB_F64) >> 1]);
          }
          r.next = this._accountDeadline(b, base);
          totalW = ENDPOINT.DEADLINE_TOTAL; seenW = ENDPOINT.DEADLINE_SEEN;
          break;
        }
        case EventType.LIVELINESS_LOST: {
          const lease = f64[(b + ENDPOINT.LEASE_MS_F64) >> 1];
          if (i32[b + ENDPOINT.QOS + QOS.LIVELINESS] === Liveliness.MANUAL_BY_TOPIC && lease !== Infinity) {
            const base = f64[(b + ENDPOINT.LAST_ASSERT_F64) >> 1];
            if (now() > base + lease) {
              if (f64[(b + ENDPOINT.LIVE_LOST_BASE_F64) >> 1] !== base) {
                f64[(b + ENDPOINT.LIVE_LOST_BASE_F64) >> 1] = base;
                i32[b + ENDPOINT.LIVE_LOST_TOTAL] += 1;
              }
            } else r.next = base + lease;
          }
          totalW = ENDPOINT.LIVE_LOST_TOTAL; seenW = ENDPOINT.LIVE_LOST_SEEN;
          break;
        }
        case EventType.LIVELINESS_CHANGED: {
          const [alive, notAlive, next] = this._liveliness(ep);
          r.alive = alive;
          r.notAlive = notAlive;
          r.next = next;
          r.aliveChange = alive - i32[b + ENDPOINT.ALIVE_SEEN];
          r.notAliveChange = notAlive - i32[b + ENDPOINT.NOT_ALIVE_SEEN];
          r.changed = r.aliveChange !== 0 || r.notAliveChange !== 0;
          if (take) {
            i32[b + ENDPOINT.ALIVE_SEEN] = alive;
            i32[b + ENDPOINT.NOT_ALIVE_SEEN] = notAlive;
          }
          return r;
        }
        default:
          throw new BusError(Code.INVALID_ARGUMENT, `unknown event type ${type}`);
      }
      r.total = Atomics.load(i32, b + totalW);
      r.change = r.total - i32[b + seenW];
      r.changed = r.change !== 0;
      if (take) i32[b + seenW] = r.total;
      return r;
    } finally {
      this._evunlock(b);
    }
  }

  // ------------------------------------------------------------ waiting

  /** The process doorbell value (read before checking, pass to sleep()). */
  bell() {
    return Atomics.load(this.bus.i32, this.bellIndex);
  }

  /** Count this thread as a sleeper of the process (before bell() and checking). */
  register() {
    Atomics.add(this.bus.i32, this.sleepersIndex, 1);
  }

  /** Stop counting this thread as a sleeper. */
  unregister() {
    Atomics.sub(this.bus.i32, this.sleepersIndex, 1);
  }

  /**
   * Sleep on this process' doorbell while it still holds `bell` (registered callers only).
   * @param {number} bell value read after register() and before checking the entities
   * @param {number} ms at most this long (Infinity: no limit)
   */
  sleep(bell, ms) {
    if (this._beforeSleep !== null) this._firstSleep();
    Atomics.wait(this.bus.i32, this.bellIndex, bell, ms);
  }

  /**
   * Call `fn` once, just before this thread first sleeps on the bus (a wait,
   * a blocked publish, a wait for acknowledgements): the host's sign that
   * main() has started and now waits for work.
   * @param {function(): void} fn
   */
  beforeFirstSleep(fn) {
    this._beforeSleep = fn;
  }

  _firstSleep() {
    const fn = this._beforeSleep;
    this._beforeSleep = null;
    fn();
  }

  /** Wake every wait of this process (guard condition triggers, listener changes). */
  ringSelf() {
    this.bus.ring(this.pid);
  }

  /**
   * Check wait items once.
   * @param {Int32Array} items WAIT_ITEM_WORDS words per item: kind, handle, aux, result
   * @param {number} base first word
   * @param {number} count items
   * @param {Int32Array} heap32 the memory guard condition pointers refer to
   * @returns {number} number of ready items; this._nextExpiry is set
   */
  checkItems(items, base, count, heap32) {
    let ready = 0;
    let next = Infinity;
    for (let i = 0; i < count; i++) {
      const o = base + i * WAIT_ITEM_WORDS;
      const kind = items[o];
      const handle = items[o + 1];
      let r = 0;
      switch (kind) {
        case WaitKind.SUBSCRIPTION:
        case WaitKind.SERVICE:
          r = this.takeBegin(handle, kind === WaitKind.SERVICE ? TakeMode.REQUEST : TakeMode.MESSAGE) >= 0 ? 1 : 0;
          break;
        case WaitKind.CLIENT:
          r = this.takeBegin(handle, TakeMode.RESPONSE) >= 0 ? 1 : 0;
          break;
        case WaitKind.GUARD_CONDITION: {
          const w = handle >> 2;
          if (heap32[w] === 1) {
            const v = Atomics.load(this.bus.i32, HEADER.GRAPH_VERSION);
            if (Atomics.exchange(heap32, w + 2, v) !== v) r = 1;
          }
          if (Atomics.exchange(heap32, w + 1, 0) !== 0) r = 1;
          break;
        }
        case WaitKind.EVENT: {
          const s = this.eventStatus(handle, items[o + 2], false);
          r = s.changed ? 1 : 0;
          if (s.next < next) next = s.next;
          break;
        }
        default:
          throw new BusError(Code.INVALID_ARGUMENT, `wait: unknown item kind ${kind}`);
      }
      items[o + 3] = r;
      ready += r;
    }
    this._nextExpiry = next;
    return ready;
  }

  /**
   * Wait until an item is ready or the timeout passes.
   * @param {Int32Array} items see checkItems()
   * @param {number} base
   * @param {number} count
   * @param {number} timeoutMs < 0: forever, 0: check once
   * @param {Int32Array} heap32
   * @param {boolean} returnAfterWake return -1 after the first sleep (the caller
   *   has work to do between sleeps, e.g. the main thread's proxied calls)
   * @returns {number} ready count (0: timed out, -1: woken, call again)
   */
  wait(items, base, count, timeoutMs, heap32, returnAfterWake = false) {
    // The clock is read only when we are about to sleep (a clock read costs
    // 90-340 ns in a Chromium worker, see bus.mjs).
    let deadline = timeoutMs < 0 ? Infinity : -1;
    for (;;) {
      if (this.service) this.service();
      let ready = this.checkItems(items, base, count, heap32);
      if (ready > 0 || timeoutMs === 0) return ready;
      const t = now();
      if (deadline < 0) deadline = t + timeoutMs;
      if (t >= deadline) return 0;
      // Register, then look again before sleeping (see the module comment):
      // writers only ring while we are registered, so keep that window short.
      this.register();
      const bell = this.bell();
      if (this.service) this.service();
      ready = this.checkItems(items, base, count, heap32);
      if (ready === 0) {
        const until = Math.min(deadline, this._nextExpiry);
        this.sleep(bell, until === Infinity ? Infinity : Math.max(0, until - t));
      }
      this.unregister();
      if (ready > 0) return ready;
      if (returnAfterWake) return -1;
    }
  }

  /**
   * Count what arrived since the listener last looked (no message is taken).
   * Items use the wait layout and must live in `items` = the wasm heap (a
   * guard condition item points at a wake-up word there); result = number
   * of new events.
   * @returns {number} total new events; this._nextExpiry is set
   */
  listenCheck(items, base, count) {
    const bus = this.bus;
    const i32 = bus.i32;
    this._refresh();
    let total = 0;
    let next = Infinity;
    for (let i = 0; i < count; i++) {
      const o = base + i * WAIT_ITEM_WORDS;
      const kind = items[o];
      const ep = items[o + 1];
      let n = 0;
      if (kind === WaitKind.GUARD_CONDITION) {
        // The listener's own wake-up word (registration changes): items is the wasm heap.
        n = Atomics.exchange(items, (ep >> 2) + 1, 0) !== 0 ? 1 : 0;
      } else if (kind === WaitKind.EVENT) {
        const key = -1 - (ep * 8 + items[o + 2]);
        const s = this.eventStatus(ep, items[o + 2], false);
        const level = items[o + 2] === EventType.LIVELINESS_CHANGED
          ? s.alive * 65536 + s.notAlive : s.total;
        const seen = this._listenMarks.get(key);
        if (seen === undefined) {
          n = s.changed ? 1 : 0;
        } else if (seen !== level) n = items[o + 2] === EventType.LIVELINESS_CHANGED ? 1 : level - seen;
        this._listenMarks.set(key, level);
        if (s.next < next) next = s.next;
      } else {
        const links = this._readerLinks(ep);
        for (let k = 0; k < links.length; k++) {
          const lb = bus.link(links[k]);
          if (Atomics.load(i32, lb + LINK.STATE) !== REC_ALIVE) continue;
          const wb = bus.ep(i32[lb + LINK.WRITER]);
          const head = Atomics.load(i32, wb + ENDPOINT.HEAD);
          const key = links[k] * LISTEN_KEY + ep;
          let mark = this._listenMarks.get(key);
          if (mark === undefined) mark = Atomics.load(i32, lb + LINK.CURSOR);
          const slots = i32[wb + ENDPOINT.RING_SLOTS];
          let from = mark;
          if (((head - from) | 0) > slots) from = (head - slots) | 0;
          if (i32[lb + LINK.FLAGS] & LINK_TARGETED) {
            const ring = i32[wb + ENDPOINT.RING_OFF] >> 2;
            const serial = i32[bus.ep(ep) + ENDPOINT.SERIAL];
            for (let m = from; ((head - m) | 0) > 0; m = (m + 1) | 0) {
              const sw = ring + (m & (slots - 1)) * SLOT.WORDS;
              if (i32[sw + SLOT.TARGET] === ep + 1 && i32[sw + SLOT.TARGET_SERIAL] === serial) n++;
            }
          } else {
            let d = (head - from) | 0;
            const depth = i32[lb + LINK.DEPTH];
            if (depth && d > depth && mark === Atomics.load(i32, lb + LINK.CURSOR)) d = depth;
            n += Math.max(0, d);
          }
          this._listenMarks.set(key, head);
        }
      }
      items[o + 3] = n;
      total += n;
    }
    this._nextExpiry = next;
    return total;
  }

  /**
   * Wait until something new arrives for the listener's items (nothing is taken).
   * @returns {number} new events (0: timed out, -1: woken, call again)
   */
  listen(items, base, count, timeoutMs, returnAfterWake = false) {
    const deadline = timeoutMs < 0 ? Infinity : now() + timeoutMs;
    this.register();
    try {
      for (;;) {
        const bell = this.bell();
        if (this.service) this.service();
        const n = this.listenCheck(items, base, count);
        if (n > 0) return n;
        const t = now();
        if (t >= deadline) return 0;
        const until = Math.min(deadline, this._nextExpiry);
        this.sleep(bell, until === Infinity ? Infinity : Math.max(0, until - t));
        if (returnAfterWake) return -1;
      }
    } finally {
      this.unregister();
    }
  }

  /** Forget the listener marks of endpoint ep (its callback was cleared). */
  listenForget(ep) {
    for (const key of [...this._listenMarks.keys()]) {
      if ((key >= 0 && key % LISTEN_KEY === ep) || (key < 0 && Math.floor((-1 - key) / 8) === ep)) {
        this._listenMarks.delete(key);
      }
    }
  }

  // ------------------------------------------------------------ graph

  /** The graph version. */
  graphVersion() {
    return this.bus.graphVersion();
  }

  /**
   * A snapshot of the graph.
   * @param {object} [filter] {domain}
   */
  graph(filter) {
    return this.bus.snapshot(filter);
  }
}

export { Code, BusError, KIND_CLIENT, KIND_PUBLISHER, KIND_SERVICE, KIND_SUBSCRIPTION };
