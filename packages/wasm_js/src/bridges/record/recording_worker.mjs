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
 * After a wake-up it naps `coalesceMs` before the next wait, so a 1 kHz
 * topic wakes it a few hundred times a second rather than a thousand; the
 * writers' histories hold what arrives meanwhile.
 *
 * Control comes through a MessagePort read synchronously between waits
 * (`receiveMessageOnPort`, about 20 µs a call: only when a shared counter
 * says a request was posted); whoever posts counts it and rings this
 * process' doorbell. Each request is
 * answered on `parentPort` ({type: 'reply', id, value} or {error}); chunks
 * are {type: 'chunk', ...}.
 *
 * @module bridges/record/recording_worker
 */

import { parentPort, receiveMessageOnPort, workerData } from 'node:worker_threads';
import { BusClient, EventType, KIND_SUBSCRIPTION } from '../../bus_client.mjs';
import zlib from 'node:zlib';
import { ChunkBuilder } from './chunk_builder.mjs';
import { ChunkPool } from './chunk_pool.mjs';

const { handle, pid, control, requests, pool, crc, chunkBytes, flushMs, coalesceMs } = workerData;
/** requests[0] counts the requests posted: the port is read only when it moved */
const posted = new Int32Array(requests);
let served = 0;
const client = BusClient.attach(handle, pid);
const nap = new Int32Array(new SharedArrayBuffer(4));
const post = (m, transfer) => parentPort.postMessage(m, transfer || []);

/** Node.js 20.15 and later: the C CRC-32 of zlib; else the chunks go without one (CRC 0, allowed). */
const crc32 = crc && typeof zlib.crc32 === 'function' ? zlib.crc32 : null;
const builder = new ChunkBuilder(client, {
  chunkBytes, flushMs, sink: postChunk, pool: new ChunkPool(pool.sab, pool.slots, pool.slotBytes),
});
/** subscription endpoints of the recording */
const endpoints = new Set();
let halted = false;
let running = true;

/** Post a closed chunk: its pool slot (or its own buffer, transferred), its indexes. */
function postChunk(chunk) {
  const own = chunk.slot < 0 ? chunk.records.buffer : null;
  const transfer = own ? [own, chunk.indexes.buffer] : [chunk.indexes.buffer];
  post({
    type: 'chunk', slot: chunk.slot, records: own, length: chunk.records.length,
    indexes: chunk.indexes.buffer, crc: crc32 ? crc32(chunk.records) : 0,
    channels: chunk.channels, start: chunk.start, end: chunk.end, messages: chunk.messages,
  }, transfer);
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

/** Copy what came; close the chunk when its time is up. */
function record() {
  builder.drain();
  if (builder.flushDue()) builder.flush();
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

while (running) {
  client.register();
  // the doorbell before the port: a request posted (and rung) after this read
  // changes the doorbell, so the wait below returns at once
  const bell = client.bell();
  const count = Atomics.load(posted, 0);
  if (count !== served) {
    served = count;
    for (let m; running && (m = receiveMessageOnPort(control));) serve(m.message);
  }
  if (!running) {
    client.unregister();
    break;
  }
  record();
  const due = builder.deadline === Infinity ? Infinity : Math.max(0, builder.deadline - performance.now());
  client.sleep(bell, due);
  client.unregister();
  if (coalesceMs > 0) Atomics.wait(nap, 0, 0, coalesceMs);
}
control.close();
