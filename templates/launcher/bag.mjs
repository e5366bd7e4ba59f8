// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The page's record and replay of rosbag2 MCAP bags, with the /bag WebSocket
// of `colcon-wasm serve` (colcon_wasm/server/bag_socket.py, which has the
// MCAP library): the recorder streams every topic of this page's bus there
// as CDR, as it goes, and offers the file for download; the player uploads
// a bag and publishes what serve sends back in its recorded timing, with
// pause, step, seek and rate. A page with no serve behind it (an export)
// reads and writes the bag itself (bag_local.mjs): the same player and
// the same subscriptions, with another source of messages and another sink.

// /clock as the Node.js player publishes it (one definition in the runtime)
import { CLOCK_QOS, clockMessage } from '../wasm_js/bridges/record/clock.mjs';

const RECORD_DEPTH = 1000;
const UPLOAD_SLICE = 1 << 20;
/** Bytes waiting for serve before the recorder drops (and counts) messages. */
const MAX_BUFFERED = 256 * 1024 * 1024;

/** A rosbag2 topic QoS for a subscription that matches the offers (ros2 bag record's rule). */
export function recordQos(offers) {
  const all = (field, value) => offers.length > 0 && offers.every((q) => q[field] === value);
  return {
    history: 'keep_last',
    depth: RECORD_DEPTH,
    reliability: offers.some((q) => q.reliability === 'best_effort') ? 'best_effort' : 'reliable',
    durability: all('durability', 'transient_local') ? 'transient_local' : 'volatile',
  };
}

/** Open `/bag` of this serve; resolves once open. */
function openBagSocket() {
  const ws = new WebSocket(`${location.protocol === 'https:' ? 'wss' : 'ws'}://${location.host}/bag`);
  ws.binaryType = 'arraybuffer';
  return new Promise((resolve, reject) => {
    ws.onopen = () => resolve(ws);
    ws.onerror = () => reject(new Error(`cannot open ${ws.url}: is this page served by colcon-wasm serve?`));
  });
}

/** Messages from serve: JSON ones go to the waiter of their op (or `onEvent`), binary to `onBinary`. */
class BagChannel {
  constructor(ws, { onEvent = () => {}, onBinary = () => {} } = {}) {
    this.ws = ws;
    this.onEvent = onEvent;
    this.onBinary = onBinary;
    this.waiters = new Map();
    ws.onmessage = (e) => {
      if (typeof e.data !== 'string') {
        this.onBinary(e.data);
        return;
      }
      const msg = JSON.parse(e.data);
      if (msg.op === 'error' && this.waiters.size) {
        for (const [, w] of this.waiters) w.reject(new Error(msg.msg));
        this.waiters.clear();
        return;
      }
      const waiter = this.waiters.get(msg.op);
      if (waiter) {
        this.waiters.delete(msg.op);
        waiter.resolve(msg);
      } else {
        this.onEvent(msg);
      }
    };
    ws.onclose = () => {
      for (const [, w] of this.waiters) w.reject(new Error('serve closed the /bag connection'));
      this.waiters.clear();
      this.onEvent({ op: 'closed' });
    };
  }

  send(op, fields = {}) {
    this.ws.send(JSON.stringify({ op, ...fields }));
  }

  /** Resolve with the next message of `op` (rejects on an `error`). */
  reply(op) {
    return new Promise((resolve, reject) => this.waiters.set(op, { resolve, reject }));
  }

  /** Wait until fewer than `bytes` bytes wait to be sent. */
  async drain(bytes) {
    while (this.ws.bufferedAmount > bytes) await new Promise((r) => setTimeout(r, 5));
  }
}

/**
 * What both recorders share: every topic with a publisher is subscribed,
 * once, with `recordQos`, and each one that appears later; `_channel(t,
 * type)` (the recorder's) gives the id its messages are written under, or
 * null for a topic it does not record, and `_write(id, batch)` takes them.
 */
export class GraphRecorder {
  constructor(session) {
    this.session = session;
    this.topics = new Map();
    this.messages = 0;
    this.dropped = 0;
    this.warnings = [];
    this._onGraph = () => this._subscribeNew();
  }

  /** Follow the graph: subscribe to what has a publisher now and later. */
  _follow() {
    this.session.on('graph', this._onGraph);
    this._subscribeNew();
  }

  _subscribeNew() {
    if (!this.recording) return;
    for (const t of this.session.graph.topics) {
      if (this.topics.has(t.name) || t.publishers === 0 || !t.types.length) continue;
      const type = t.types[0];
      const id = this._channel(t, type);
      if (id === null) {
        this.topics.set(t.name, null);
        continue;
      }
      const subscription = this.session.tools.subscribe(
        { topic: t.name, type, qos: recordQos(t.publisherQos) }, (batch) => this._write(id, batch));
      this.topics.set(t.name, { id, subscription });
    }
  }

  /** Stop following the graph and close the subscriptions (resolves once closed). */
  async _unfollow() {
    this.session.off('graph', this._onGraph);
    const closing = [...this.topics.values()].filter(Boolean)
      .map((t) => t.subscription.then((s) => s.close()).catch(() => {}));
    this.topics.clear();
    await Promise.all(closing);
  }
}

/** Records this page's bus into a bag written by serve. */
export class PageRecorder extends GraphRecorder {
  constructor(session) {
    super(session);
    this.channel = null;
  }

  get recording() { return this.channel !== null; }

  /** Start recording every topic with a publisher (and each one that appears). */
  async start({ name = 'launcher.mcap', compression = 'zstd' } = {}) {
    if (this.channel) throw new Error('already recording');
    const ws = await openBagSocket();
    this.channel = new BagChannel(ws, {
      onEvent: (msg) => {
        if (msg.op === 'skipped') this.warnings.push(`not recording ${msg.topic}: ${msg.why}`);
        if (msg.op === 'error') this.warnings.push(msg.msg);
      },
    });
    const started = this.channel.reply('recording');
    this.channel.send('record', { name, compression });
    await started;
    this.messages = 0;
    this.dropped = 0;
    this._follow();
  }

  _channel(t, type) {
    const id = this.topics.size + 1;
    this.channel.send('topic', { id, topic: t.name, type, qos: t.publisherQos });
    return id;
  }

  _write(id, batch) {
    const ws = this.channel && this.channel.ws;
    if (!ws) return;
    for (const m of batch) {
      if (ws.bufferedAmount > MAX_BUFFERED) {
        this.dropped++;
        continue;
      }
      const frame = new Uint8Array(20 + m.data.length);
      const view = new DataView(frame.buffer);
      view.setUint32(0, id, true);
      view.setFloat64(4, m.info.receivedTime, true);
      view.setFloat64(12, m.info.sourceTime, true);
      frame.set(m.data, 20);
      ws.send(frame);
      this.messages++;
    }
  }

  /**
   * Stop: resolves to {url, name, messages, bytes, skipped, error, dropped,
   * droppedWhy, warnings} once serve closed the file.
   */
  async stop() {
    if (!this.channel) throw new Error('not recording');
    await this._unfollow();
    const channel = this.channel;
    await channel.drain(0);
    const done = channel.reply('recorded');
    channel.send('stop');
    const result = await done;
    this.channel = null;
    channel.ws.close();
    return { ...result, dropped: this.dropped, droppedWhy: 'serve did not keep up', warnings: this.warnings.slice() };
  }
}

/**
 * A bag served back by serve: uploaded over `/bag`, which reads it and sends
 * its messages in their recorded timing. The source of a `PagePlayer`.
 */
export class ServeBagSource {
  /** @param {object} hooks {onState(state), onError(text), onMessage(id, data), onClock(ns)} */
  constructor(hooks) {
    this.hooks = hooks;
    this.channel = null;
  }

  /** Upload the bag; resolves to serve's description of it. */
  async open(file) {
    const ws = await openBagSocket();
    this.channel = new BagChannel(ws, {
      onEvent: (msg) => {
        if (msg.op === 'state') this.hooks.onState(msg);
        else if (msg.op === 'error') this.hooks.onError(msg.msg);
        else this.hooks.onState(null);
      },
      onBinary: (buffer) => this._frame(buffer),
    });
    const described = this.channel.reply('bag');
    this.channel.send('upload', { name: file.name || 'bag.mcap', size: file.size });
    for (let offset = 0; offset < file.size; offset += UPLOAD_SLICE) {
      await this.channel.drain(4 * UPLOAD_SLICE);
      ws.send(await file.slice(offset, offset + UPLOAD_SLICE).arrayBuffer());
    }
    return described;
  }

  /** A played message (`<u32 id><f64 position ms>` and the CDR bytes) or the bag time (id 0). */
  _frame(buffer) {
    const view = new DataView(buffer);
    const id = view.getUint32(0, true);
    if (id === 0) this.hooks.onClock(view.getBigUint64(12, true));
    else this.hooks.onMessage(id, new Uint8Array(buffer, 12));
  }

  // the controls, carried out by serve's player (colcon_wasm/record/paced_player.py)
  /** Play from where it stands (from the start once it ended). */
  play() { this.channel?.send('play'); }
  /** Stop sending; the position stays. */
  pause() { this.channel?.send('pause'); }
  /** Pause, and send the next message at once. */
  step() { this.channel?.send('step'); }
  /** Go to `positionMs` from the first message. */
  seek(positionMs) { this.channel?.send('seek', { position_ms: positionMs }); }
  /** Play `rate` times as fast as recorded. */
  setRate(rate) { this.channel?.send('rate', { rate }); }
  /** Send the bag time for /clock `hz` times a second while playing (0: none). */
  setClock(hz) { this.channel?.send('clock', { hz }); }

  /** Close the connection (serve stops playing). */
  close() {
    if (this.channel) this.channel.ws.close();
    this.channel = null;
  }
}

/**
 * Plays a bag (a File or Blob) into this page's bus: one publisher per
 * topic with the QoS rosbag2's player would offer, each message published
 * when its source hands it over, and /clock. The source reads the bag and
 * keeps the timing: serve's (`ServeBagSource`, the default) or the page's
 * own (bag_local.mjs, `makeSource`).
 */
export class PagePlayer {
  /**
   * @param {function(PagePlayer): void} [onChange] told of every change of state
   * @param {object} [options]
   * @param {function(object): object} [options.makeSource] makes a source from its hooks
   */
  constructor(session, onChange = () => {}, { makeSource = (hooks) => new ServeBagSource(hooks) } = {}) {
    this.session = session;
    this.onChange = onChange;
    this.makeSource = makeSource;
    this.source = null;
    this.info = null;
    this.state = { state: 'closed', position_ms: 0, sent: 0, rate: 1 };
    this.published = 0;
    this.publishers = new Map();
    this.error = null;
    this.clock = null;
    this.clockHz = 0;
    this.clockTime = null;
  }

  /** Open the bag and prepare its publishers; resolves to the source's description of it. */
  async open(file) {
    await this.close();
    this.source = this.makeSource({
      onState: (state) => {
        if (state) this.state = state;
        if (state && state.error) this.error = state.error;
        this.onChange(this);
      },
      onError: (text) => {
        this.error = text;
        this.onChange(this);
      },
      onMessage: (id, data) => this._publish(id, data),
      onClock: (ns) => this._clock(ns),
    });
    try {
      this.info = await this.source.open(file);
    } catch (e) {
      await this.close();
      throw e;
    }
    this.error = this.info.error;
    for (const t of this.info.topics) {
      this.publishers.set(t.id, this.session.tools.advertise({ topic: t.topic, type: t.type, qos: t.qos }));
    }
    await Promise.all(this.publishers.values());
    if (this.clockHz > 0) await this.setClock(this.clockHz);
    this.state = { state: 'paused', position_ms: 0, sent: 0, rate: 1 };
    this.onChange(this);
    return this.info;
  }

  _clock(ns) {
    this.clockTime = ns;
    if (this.clock) this.clock.then((p) => p.publish(clockMessage(ns))).catch(() => {});
  }

  _publish(id, data) {
    const publisher = this.publishers.get(id);
    if (!publisher) return;
    this.published++;
    publisher.then((p) => p.publish(data)).catch((e) => { this.error = `publishing failed: ${e.message}`; });
  }

  /** Play from where it stands (from the start once it ended). */
  play() { this.source?.play(); }
  /** Stop sending; the position stays. */
  pause() { this.source?.pause(); }
  /** Pause, and send the next message at once. */
  step() { this.source?.step(); }
  /** Go to `positionMs` from the first message; nothing between is sent. */
  seek(positionMs) { this.source?.seek(positionMs); }
  /** Play `rate` times as fast as recorded. */
  setRate(rate) { this.source?.setRate(rate); }

  /** Publish /clock (rosgraph_msgs/msg/Clock) with the bag time `hz` times a second while playing (0: stop). */
  async setClock(hz) {
    this.clockHz = hz;
    if (hz > 0 && !this.clock) {
      this.clock = this.session.tools.advertise({ topic: '/clock', type: 'rosgraph_msgs/msg/Clock', qos: CLOCK_QOS });
      await this.clock;
    }
    this.source?.setClock(hz);
  }

  /** Stop playing and remove the publishers. */
  async close() {
    if (this.source) this.source.close();
    this.source = null;
    const closing = [...this.publishers.values()].map((p) => p.then((x) => x.close()).catch(() => {}));
    this.publishers.clear();
    if (this.clock) closing.push(this.clock.then((p) => p.close()).catch(() => {}));
    this.clock = null;
    await Promise.all(closing);
    this.info = null;
    this.state = { state: 'closed', position_ms: 0, sent: 0, rate: 1 };
  }
}
