// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * Drive the recording worker's chunk builder (bridges/record/chunk_builder.mjs)
 * on a real bus, for tests/test_chunk_builder.py:
 *
 *   node chunk_builder_check.mjs WASM_JS_SRC_DIR pipe OUT_FILE
 *   node chunk_builder_check.mjs WASM_JS_SRC_DIR file FD OFFSET RECORDS_FILE
 *
 * A publisher process sends, on two topics, small messages and frames of
 * about 900 KiB (byte j of frame r is (7 j + 13 r) mod 256, its length
 * 900 KiB + r); a recorder process records both into chunks of 1 MiB.
 * `pipe`: every closed chunk, in a buffer of its own, is written to OUT_FILE
 * as the recorder's pipe frames carry it (bridges/record/frames.mjs).
 * `file`: chunks are built in the slots of a 4-slot pool as in the
 * recording worker (the later ones, with every slot waiting for the disk,
 * in buffers of their own); the bag's descriptor FD (inherited, the
 * launcher's BagWriter wrote its header up to OFFSET) gets the launcher's
 * Schema/Channel records (RECORDS_FILE) and then every chunk through
 * bridges/record/file_sink.mjs, as the host writes it.
 * A JSON line on stdout lists what was published (topic channel, length,
 * first byte), the messages per chunk, in file mode the write reports and
 * how many chunks were built in pool slots.
 */

import { readFileSync, writeFileSync } from 'node:fs';
import zlib from 'node:zlib';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

const [srcDir, mode, ...rest] = process.argv.slice(2);
const src = (file) => pathToFileURL(path.join(path.resolve(srcDir), file)).href;
const { Bus, KIND_PUBLISHER, KIND_SUBSCRIPTION } = await import(src('bus.mjs'));
const { BusClient } = await import(src('bus_client.mjs'));
const { PROC_KIND_NODE, PROC_KIND_RUNTIME } = await import(src('layout.mjs'));
const { ChunkBuilder } = await import(src('bridges/record/chunk_builder.mjs'));
const { ChunkPool } = await import(src('bridges/record/chunk_pool.mjs'));
const { FileSink } = await import(src('bridges/record/file_sink.mjs'));
const { chunkHead } = await import(src('bridges/record/frames.mjs'));

const bus = Bus.create({ initialBytes: 8 << 20, maxBytes: 256 << 20, maxMessageBytes: 16 << 20 });
bus.tryLock(1);
bus.allocProcess(PROC_KIND_RUNTIME);
const [pubPid, recPid] = [bus.allocProcess(PROC_KIND_NODE), bus.allocProcess(PROC_KIND_NODE)];
bus.unlock(1);
const publisher = new BusClient(Bus.attach(bus.sab), pubPid);
const recorder = new BusClient(Bus.attach(bus.sab), recPid);
const endpoint = (c, kind, node, name) => c.createEndpoint({
  kind, node, name, type: 'test_msgs/msg/Bytes', qos: { history: 'keep_all' },
}).index;

const frames = [];
const chunks = [];
const reports = [];
let sink = null;
let pool = null;
let inSlots = 0;
if (mode === 'file') {
  pool = ChunkPool.create(4, 1 << 20);
  const [fd, offset, recordsFile] = rest;
  sink = new FileSink({
    fd: Number(fd), offset: Number(offset), maxQueuedBytes: 1 << 30,
    onWritten: (r) => reports.push(r),
    onFailed: (f) => { throw new Error(`the bag failed: ${f.message}`); },
  });
  sink.writeRecords(new Uint8Array(readFileSync(recordsFile)));
}
/** file mode: chunks go to the sink two at a time, as the recording worker batches them */
let batch = [];
const writeBatch = () => {
  if (batch.length) sink.writeChunks(batch);
  batch = [];
};
const recording = new ChunkBuilder(recorder, {
  chunkBytes: 1 << 20, flushMs: 60000, pool,
  sink: (chunk) => {
    chunks.push(chunk.messages);
    if (sink) {
      // as the recording worker posts it: the slot is freed once written
      if (chunk.slot >= 0) inSlots++;
      const release = () => { if (chunk.slot >= 0) pool.release(chunk.slot); };
      batch.push({ ...chunk, crc: zlib.crc32(chunk.records), release });
      if (batch.length === 2) writeBatch();
      return true;
    }
    frames.push(chunkHead({ ...chunk, length: chunk.records.length }, chunk.records.length + chunk.indexes.length),
      chunk.records.slice(), chunk.indexes);
    return true;
  },
});
const recNode = recorder.createNode({ name: 'rosbag2_recorder' }).index;
recording.add(endpoint(recorder, KIND_SUBSCRIPTION, recNode, '/small'), 1);
recording.add(endpoint(recorder, KIND_SUBSCRIPTION, recNode, '/frames'), 2);
const pubNode = publisher.createNode({ name: 'source' }).index;
const small = endpoint(publisher, KIND_PUBLISHER, pubNode, '/small');
const big = endpoint(publisher, KIND_PUBLISHER, pubNode, '/frames');

const published = [];
for (let round = 0; round < 6; round++) {
  for (let i = 0; i < 40; i++) {
    const n = 24 + ((round * 40 + i) % 50);
    const data = new Uint8Array(n).fill((round * 40 + i) & 255);
    publisher.publish(small, data);
    published.push([1, n, data[0]]);
  }
  const frame = new Uint8Array(900 * 1024 + round);
  for (let j = 0; j < frame.length; j++) frame[j] = (7 * j + 13 * round) & 255;
  publisher.publish(big, frame);
  published.push([2, frame.length, frame[0]]);
  // the recorder wakes up now and then, as the tools worker does
  if (round % 2 === 1) recording.drain();
}
recording.drain();
recording.flush();
if (sink) {
  writeBatch();
  await sink.drained();
}
if (mode === 'pipe') {
  let size = 0;
  for (const f of frames) size += f.length;
  const out = new Uint8Array(size);
  let at = 0;
  for (const f of frames) {
    out.set(f, at);
    at += f.length;
  }
  writeFileSync(rest[0], out);
}
console.log(JSON.stringify({ published, chunks, reports, inSlots }));
