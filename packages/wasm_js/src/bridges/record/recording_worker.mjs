// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The recording worker of `--record` (Node.js): a bus process of its own
 * whose thread does nothing but record. It blocks in `Atomics.wait` on its
 * doorbell like a C++ node (no event loop turn, promise or timer per
 * wake-up), copies what its subscriptions received into MCAP chunks
 * (./chunk_builder.mjs) and writes each closed chunk to the bag itself
 * (./file_sink.mjs), or posts it to the main thread when the launcher
 * compresses chunks.
 *
 * After a wake-up it naps `coalesceMs` before the next wait, so a 1 kHz
 * topic wakes it a few hundred times a second rather than a thousand; the
 * writers' histories hold what arrives meanwhile.
 *
 * Control comes through a MessagePort read synchronously between waits
 * (`receiveMessageOnPort`, about 20 µs a call: only when a shared counter
 * says a request was posted); whoever posts counts it and rings this
 * process' doorbell.
 * Each request is answered on `parentPort` ({type: 'reply', id, value} or
 * {error}); write reports are {type: 'written', ...}, pipe-mode chunks
 * {type: 'chunk', ...} and a failed write {type: 'failed', code, message,
 * kept}, after which nothing more is recorded.
 *
 * @module bridges/record/recording_worker
 */

import { parentPort, receiveMessageOnPort, workerData } from 'node:worker_threads';
import { BusClient, EventType, KIND_SUBSCRIPTION } from '../../bus_client.mjs';
import { ChunkBuilder } from './chunk_builder.mjs';
import { BagWriteError, FileSink } from './file_sink.mjs';

const { handle, pid, control, requests, fd, offset, chunkBytes, flushMs, coalesceMs } = workerData;
/** requests[0] counts the requests posted: the port is read only when it moved */
const posted = new Int32Array(requests);
let served = 0;
const client = BusClient.attach(handle, pid);
const nap = new Int32Array(new SharedArrayBuffer(4));
const post = (m, transfer) => parentPort.postMessage(m, transfer || []);

const sink = fd === null ? null : new FileSink({
  fd, offset, onWritten: (report) => post({ type: 'written', ...report }),
});
const builder = new ChunkBuilder(client, {
  chunkBytes, flushMs,
  sink: sink ? (chunk) => sink.chunk(chunk) : postChunk,
});
/** subscription endpoints of the recording */
const endpoints = new Set();
let failed = null;
let running = true;

/** Pipe mode: the chunk's buffers go to the main thread (transferred), the records one comes back. */
function postChunk(chunk) {
  const records = chunk.records.buffer;
  post({
    type: 'chunk', records, length: chunk.records.length, indexes: chunk.indexes.buffer,
    channels: chunk.channels, start: chunk.start, end: chunk.end, messages: chunk.messages,
  }, [records, chunk.indexes.buffer]);
  return false;
}

/** Stop recording for good after a failed write: say why once, let go of the subscriptions. */
function fail(e) {
  if (!(e instanceof BagWriteError)) throw e;
  failed = e;
  post({ type: 'failed', code: e.code, message: e.message, kept: e.kept });
  for (const ep of endpoints) client.destroyEndpoint(ep);
  endpoints.clear();
  builder.channels.clear();
}

/** Copy what came; close the chunk when its time is up. */
function record() {
  if (failed) return;
  try {
    builder.drain();
    if (builder.flushDue()) builder.flush();
  } catch (e) {
    fail(e);
  }
}

const operations = {
  node({ name, namespace }) {
    return client.createNode({ name, namespace, context: client.createContext() }).index;
  },
  /** Write the topic's Schema/Channel records (file mode), then subscribe. */
  add({ node, topic, type, qos, channel, records }) {
    if (failed) throw new Error(`recording stopped: ${failed.message}`);
    if (sink && records) {
      try {
        sink.writeRecords(new Uint8Array(records));
      } catch (e) {
        fail(e);
        throw new Error(`recording stopped: ${e.message}`);
      }
    }
    const ep = client.createEndpoint({ kind: KIND_SUBSCRIPTION, node, name: topic, type, qos }).index;
    endpoints.add(ep);
    builder.add(ep, channel);
    record(); // a TRANSIENT_LOCAL writer's history is there at once
    return ep;
  },
  recycle({ buffer }) {
    builder.recycle(buffer);
  },
  /**
   * Record what is waiting, close the last chunk, unsubscribe, end the loop.
   * @returns {{lost: number}} the messages the publishers' histories dropped
   *   before this worker took them (the bus counts them per subscription)
   */
  stop() {
    record();
    if (!failed) {
      try {
        builder.flush();
      } catch (e) {
        fail(e);
      }
    }
    let lost = 0;
    for (const ep of endpoints) {
      lost += client.eventStatus(ep, EventType.MESSAGE_LOST, false).total;
      client.destroyEndpoint(ep);
    }
    endpoints.clear();
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
