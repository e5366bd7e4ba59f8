// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The main thread's handle of the recording worker (./recording_worker.mjs,
 * Node.js only): it starts the worker as a bus process of the Runtime,
 * sends it requests (each followed by a ring of its doorbell, since the
 * worker reads them between waits) and passes its chunks on, a batch at a
 * time.
 *
 * @module bridges/record/recording_process
 */

import { MessageChannel, Worker } from 'node:worker_threads';
import { ChunkPool } from './chunk_pool.mjs';

/** After a wake-up the worker naps this long: bursts are taken together. */
const COALESCE_MS = 5;
/** Chunk buffers shared with the worker: what may wait for the disk without an allocation. */
const POOL_SLOTS = 16;
/** Closed chunks posted together (one message, one write, one report), */
const BATCH_CHUNKS = 4;
/** unless the first of them waited this long. */
const BATCH_MS = 50;

export class RecordingProcess {
  /**
   * Start the recording worker.
   * @param {import('../../runtime.mjs').Runtime} runtime
   * @param {object} options
   * @param {boolean} options.crc add the CRC-32 of each chunk's records (`crc`)
   * @param {number} options.chunkBytes chunk size
   * @param {number} options.flushMs a chunk is closed at the latest this long after its first message
   * @param {function(object[]): void} options.onChunks gets the closed chunks, a batch at a
   *   time, in the order they closed: each {records: Uint8Array, indexes: Uint8Array, crc,
   *   channels, start, end, messages, release}; call `release()` once its bytes are written
   * @returns {Promise<RecordingProcess>}
   */
  static async start(runtime, { crc, chunkBytes, flushMs, onChunks }) {
    const { pid, release } = await runtime.helperProcess('recorder');
    const { port1, port2 } = new MessageChannel();
    const requests = new SharedArrayBuffer(4);
    const pool = ChunkPool.create(POOL_SLOTS, chunkBytes);
    const worker = new Worker(new URL('./recording_worker.mjs', import.meta.url), {
      name: 'wasm_js recorder',
      workerData: {
        handle: runtime.bus.handle, pid, control: port2, requests, crc, chunkBytes, flushMs,
        pool: { memory: pool.memory, slots: pool.slots, slotBytes: pool.slotBytes },
        coalesceMs: COALESCE_MS, batchChunks: BATCH_CHUNKS, batchMs: BATCH_MS,
      },
      transferList: [port2],
    });
    return new RecordingProcess(runtime, { pid, release }, worker, port1, new Int32Array(requests), pool, onChunks);
  }

  constructor(runtime, { pid, release }, worker, port, requests, pool, onChunks) {
    this.runtime = runtime;
    /** The recording worker's bus process id. */
    this.pid = pid;
    this._worker = worker;
    this._port = port;
    this._requests = requests;
    this._next = 1;
    this._pending = new Map();
    this._ended = false;
    this.exited = new Promise((resolve) => {
      worker.on('exit', (code) => {
        this._ended = true;
        const why = new Error(`the recording worker ended (exit code ${code})`);
        for (const p of this._pending.values()) p.reject(why);
        this._pending.clear();
        // its endpoints leave the graph as those of any process that ends
        release().then(resolve, resolve);
      });
    });
    /** the worker's error, when it failed */
    this.error = null;
    worker.on('error', (e) => { this.error = e; });
    worker.on('message', (m) => {
      if (m.type === 'chunks') {
        onChunks(m.chunks.map((c) => ({
          ...c,
          records: c.slot >= 0 ? pool.bytes(c.slot).subarray(0, c.length) : new Uint8Array(c.records, 0, c.length),
          indexes: new Uint8Array(c.indexes),
          release: () => { if (c.slot >= 0) pool.release(c.slot); },
        })));
        return;
      }
      const p = this._pending.get(m.id);
      if (!p) return;
      this._pending.delete(m.id);
      if (m.error) p.reject(Object.assign(new Error(m.error.message), { code: m.error.code }));
      else p.resolve(m.value);
    });
    runtime._atClose(() => this.stop());
  }

  /** Send a request; its answer comes back from the worker. */
  _call(op, args, transfer = []) {
    if (this._ended) return Promise.reject(new Error('the recording worker has ended'));
    const id = this._next++;
    return new Promise((resolve, reject) => {
      this._pending.set(id, { resolve, reject });
      this._post({ id, op, args }, transfer);
    });
  }

  /** Post a request, count it (the worker reads its port only then) and wake the worker. */
  _post(message, transfer = []) {
    this._port.postMessage(message, transfer);
    Atomics.add(this._requests, 0, 1);
    this.runtime.bus.ring(this.pid);
  }

  /** Create the recorder's node. */
  node(name, namespace = '/') {
    return this._call('node', { name, namespace });
  }

  /**
   * Record a topic as MCAP channel `channel`.
   * @returns {Promise<number>} the subscription endpoint
   */
  add({ node, topic, type, qos, channel }) {
    return this._call('add', { node, topic, type, qos, channel });
  }

  /** Record nothing more (the bag failed); `stop` still ends the worker. */
  halt() {
    return this._call('halt');
  }

  /**
   * Record what is waiting, close the last chunk, unsubscribe; resolves once the worker ended.
   * @returns {Promise<{lost: number}>} messages the publishers' histories dropped before the
   *   worker took them
   */
  async stop() {
    let result = { lost: 0 };
    if (!this._ended) result = await this._call('stop').catch(() => result);
    await this.exited;
    return result;
  }
}
