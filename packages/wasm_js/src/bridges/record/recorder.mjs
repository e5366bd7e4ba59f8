// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The recording side of `--record` in the Node.js launcher: one tools subscription
 * per topic with a publisher (or per `--record-topic`), subscribed as soon
 * as the topic shows up in the graph, with the QoS that matches its
 * publishers (as `ros2 bag record` adapts). Every message goes, as the
 * bus delivered it (raw CDR, no decode), to the launcher's pipe
 * (./frames.mjs); the launcher writes the MCAP file.
 *
 * @module bridges/record/recorder
 */

import { subscriptionQos } from '../../page/graph.mjs';
import { jsonFrame, Kind, messageHead } from './frames.mjs';

/** Bytes waiting for the pipe beyond which messages are dropped (and counted). */
const MAX_QUEUED_BYTES = 256 * 1024 * 1024;
/** History of the recorder's subscriptions: bursts between two wake-ups are kept. */
const DEPTH = 1000;

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
    this.dropped = 0;
    this.lastBatch = 0;
    this.closed = false;
    this.broken = false;
    sink.on('error', (e) => {
      if (!this.broken) this.log('error', `the recording pipe failed (${e.message}): recording stopped`);
      this.broken = true;
    });
  }

  async start() {
    this.node = await this.tools.createNode('rosbag2_recorder', { namespace: '/' });
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
      this.subscriptions.push(this.tools.subscribe({ topic: t.name, type, qos, node: this.node }, (batch) => {
        this.lastBatch = Date.now();
        // one write per batch (a write to the pipe is a system call on libuv's thread pool),
        // large payloads not copied: the head and the bytes go out in one writev
        const parts = [];
        for (const m of batch) parts.push(messageHead(id, m.info.receivedTime, m.info.sourceTime, m.data.length), m.data);
        this._sendParts(parts, batch.length);
      }).then((s) => { this.subscribed.add(t.name); return s; }).catch((e) => {
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

  /** Write message frames (heads and payloads) in one go; past the bound they are dropped. */
  _sendParts(parts, messages) {
    if (this.broken) return;
    if (this.sink.writableLength > MAX_QUEUED_BYTES) {
      this.dropped += messages;
      return;
    }
    this.sink.cork();
    for (const p of parts) this.sink.write(p);
    process.nextTick(() => this.sink.uncork());
  }

  /** Stop recording: unsubscribe, let what is queued reach the launcher, end the pipe. */
  async close() {
    if (this.closed) return;
    this.closed = true;
    // what is on its way from the tools worker is recorded too: wait for a quiet 100 ms (3 s at most)
    const until = Date.now() + 3000;
    while (this.lastBatch && Date.now() - this.lastBatch < 100 && Date.now() < until) {
      await new Promise((resolve) => setTimeout(resolve, 20));
    }
    const subscriptions = await Promise.all(this.subscriptions);
    await Promise.all(subscriptions.filter(Boolean).map((s) => s.close().catch(() => {})));
    if (this.dropped) {
      this.log('warning', `${this.dropped} messages were dropped: the launcher did not keep up with writing them`);
      this._send(jsonFrame(Kind.NOTE, { dropped: this.dropped }));
    }
    if (this.broken) return;
    await new Promise((resolve) => this.sink.end(resolve));
  }
}
