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
 * This class holds the thread's state and gives the rooms of src/client/
 * one face:
 *   links.mjs     the links of this thread's endpoints, cached per graph version
 *   registry.mjs  nodes and endpoints of this process
 *   writer.mjs    publish, send_response, wait_for_all_acked, liveliness
 *   reader.mjs    take, has_data, matched counts
 *   events.mjs    QoS event status
 *   wait.mjs      doorbell, wait sets, listener
 *
 * @module bus_client
 */

import { EventType, TakeMode, WAIT_ITEM_WORDS, WaitKind } from './abi/bus_abi.mjs';
import {
  Bus, BusError, Code, KIND_CLIENT, KIND_PUBLISHER, KIND_SERVICE, KIND_SUBSCRIPTION,
} from './bus.mjs';
import * as events from './client/events.mjs';
import * as reader from './client/reader.mjs';
import * as registry from './client/registry.mjs';
import * as wait from './client/wait.mjs';
import * as writer from './client/writer.mjs';
import { heapCopier } from './copier.mjs';
import { PROC_KIND_NODE, PROCESS } from './layout.mjs';

/** Event kinds, wait item kinds, take modes: abi/bus_abi.mjs (shared with wasm_cpp). */
export { EventType, TakeMode, WAIT_ITEM_WORDS, WaitKind };

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

  // ---------------------------------------- registry (client/registry.mjs)

  /** A bus-wide unique context id. */
  createContext() { return registry.createContext(this); }

  /**
   * Create a node: {domain, context, name, namespace, enclave}.
   * @returns {{index: number, gid: Int32Array, nameTaken: boolean}}
   */
  createNode(spec) { return registry.createNode(this, spec); }

  /** Remove a node (and its endpoints). */
  destroyNode(index) { registry.destroyNode(this, index); }

  /**
   * Create a publisher, subscription, service or client (see registry.createEndpoint).
   * @returns {{index: number, gid: Int32Array, qos: Int32Array}}
   */
  createEndpoint(spec) { return registry.createEndpoint(this, spec); }

  /** Remove an endpoint. */
  destroyEndpoint(index) { registry.destroyEndpoint(this, index); }

  /** The topic/service name of an endpoint (for messages). */
  endpointName(index) { return registry.endpointName(this, index); }

  // -------------------------------------------- writer (client/writer.mjs)

  /**
   * Publish bytes (publisher) or send a request (client).
   * @param {number} ep writer endpoint
   * @param {Uint8Array} src payload (may be a view of a wasm heap)
   * @param {number} timeoutMs how long to block on a full KEEP_ALL reader (< 0: forever)
   * @returns {number} the message's sequence number (1, 2, ...)
   */
  publish(ep, src, timeoutMs = -1) { return writer.publish(this, ep, src, timeoutMs); }

  /**
   * Publish `len` bytes at `offset` of `heap` without creating a view of
   * them; `heap` null: of the memory given to useHeapMemory().
   * @returns {number} the message's sequence number
   */
  publishFrom(ep, heap, offset, len, timeoutMs = -1) {
    return writer.publishFrom(this, ep, heap, offset, len, timeoutMs);
  }

  /**
   * Send a response (service) to the client named by `gid` (4 words).
   * @returns {boolean} false when the client is gone (response dropped)
   */
  sendResponse(ep, gid, seqLo, seqHi, src, timeoutMs = -1) {
    return writer.sendResponse(this, ep, gid, seqLo, seqHi, src, timeoutMs);
  }

  /**
   * Block until every matched RELIABLE reader took every message so far.
   * @returns {boolean} false on timeout
   */
  waitForAllAcked(ep, timeoutMs) { return writer.waitForAllAcked(this, ep, timeoutMs); }

  /** Assert the liveliness of a publisher, or of every publisher of a node (ep = -1 - node). */
  assertLiveliness(ep) { writer.assertLiveliness(this, ep); }

  // -------------------------------------------- reader (client/reader.mjs)

  /**
   * Find the next message for reader `ep` and remember it for takeCopy().
   * @param {number} ep reader endpoint
   * @param {number} mode TakeMode
   * @returns {number} the message length, or -1 when there is none
   */
  takeBegin(ep, mode) { return reader.takeBegin(this, ep, mode); }

  /**
   * Copy the message found by takeBegin() to `dst` at `dstOff` (null: the
   * memory given to useHeapMemory()), validate it and consume it. On false,
   * call takeBegin() again.
   * @returns {boolean}
   */
  takeCopy(dst, dstOff) { return reader.takeCopy(this, dst, dstOff); }

  /**
   * Take the next message as a new Uint8Array (JS callers).
   * @returns {Uint8Array|null} null when there is none; this.info describes it
   */
  take(ep, mode = TakeMode.MESSAGE) { return reader.take(this, ep, mode); }

  /** True when reader `ep` has a message to take now. */
  hasData(ep) { return reader.hasData(this, ep); }

  /** Number of live matched peers (publisher: readers; subscription: writers). */
  matchedCount(ep) { return reader.matchedCount(this, ep); }

  /** True when a client has at least one live matched server. */
  serverAvailable(ep) { return reader.serverAvailable(this, ep); }

  // -------------------------------------------- events (client/events.mjs)

  /**
   * Compute (and with `take`, consume) the status of one event of endpoint ep.
   * @param {number} ep
   * @param {number} type EventType
   * @param {boolean} take reset the "change" fields
   * @returns {{changed: boolean, total: number, change: number, alive: number, notAlive: number,
   *            aliveChange: number, notAliveChange: number, policy: number, next: number}}
   */
  eventStatus(ep, type, take) { return events.eventStatus(this, ep, type, take); }

  // ------------------------------------------------ waiting (client/wait.mjs)

  /** The process doorbell value (read before checking, pass to sleep()). */
  bell() { return wait.readBell(this); }

  /** Count this thread as a sleeper of the process (before bell() and checking). */
  register() { wait.register(this); }

  /** Stop counting this thread as a sleeper. */
  unregister() { wait.unregister(this); }

  /** Sleep on this process' doorbell while it still holds `bell`, at most `ms`. */
  sleep(bell, ms) { wait.sleep(this, bell, ms); }

  /** Call `fn` once, just before this thread first sleeps on the bus. */
  beforeFirstSleep(fn) { wait.beforeFirstSleep(this, fn); }

  /** Wake every wait of this process (guard condition triggers, listener changes). */
  ringSelf() { wait.ringSelf(this); }

  /**
   * Check wait items once (WAIT_ITEM_WORDS words each: kind, handle, aux, result).
   * @returns {number} number of ready items; this._nextExpiry is set
   */
  checkItems(items, base, count, heap32) { return wait.checkItems(this, items, base, count, heap32); }

  /**
   * Wait until an item is ready or the timeout passes.
   * @returns {number} ready count (0: timed out, -1: woken, call again)
   */
  wait(items, base, count, timeoutMs, heap32, returnAfterWake = false) {
    return wait.wait(this, items, base, count, timeoutMs, heap32, returnAfterWake);
  }

  /**
   * Count what arrived since the listener last looked (no message is taken).
   * @returns {number} total new events; this._nextExpiry is set
   */
  listenCheck(items, base, count) { return wait.listenCheck(this, items, base, count); }

  /**
   * Wait until something new arrives for the listener's items (nothing is taken).
   * @returns {number} new events (0: timed out, -1: woken, call again)
   */
  listen(items, base, count, timeoutMs, returnAfterWake = false) {
    return wait.listen(this, items, base, count, timeoutMs, returnAfterWake);
  }

  /** Forget the listener marks of endpoint ep (its callback was cleared). */
  listenForget(ep) { wait.listenForget(this, ep); }

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
