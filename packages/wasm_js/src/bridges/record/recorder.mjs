// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The recording side of `--record` in the Node.js launcher: one subscription
 * per topic with a publisher (or per `--record-topic`), made as soon as the
 * topic shows up in the graph, with the QoS that matches its publishers (as
 * `ros2 bag record` adapts).
 *
 * The subscriptions belong to the recording worker (./recording_process.mjs),
 * which copies every message as the bus delivered it (raw CDR, no decode)
 * into the records of an MCAP chunk; each closed chunk comes here and is
 * written into the bag (./file_sink.mjs), or, when the launcher compresses
 * chunks, goes to it through the pipe. Each new topic is first announced
 * to the launcher (CHANNEL), which answers with the Schema and Channel
 * records to write before it (READY) or says why the topic is not recorded
 * (REFUSED); the launcher learns of every write (WRITTEN, or FAILED) for
 * the bag's summary (colcon_wasm/record/session.py).
 *
 * @module bridges/record/recorder
 */

import { subscriptionQos } from '../../page/graph.mjs';
import { chunkHead, FrameReader, jsonFrame, Kind } from './frames.mjs';
import { FileSink } from './file_sink.mjs';
import { RecordingProcess } from './recording_process.mjs';

/** Bytes waiting for the pipe or the disk beyond which chunks are dropped (and counted). */
const MAX_QUEUED_BYTES = 256 * 1024 * 1024;
/** History of the recorder's subscriptions: bursts between two wake-ups are kept. */
const DEPTH = 1000;
/**
 * A chunk is closed at this size of its records (as the launcher's own
 * chunks): small enough that its CRC and its write read it from the cache
 * (4 MiB chunks cost more CPU here), */
const CHUNK_BYTES = 1024 * 1024;
/** or this long after its first message (a crash loses at most that much). */
const FLUSH_MS = 1000;

/** A regular expression option, searched in topic names; null for none. */
function compile(pattern, option) {
  if (pattern === null || pattern === undefined) return null;
  try {
    return new RegExp(pattern);
  } catch (e) {
    throw new Error(`${option} '${pattern}' is not a regular expression: ${e.message}`);
  }
}

export class Recorder {
  /**
   * @param {object} options
   * @param {import('../../runtime.mjs').Runtime} options.runtime
   * @param {import('node:stream').Writable} options.sink the pipe to the launcher
   * @param {import('node:stream').Readable} options.replies the launcher's answers
   * @param {?{fd: number, offset: number}} options.file the bag, when the worker writes it
   * @param {?string[]} options.topics only these topics (null: all)
   * @param {?string} [options.regex] also (or, without topics, only) the topics this finds
   * @param {?string} [options.exclude] none of the topics this finds
   * @param {function(string, string): void} options.log (level, text)
   * @throws {Error} naming the option whose regular expression is not one
   */
  constructor({ runtime, sink, replies, file, topics, regex = null, exclude = null, log }) {
    this.runtime = runtime;
    this.sink = sink;
    this.replies = replies;
    this.file = file;
    this.topics = topics && topics.length ? new Set(topics) : null;
    this.regex = compile(regex, '--record-regex');
    this.exclude = compile(exclude, '--record-exclude');
    this.log = log;
    this.channels = new Map();
    /** topics whose subscription is in place */
    this.subscribed = new Set();
    this.subscriptions = [];
    /** channel id -> {resolve, reject}: the launcher's answer to a CHANNEL */
    this.answers = new Map();
    this.process = null;
    /** the bag, when this side writes it (no compression) */
    this.bag = null;
    this.dropped = 0;
    this.closed = false;
    this.broken = false;
    sink.on('error', (e) => {
      if (!this.broken) this.log('error', `the recording pipe failed (${e.message}): recording stopped`);
      this.broken = true;
    });
  }

  async start() {
    this._readAnswers();
    if (this.file) {
      this.bag = new FileSink({
        fd: this.file.fd, offset: this.file.offset, maxQueuedBytes: MAX_QUEUED_BYTES,
        onWritten: (reports) => this._send(jsonFrame(Kind.WRITTEN, reports)),
        onFailed: (failure) => {
          this._send(jsonFrame(Kind.FAILED, failure));
          this.process.halt().catch(() => {});
        },
      });
    }
    this.process = await RecordingProcess.start(this.runtime, {
      crc: !!this.file, chunkBytes: CHUNK_BYTES, flushMs: FLUSH_MS,
      onChunks: (chunks) => (this.bag ? this._write(chunks) : chunks.forEach((c) => this._chunk(c))),
    });
    this.node = await this.process.node('rosbag2_recorder');
    this.runtime.onGraphChange(() => this._scan());
    this._scan();
  }

  _readAnswers() {
    const reader = new FrameReader();
    const settle = (id, fn) => {
      const a = this.answers.get(id);
      if (!a) return;
      this.answers.delete(id);
      fn(a);
    };
    this.replies.on('data', (data) => {
      for (const f of reader.push(data)) {
        if (f.kind === Kind.READY) settle(f.channel, (a) => a.resolve(f.records));
        else if (f.kind === Kind.REFUSED) settle(f.json.id, (a) => a.reject(Object.assign(new Error(f.json.reason), { refused: true })));
      }
    });
    const gone = () => {
      for (const a of this.answers.values()) a.reject(new Error('the launcher stopped answering'));
      this.answers.clear();
    };
    this.replies.on('end', gone);
    this.replies.on('error', gone);
  }

  _scan() {
    if (this.closed) return;
    for (const t of this.runtime.graph().topics) {
      if (t.domain !== 0 || this.channels.has(t.name) || t.publishers.length === 0) continue;
      if (!this.wants(t.name)) continue;
      const type = t.types[0];
      if (t.types.length > 1) this.log('warning', `topic '${t.name}' has several types (${t.types.join(', ')}): recording ${type}`);
      const id = this.channels.size + 1;
      const offered = t.publishers.map((e) => e.qos).filter(Boolean);
      this.channels.set(t.name, id);
      const answered = new Promise((resolve, reject) => this.answers.set(id, { resolve, reject }));
      this._send(jsonFrame(Kind.CHANNEL, { id, topic: t.name, type, qos: offered }));
      const qos = subscriptionQos(offered, DEPTH);
      this.subscriptions.push(answered
        .then((records) => {
          // the channel's records reach the bag before any chunk with its messages
          if (this.bag) this.bag.writeRecords(records);
          return this.process.add({ node: this.node, topic: t.name, type, qos, channel: id });
        })
        .then((ep) => {
          this.subscribed.add(t.name);
          return ep;
        })
        .catch((e) => {
          // a refusal was said by the launcher, with its reason
          if (!e.refused && !this.closed) this.log('error', `cannot record '${t.name}': ${e.message}`);
          return null;
        }));
    }
  }

  /**
   * Does this recorder record this topic (once it has a publisher)? As ros2 bag record:
   * the listed topics and those the regex finds (every topic without either), less those
   * the exclude regex finds.
   */
  wants(topic) {
    const chosen = (!this.topics && !this.regex) || (this.topics && this.topics.has(topic))
      || (this.regex && this.regex.test(topic));
    return Boolean(chosen) && !(this.exclude && this.exclude.test(topic));
  }

  /** Write a batch of chunks of the recording worker into the bag; past the bound they are dropped and counted. */
  _write(chunks) {
    const written = this.bag.writeChunks(chunks);
    if (!written && !this.bag.failed) for (const c of chunks) this.dropped += c.messages;
  }

  /** Write frames to the pipe (nothing once it broke). */
  _send(frame) {
    if (!this.broken) this.sink.write(frame);
  }

  /**
   * Write a chunk of the recording worker to the pipe in one go (its head,
   * the records, the message indexes; nothing copied); past the bound it is
   * dropped and its messages counted. Its buffer is freed once written.
   */
  _chunk(chunk) {
    const { records, indexes } = chunk;
    if (this.broken || this.sink.writableLength > MAX_QUEUED_BYTES) {
      if (!this.broken) this.dropped += chunk.messages;
      chunk.release();
      return;
    }
    this.sink.cork();
    this.sink.write(chunkHead({ ...chunk, length: records.length }, records.length + indexes.length));
    this.sink.write(records);
    this.sink.write(indexes, () => chunk.release());
    process.nextTick(() => this.sink.uncork());
  }

  /** Stop recording: what is waiting on the bus goes into the last chunk, then the pipe ends. */
  close() {
    // a second call waits for the first: the host must not end before the bag is written
    if (!this._closing) this._closing = this._close();
    return this._closing;
  }

  async _close() {
    this.closed = true;
    // the subscriptions in the making first; the worker's last reports come
    // before its answer to stop
    await Promise.all(this.subscriptions);
    const { lost } = this.process ? await this.process.stop() : { lost: 0 };
    if (this.bag) await this.bag.drained();
    if (this.dropped) {
      this.log('warning', `${this.dropped} messages were dropped: ${this.bag ? 'the disk' : 'the launcher'} did not keep up with writing them`);
    }
    if (lost) {
      this.log('warning', `${lost} messages were lost before the recorder took them: their publishers' history (QoS depth) was overwritten first; a deeper history keeps them`);
    }
    if (this.dropped || lost) this._send(jsonFrame(Kind.NOTE, { dropped: this.dropped, lost }));
    this.replies.destroy();
    if (this.broken) return;
    await new Promise((resolve) => this.sink.end(resolve));
  }
}
