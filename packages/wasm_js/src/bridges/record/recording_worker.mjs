// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The recording worker of `--record` (Node.js): a bus process of its own
 * whose thread does nothing but record. It blocks in `Atomics.wait` on its
 * doorbell like a C++ node (no event loop turn, promise or timer per
 * wake-up), copies what its subscriptions received into MCAP chunks
 * (./chunk_builder.mjs) in the slots of a pool shared with the main thread
 * (./chunk_pool.mjs), and posts each closed chunk's slot to the main
 * thread, which writes it into the bag (./file_sink.mjs) or sends it to the
 * launcher to be compressed, and frees the slot. It never waits for the disk.
 * With `crc`, it adds the CRC-32 of each chunk's records (zlib's C code)
 * while they are in its cache.
 *
 * While messages come it drains, naps `coalesceMs` and drains again, with
 * no doorbell: a steady 1 kHz topic costs it one timed wake-up per nap
 * (and its publishers no futex wake per message); the writers' histories
 * hold what arrives meanwhile. Only when a drain found nothing does it
 * wait on the doorbell.
 *
 * Closed chunks are posted in batches (`batchChunks`, or once the oldest
 * waited `batchMs`, or at once when a chunk closed on its time): the main
 * thread then writes a batch in one `writev` and the launcher hears of it
 * in one report, which keeps the per-chunk cost of the threads that do not
 * record low.
 *
 * Control comes through a MessagePort read synchronously between waits
 * (`receiveMessageOnPort`, about 20 µs a call: only when a shared counter
 * says a request was posted); whoever posts counts it and rings this
 * process' doorbell. Each request is
 * answered on `parentPort` ({type: 'reply', id, value} or {error}); chunks
 * come as {type: 'chunks', chunks: [...]}.
 *
 * @module bridges/record/recording_worker
 */

import { parentPort, receiveMessageOnPort, workerData } from 'node:worker_threads';
import { BusClient, EventType, KIND_SUBSCRIPTION } from '../../bus_client.mjs';
import zlib from 'node:zlib';
import { ChunkBuilder } from './chunk_builder.mjs';
import { ChunkPool } from './chunk_pool.mjs';

const {
  handle, pid, control, requests, pool, crc, chunkBytes, flushMs, coalesceMs, batchChunks, batchMs,
} = workerData;
/** requests[0] counts the requests posted: the port is read only when it moved */
const posted = new Int32Array(requests);
let served = 0;
const client = BusClient.attach(handle, pid);
const nap = new Int32Array(new SharedArrayBuffer(4));
const post = (m, transfer) => parentPort.postMessage(m, transfer || []);

/** Node.js 20.15 and later: the C CRC-32 of zlib; else the chunks go without one (CRC 0, allowed). */
const crc32 = crc && typeof zlib.crc32 === 'function' ? zlib.crc32 : null;
const builder = new ChunkBuilder(client, {
  chunkBytes, flushMs, sink: postChunk, pool: new ChunkPool(pool.memory, pool.slots, pool.slotBytes),
});
/** subscription endpoints of the recording */
const endpoints = new Set();
let halted = false;
let running = true;

/** closed chunks not posted yet, and when the first of them closed (ms) */
let batch = [];
let transfers = [];
let batchSince = Infinity;

/** Keep a closed chunk for the next batch: its pool slot (or its own buffer), its indexes. */
function postChunk(chunk) {
  const own = chunk.slot < 0 ? chunk.records.buffer : null;
  if (own) transfers.push(own);
  transfers.push(chunk.indexes.buffer);
  batch.push({
    slot: chunk.slot, records: own, length: chunk.records.length,
    indexes: chunk.indexes.buffer, crc: crc32 ? crc32(chunk.records) : 0,
    channels: chunk.channels, start: chunk.start, end: chunk.end, messages: chunk.messages,
  });
  if (batch.length === 1) batchSince = performance.now();
  if (batch.length >= batchChunks) postBatch();
}

/** Post the closed chunks kept so far (in the order they closed). */
function postBatch() {
  if (batch.length === 0) return;
  post({ type: 'chunks', chunks: batch }, transfers);
  batch = [];
  transfers = [];
  batchSince = Infinity;
}

/** Let go of every subscription (the ones it took are in the chunks posted). */
function unsubscribe() {
  let lost = 0;
  for (const ep of endpoints) {
    lost += client.eventStatus(ep, EventType.MESSAGE_LOST, false).total;
    client.destroyEndpoint(ep);
  }
  endpoints.clear();
  builder.channels.clear();
  return lost;
}

/**
 * Copy what came; close the chunk when its time is up (and post it at once:
 * nothing more is coming soon), post a batch that waited long enough.
 * @returns {number} how many messages were copied
 */
function record() {
  const copied = builder.drain();
  if (builder.flushDue()) {
    builder.flush();
    postBatch();
  } else if (performance.now() - batchSince >= batchMs) {
    postBatch();
  }
  return copied;
}

/** How long the loop may wait before `record()` has something to close or post (ms). */
function due() {
  const at = Math.min(builder.deadline, batchSince + batchMs);
  return at === Infinity ? Infinity : Math.max(0, at - performance.now());
}

const operations = {
  node({ name, namespace }) {
    return client.createNode({ name, namespace, context: client.createContext() }).index;
  },
  /** Subscribe to a topic as MCAP channel `channel`. */
  add({ node, topic, type, qos, channel }) {
    if (halted) throw new Error('recording stopped');
    const ep = client.createEndpoint({ kind: KIND_SUBSCRIPTION, node, name: topic, type, qos }).index;
    endpoints.add(ep);
    builder.add(ep, channel);
    record(); // a TRANSIENT_LOCAL writer's history is there at once
    return ep;
  },
  /** Record nothing more (the bag failed): unsubscribe, keep answering. */
  halt() {
    halted = true;
    unsubscribe();
  },
  /**
   * Record what is waiting, close the last chunk, unsubscribe, end the loop.
   * @returns {{lost: number}} the messages the publishers' histories dropped
   *   before this worker took them (the bus counts them per subscription)
   */
  stop() {
    record();
    builder.flush();
    postBatch();
    const lost = unsubscribe();
    running = false;
    return { lost };
  },
};

function serve({ id, op, args }) {
  try {
    post({ type: 'reply', id, value: operations[op](args || {}) });
  } catch (e) {
    post({ type: 'reply', id, error: { message: e.message, code: e.code || 1 } });
  }
}

/** Serve the requests posted since the last look (the counter moved). */
function serveRequests() {
  const count = Atomics.load(posted, 0);
  if (count === served) return;
  served = count;
  for (let m; running && (m = receiveMessageOnPort(control));) serve(m.message);
}

while (running) {
  serveRequests();
  if (!running) break;
  if (record() > 0) {
    // messages are coming: take the next ones after a nap, with no doorbell
    Atomics.wait(nap, 0, 0, Math.min(coalesceMs, due()));
    continue;
  }
  client.register();
  // the doorbell before the last look: a message or a request (rung) that
  // comes after this read changes the doorbell, so the wait returns at once
  const bell = client.bell();
  serveRequests();
  if (running && record() === 0) client.sleep(bell, due());
  client.unregister();
}
control.close();
