// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * Drive the tools worker's chunk builder (tools_process/chunk_recording.mjs)
 * on a real bus, for tests/test_chunk_recording.py:
 *
 *   node chunk_recording_check.mjs WASM_JS_SRC_DIR OUT_FILE
 *
 * A publisher process sends, on two topics, small messages and frames of
 * 900 KiB; a recorder process records both into chunks of 1 MiB. Every
 * closed chunk is written to OUT_FILE as the recorder's pipe frames carry
 * it (bridges/record/frames.mjs), and a JSON line on stdout lists what was
 * published (topic channel, length, first byte, bus time) for the test to
 * compare with what the MCAP readers find.
 */

import { writeFileSync } from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

const [srcDir, outFile] = process.argv.slice(2);
const src = (file) => pathToFileURL(path.join(path.resolve(srcDir), file)).href;
const { Bus, KIND_PUBLISHER, KIND_SUBSCRIPTION } = await import(src('bus.mjs'));
const { BusClient } = await import(src('bus_client.mjs'));
const { PROC_KIND_NODE, PROC_KIND_RUNTIME } = await import(src('layout.mjs'));
const { ChunkRecording } = await import(src('tools_process/chunk_recording.mjs'));
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
const recording = new ChunkRecording(recorder, {
  id: 1, chunkBytes: 1 << 20, flushMs: 60000,
  post: (chunk) => {
    chunks.push(chunk.messages);
    const records = new Uint8Array(chunk.records, 0, chunk.length);
    const indexes = new Uint8Array(chunk.indexes);
    frames.push(chunkHead(chunk, records.length + indexes.length), records.slice(), indexes);
    recording.recycle(chunk.records);
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
  const frame = new Uint8Array(900 * 1024);
  for (let j = 0; j < frame.length; j += 997) frame[j] = (j + round) & 255;
  frame[0] = round;
  publisher.publish(big, frame);
  published.push([2, frame.length, round]);
  // the recorder wakes up now and then, as the tools worker does
  if (round % 2 === 1) recording.drain();
}
recording.drain();
recording.flush();
let size = 0;
for (const f of frames) size += f.length;
const out = new Uint8Array(size);
let at = 0;
for (const f of frames) {
  out.set(f, at);
  at += f.length;
}
writeFileSync(outFile, out);
console.log(JSON.stringify({ published, chunks }));
