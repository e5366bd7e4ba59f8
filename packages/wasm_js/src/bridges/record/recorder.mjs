// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The recording side of `--record` in the Node.js launcher: one tools subscription
 * per topic with a publisher (or per `--record-topic`), subscribed as soon
 * as the topic shows up in the graph, with the QoS that matches its
 * publishers (as `ros2 bag record` adapts). The tools worker copies every
 * message, as the bus delivered it (raw CDR, no decode), into the records of
 * an MCAP chunk (tools_process/chunk_recording.mjs); each closed chunk goes
 * to the launcher's pipe (./frames.mjs) in one write, and the launcher puts
 * it into the MCAP file.
 *
 * @module bridges/record/recorder
 */

import { subscriptionQos } from '../../page/graph.mjs';
import { chunkHead, jsonFrame, Kind } from './frames.mjs';

/** Bytes waiting for the pipe beyond which messages are dropped (and counted). */
const MAX_QUEUED_BYTES = 256 * 1024 * 1024;
/** History of the recorder's subscriptions: bursts between two wake-ups are kept. */
const DEPTH = 1000;
/** A chunk is closed at this size of its records (as the launcher's own chunks), */
const CHUNK_BYTES = 1024 * 1024;
/** or this long after its first message (a crash loses at most that much). */
const FLUSH_MS = 1000;

export class Recorder {
  /**
   * @param {object} options
   * @param {import('../../runtime.mjs').Runtime} options.runtime
   * @param {import('../../tools_process/main_thread.mjs').Tools} options.tools
   * @param {import('node:stream').Writable} options.sink the pipe to the launcher
   * @param {?string[]} options.topics only these topics (null: all)
   * @param {function(string, string): void} options.log (level, text)
   */
  constructor({ runtime, tools, sink, topics, log }) {
    this.runtime = runtime;
    this.tools = tools;
    this.sink = sink;
    this.topics = topics && topics.length ? new Set(topics) : null;
    this.log = log;
    this.channels = new Map();
    /** topics whose subscription is in place */
    this.subscribed = new Set();
    this.subscriptions = [];
    this.recording = null;
    this.dropped = 0;
    this.closed = false;
    this.broken = false;
    sink.on('error', (e) => {
      if (!this.broken) this.log('error', `the recording pipe failed (${e.message}): recording stopped`);
      this.broken = true;
    });
  }

  async start() {
    this.node = await this.tools.createNode('rosbag2_recorder', { namespace: '/' });
    this.recording = await this.tools.startRecording({ chunkBytes: CHUNK_BYTES, flushMs: FLUSH_MS },
      (chunk) => this._chunk(chunk));
    this.runtime.onGraphChange(() => this._scan());
    this._scan();
  }

  _scan() {
    if (this.closed) return;
    for (const t of this.runtime.graph().topics) {
      if (t.domain !== 0 || this.channels.has(t.name) || t.publishers.length === 0) continue;
      if (this.topics && !this.topics.has(t.name)) continue;
      const type = t.types[0];
      if (t.types.length > 1) this.log('warning', `topic '${t.name}' has several types (${t.types.join(', ')}): recording ${type}`);
      const id = this.channels.size + 1;
      const offered = t.publishers.map((e) => e.qos).filter(Boolean);
      this.channels.set(t.name, id);
      this._send(jsonFrame(Kind.CHANNEL, { id, topic: t.name, type, qos: offered }));
      const qos = subscriptionQos(offered, DEPTH);
      this.subscriptions.push(this.recording.add({ topic: t.name, type, qos, node: this.node }, id).then((ep) => {
        this.subscribed.add(t.name);
        return ep;
      }).catch((e) => {
        this.log('error', `cannot record '${t.name}': ${e.message}`);
        return null;
      }));
    }
  }

  /** Does this recorder record this topic (once it has a publisher)? */
  wants(topic) {
    return !this.topics || this.topics.has(topic);
  }

  /** Write frames to the pipe; `messages` > 0: they are messages, dropped (and counted) past the bound. */
  _send(frame, messages = 0) {
    if (this.broken) return;
    if (messages && this.sink.writableLength > MAX_QUEUED_BYTES) {
      this.dropped += messages;
      return;
    }
    this.sink.write(frame);
  }

  /**
   * Write a chunk of the tools worker to the pipe in one go (its head, the
   * records, the message indexes; nothing copied); past the bound it is
   * dropped and its messages counted. Its buffer goes back to the worker once written.
   */
  _chunk(chunk) {
    const records = new Uint8Array(chunk.records, 0, chunk.length);
    const indexes = new Uint8Array(chunk.indexes);
    if (this.broken || this.sink.writableLength > MAX_QUEUED_BYTES) {
      if (!this.broken) this.dropped += chunk.messages;
      this.recording.recycle(chunk.records);
      return;
    }
    this.sink.cork();
    this.sink.write(chunkHead(chunk, records.length + indexes.length));
    this.sink.write(records);
    this.sink.write(indexes, () => this.recording.recycle(chunk.records));
    process.nextTick(() => this.sink.uncork());
  }

  /** Stop recording: unsubscribe, let what is queued reach the launcher, end the pipe. */
  async close() {
    if (this.closed) return;
    this.closed = true;
    // the subscriptions in the making first, then what is waiting on the bus goes into
    // the last chunk, which reaches this side before close() returns
    await Promise.all(this.subscriptions);
    if (this.recording) await this.recording.close().catch((e) => this.log('error', `closing the recording: ${e.message}`));
    if (this.dropped) {
      this.log('warning', `${this.dropped} messages were dropped: the launcher did not keep up with writing them`);
      this._send(jsonFrame(Kind.NOTE, { dropped: this.dropped }));
    }
    if (this.broken) return;
    await new Promise((resolve) => this.sink.end(resolve));
  }
}
