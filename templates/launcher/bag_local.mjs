// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Bags in a page with no colcon-wasm serve behind it (an export,
// `workspace.bag.local`): the page reads a dropped MCAP file and plays it
// itself (LocalBagSource, the source of bag.mjs' PagePlayer), and records
// into an MCAP file it builds in memory and offers as a download
// (LocalRecorder, with the subscriptions of bag.mjs' GraphRecorder). Under
// serve the page keeps serve's `/bag` (bag.mjs), which has zstd, lz4 and the
// disk.

import { readMcap } from '../wasm_js/page/mcap_reader.mjs';
import { McapWriter, MAX_BYTES } from '../wasm_js/page/mcap_writer.mjs';
import { PacedPlayer } from '../wasm_js/page/paced_player.mjs';
import { playerQos, toRosbag2 } from '../wasm_js/page/rosbag2_qos.mjs';
import { Ros2MsgSchemas } from '../wasm_js/page/ros2msg.mjs';
import { GraphRecorder } from './bag.mjs';

/** The largest bag the page reads: it holds the whole file in memory. */
export const MAX_PLAY_BYTES = 1024 * 1024 * 1024;

const MIB = 1024 * 1024;
const encoder = new TextEncoder();

/**
 * Why a channel of a bag cannot be played into this page, or null (the
 * rules of serve's `unplayable`, colcon_wasm/record/bag_reader.py).
 * @param {{messageEncoding: string}} channel
 * @param {?{name: string}} schema
 * @param {Ros2MsgSchemas} schemas the page's type descriptions
 */
export function unplayable(channel, schema, schemas) {
  if (channel.messageEncoding !== 'cdr') return `its messages are encoded as '${channel.messageEncoding}', not cdr`;
  if (!schema || !schema.name) return 'it has no schema';
  try {
    schemas.fullText(schema.name);
  } catch {
    return `the workspace does not know its type '${schema.name}': build its interface package with 'colcon build --wasm'`;
  }
  return null;
}

/**
 * Describe a bag read in the page as serve describes an upload, and list
 * the messages to play: `{info: {name, count, duration_ms, topics: [{id,
 * topic, type, qos}], skipped: [{topic, why}], error}, messages}`.
 * @param {import('../wasm_js/page/mcap_reader.mjs').McapContent} content
 * @param {string} name
 * @param {Ros2MsgSchemas} schemas
 */
export function describeBag(content, name, schemas) {
  const topics = [];
  const skipped = [];
  const ids = new Map(); // channel id -> played id (one per topic name)
  const byTopic = new Map();
  for (const channel of content.channels.values()) {
    if (byTopic.has(channel.topic)) {
      if (byTopic.get(channel.topic) !== null) ids.set(channel.id, byTopic.get(channel.topic));
      continue;
    }
    const schema = content.schemas.get(channel.schemaId) || null;
    const why = unplayable(channel, schema, schemas);
    if (why) {
      skipped.push({ topic: channel.topic, why });
      byTopic.set(channel.topic, null);
      continue;
    }
    const id = topics.length + 1;
    topics.push({ id, topic: channel.topic, type: schemas.resolve(schema.name), qos: playerQos(channel.metadata.offered_qos_profiles || '') });
    byTopic.set(channel.topic, id);
    ids.set(channel.id, id);
  }
  const messages = [];
  for (const m of content.messages) {
    const id = ids.get(m.channelId);
    if (id !== undefined) messages.push({ channel: id, logTime: m.logTime, data: m.data });
  }
  const count = messages.length;
  const duration = count ? Number(messages[count - 1].logTime - messages[0].logTime) / 1e6 : 0;
  return { info: { name, count, duration_ms: duration, topics, skipped, error: content.error }, messages };
}

/**
 * A bag read and played by the page: the source of a PagePlayer in a page
 * without serve. Only uncompressed chunks are read (./mcap_reader.mjs):
 * a compressed bag is refused as a whole, with what to do.
 */
export class LocalBagSource {
  /**
   * @param {object} session the page's Session (its type descriptions)
   * @param {object} hooks {onState(state), onError(text), onMessage(id, data), onClock(ns)}
   */
  constructor(session, hooks) {
    this.session = session;
    this.hooks = hooks;
    this.player = null;
  }

  /** Read the bag; resolves to its description (as serve's `bag` answer). */
  async open(file) {
    const name = file.name || 'bag.mcap';
    if (file.size > MAX_PLAY_BYTES) {
      throw new Error(`'${name}' is ${Math.round(file.size / MIB)} MiB: a page without serve reads a bag into `
        + `memory, up to ${MAX_PLAY_BYTES / MIB} MiB; play it under 'colcon-wasm serve', which reads it as it plays`);
    }
    if (file.size === 0) throw new Error(`'${name}' is empty`);
    await this.session.ready;
    const content = readMcap(new Uint8Array(await file.arrayBuffer()), { name });
    const { info, messages } = describeBag(content, name, Ros2MsgSchemas.fromDocuments(this.session.typeDocuments || []));
    this.player = new PacedPlayer(messages, {
      send: (id, positionMs, data) => this.hooks.onMessage(id, data),
      report: (state) => this.hooks.onState(state),
      tick: (ns) => this.hooks.onClock(ns),
      error: info.error,
    });
    return info;
  }

  // the controls, carried out by the page's paced player (../wasm_js/page/paced_player.mjs)
  /** Play from where it stands (from the start once it ended). */
  play() { this.player?.play(); }
  /** Stop sending; the position stays. */
  pause() { this.player?.pause(); }
  /** Pause, and send the next message at once. */
  step() { this.player?.step(); }
  /** Go to `positionMs` from the first message. */
  seek(positionMs) { this.player?.seek(positionMs); }
  /** Play `rate` times as fast as recorded. */
  setRate(rate) { this.player?.setRate(rate); }
  /** Tick /clock with the bag time `hz` times a second while playing (0: none). */
  setClock(hz) { this.player?.setClock(hz); }

  /** Stop playing (the bag's bytes are let go). */
  close() {
    this.player?.close();
    this.player = null;
  }
}

/**
 * Records this page's bus into an MCAP file built in the page: rosbag2's
 * layout as serve's recorder writes it (profile `ros2`, a `ros2msg` schema
 * per type with its complete definition, a `cdr` channel per topic with
 * its publishers' `offered_qos_profiles`), uncompressed chunks, and a
 * summary. The file is at most `maxBytes`: past that, messages are dropped
 * and counted. Stop gives it as a Blob URL (kept until the next recording).
 */
export class LocalRecorder extends GraphRecorder {
  /** @param {object} [options] {maxBytes = MAX_BYTES} */
  constructor(session, { maxBytes = MAX_BYTES } = {}) {
    super(session);
    this.maxBytes = maxBytes;
    this.writer = null;
    this.url = null;
    this.name = null;
  }

  get recording() { return this.writer !== null; }

  /** Start recording every topic with a publisher (and each one that appears). */
  async start({ name = 'launcher.mcap' } = {}) {
    if (this.writer) throw new Error('already recording');
    await this.session.ready;
    if (this.url) URL.revokeObjectURL(this.url);
    this.url = null;
    this.name = name;
    this.schemas = Ros2MsgSchemas.fromDocuments(this.session.typeDocuments || []);
    this.schemaIds = new Map();
    this.skipped = {};
    this.warnings = [];
    this.writer = new McapWriter({ library: 'colcon-wasm page', maxBytes: this.maxBytes });
    this.messages = 0;
    this.dropped = 0;
    this._follow();
  }

  _channel(t, type) {
    let schemaId = this.schemaIds.get(type);
    if (schemaId === undefined) {
      let text;
      try {
        text = this.schemas.fullText(type);
      } catch (e) {
        this.skipped[t.name] = e.message;
        this.warnings.push(`not recording ${t.name}: ${e.message}`);
        return null;
      }
      schemaId = this.writer.addSchema(type, 'ros2msg', encoder.encode(text));
      this.schemaIds.set(type, schemaId);
    }
    return this.writer.addChannel(t.name, 'cdr', schemaId, { offered_qos_profiles: toRosbag2(t.publisherQos) });
  }

  _write(id, batch) {
    if (!this.writer) return;
    this.messages += this.writer.write(id, batch);
    this.dropped = this.writer.dropped;
  }

  /**
   * Stop: resolves to {url, name, messages, bytes, skipped, error, dropped,
   * droppedWhy, warnings}, `url` a Blob URL of the file.
   */
  async stop() {
    if (!this.writer) throw new Error('not recording');
    await this._unfollow();
    const writer = this.writer;
    this.writer = null;
    const blob = new Blob(writer.finish(), { type: 'application/octet-stream' });
    this.url = URL.createObjectURL(blob);
    return {
      url: this.url, name: this.name, messages: this.messages, bytes: blob.size, skipped: this.skipped,
      error: null, dropped: this.dropped, warnings: this.warnings.slice(),
      droppedWhy: `the recording reached the page's ${this.maxBytes / MIB} MiB`,
    };
  }
}

