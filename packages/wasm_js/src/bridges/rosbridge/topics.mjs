// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * Topic operations of a session: advertise, unadvertise, publish,
 * subscribe (throttle_rate, queue_length, fragment_size, compression) and
 * unsubscribe, as rosbridge_library's capabilities do them:
 *
 *  - one subscription per topic and client; several subscribe requests
 *    (ids) to a topic combine as rosbridge combines them: the lowest
 *    throttle_rate, queue_length and fragment_size, the "largest"
 *    compression (cbor-raw > cbor > png > none); unsubscribe with an id
 *    removes that request, without one all of them;
 *  - throttle_rate without queue_length drops what comes within
 *    throttle_rate ms of the last message sent; with queue_length the last
 *    queue_length messages wait and one is sent per throttle_rate ms (and
 *    while the client's socket is backed up, so a slow client gets the
 *    newest messages, not a growing backlog);
 *  - a message whose publisher has a QoS lifespan carries `ttl` (the ms it
 *    has left) and is dropped, and counted, once stale (rowe's TTL).
 *
 * Each message is decoded and encoded once per form (JSON, CBOR, CBOR-raw)
 * however many clients receive it.
 *
 * @module bridges/rosbridge/topics
 */

import { CborWriter } from './cbor.mjs';
import { publisherQos } from './bus_link.mjs';
import { COMPRESSIONS, field, FieldError, rosName } from './protocol.mjs';

const COMPRESSION_RANK = { none: 0, png: 1, cbor: 2, 'cbor-raw': 3 };
const now = () => Date.now();

/** The bytes of a publish op in CBOR, with the message's rosbridge CBOR form. */
function cborPublish(topic, write) {
  const w = new CborWriter(256);
  w.map(3);
  w.string('op'); w.string('publish');
  w.string('topic'); w.string(topic);
  w.string('msg');
  write(w);
  return w.result().slice();
}

/** One client's subscription to one topic. */
class ClientSubscription {
  constructor(session, topic, type) {
    this.session = session;
    this.core = session.core;
    this.topic = topic;
    this.type = type;
    this.requests = new Map();
    this.params = { throttle: 0, queueLength: 0, fragmentSize: undefined, compression: 'none' };
    this.queue = [];
    this.lastSent = 0;
    this.timer = null;
    this.stop = null;
    this.stopDrain = null;
    this._lifespans = new Map();
    this._decodeFailed = false;
  }

  update() {
    const r = [...this.requests.values()];
    const frags = r.map((x) => x.fragmentSize).filter((x) => x);
    this.params = {
      throttle: Math.min(...r.map((x) => x.throttle)),
      queueLength: Math.min(...r.map((x) => x.queueLength)),
      fragmentSize: frags.length ? Math.min(...frags) : undefined,
      compression: r.map((x) => x.compression).reduce((a, b) => (COMPRESSION_RANK[b] > COMPRESSION_RANK[a] ? b : a), 'none'),
    };
    while (this.queue.length > Math.max(this.params.queueLength, 0)) {
      if (this.params.queueLength === 0) break;
      this.queue.shift();
      this.session.stats.dropped++;
    }
    if (this.params.queueLength === 0 && this.queue.length) this.flush(true);
  }

  lifespan(info) {
    const g = info.publisherGid;
    const key = g[1] * 16777216 + (g[2] & 0xffffff);
    let ms = this._lifespans.get(key);
    if (ms === undefined) {
      ms = this.core.link.lifespanOf(this.topic, info.publisherGid);
      this._lifespans.set(key, ms);
    }
    return ms;
  }

  onBatch(batch) {
    if (this.session.closed) return;
    for (const m of batch) {
      const lifespan = this.lifespan(m.info);
      const entry = { m, expires: lifespan ? m.info.sourceTime + lifespan : Infinity };
      if (this.params.queueLength === 0) {
        if (this.params.throttle && now() - this.lastSent < this.params.throttle) continue;
        this.send(entry);
      } else {
        this.queue.push(entry);
        if (this.queue.length > this.params.queueLength) {
          this.queue.shift();
          this.session.stats.dropped++;
        }
      }
    }
    if (this.queue.length) this.flush();
  }

  /** Send what the queue holds, as throttle_rate and the socket allow. */
  flush(all = false) {
    if (this.timer || this.session.closed) return;
    const highWater = Math.min(1 << 20, this.core.limits.maxQueuedBytes >> 2);
    while (this.queue.length) {
      const wait = this.params.throttle - (now() - this.lastSent);
      if (!all && this.params.throttle && wait > 0) {
        this.timer = setTimeout(() => { this.timer = null; this.flush(); }, wait);
        return;
      }
      if (!all && this.session.backedUp(highWater)) {
        if (!this.stopDrain) this.stopDrain = this.session.onDrain(() => { this.stopDrain(); this.stopDrain = null; this.flush(); });
        return;
      }
      this.send(this.queue.shift());
    }
  }

  send({ m, expires }) {
    const t = now();
    if (t > expires) {
      this.session.stats.expired++;
      this.core.stats.expired++;
      return;
    }
    this.lastSent = t;
    const { compression, fragmentSize } = this.params;
    const conv = this.core.converter;
    try {
      if (compression === 'cbor-raw') {
        if (!m.cborRaw) {
          const secs = Math.floor(t / 1000);
          m.cborRaw = cborPublish(this.topic, (w) => {
            w.map(3);
            w.string('secs'); w.int(secs);
            w.string('nsecs'); w.int((t - secs * 1000) * 1e6);
            w.string('bytes'); w.byteString(m.data);
          });
        }
        this.session.write(m.cborRaw);
        return;
      }
      if (m.value === undefined) m.value = this.core.registry.decode(this.type, m.data);
      if (compression === 'cbor') {
        if (!m.cbor) m.cbor = cborPublish(this.topic, (w) => conv.cborWriter(this.type)(w, m.value));
        this.session.write(m.cbor);
        return;
      }
      if (!m.text) m.text = `{"op":"publish","topic":${JSON.stringify(this.topic)},"msg":${conv.jsonWriter(this.type)(m.value)}}`;
      let text = m.text;
      if (expires !== Infinity) text = `${text.slice(0, -1)},"ttl":${Math.max(0, Math.round(expires - t))}}`;
      if (compression === 'png') text = JSON.stringify({ op: 'png', data: this.core.png(text) });
      this.session.sendText(text, fragmentSize);
    } catch (e) {
      if (!this._decodeFailed) {
        this._decodeFailed = true;
        this.session.status('error', `cannot forward a message of '${this.topic}' (${this.type}): ${e.message}`);
      }
    }
  }

  close() {
    if (this.timer) clearTimeout(this.timer);
    if (this.stopDrain) this.stopDrain();
    this.queue = [];
    if (this.stop) this.stop();
  }
}

/**
 * Register the topic operations on a session.
 * @param {import('./session.mjs').Session} session
 */
export function installTopics(session) {
  const { core } = session;
  const subscriptions = new Map();
  const publishers = new Map();

  const messageType = (op, name) => {
    try {
      return core.converter.messageType(name);
    } catch (e) {
      throw new FieldError(op, 'type', `names an unknown type: ${e.message}`);
    }
  };

  session.register('subscribe', async (msg) => {
    const topic = rosName('subscribe', 'topic', field(msg, 'topic', 'string', { required: true, what: 'the topic to subscribe to' }));
    if (!core.capabilities.allows('subscribe', topic)) throw new Error(core.capabilities.refusal('subscribe', topic));
    const request = {
      throttle: Math.max(0, field(msg, 'throttle_rate', 'int', { fallback: 0, what: 'ms between messages' })),
      queueLength: Math.max(0, field(msg, 'queue_length', 'int', { fallback: 0 })),
      fragmentSize: field(msg, 'fragment_size', 'int', { fallback: undefined }) || undefined,
      compression: field(msg, 'compression', 'string', { fallback: 'none' }),
    };
    if (!COMPRESSIONS.includes(request.compression)) {
      throw new FieldError('subscribe', 'compression', `must be one of ${COMPRESSIONS.join(', ')}, got '${request.compression}'`);
    }
    const given = field(msg, 'type', 'string');
    let type = given ? messageType('subscribe', given) : null;
    const inGraph = core.link.topicType(topic);
    if (!type) {
      if (!inGraph) throw new Error(`cannot infer the type of topic '${topic}': it is not in the graph yet; give 'type'`);
      type = messageType('subscribe', inGraph);
    } else if (inGraph && inGraph !== type) {
      throw new FieldError('subscribe', 'type', `is ${type}, but topic '${topic}' has type ${inGraph}`);
    }
    let sub = subscriptions.get(topic);
    if (sub && sub.type !== type) throw new FieldError('subscribe', 'type', `is ${type}, but this client is subscribed to '${topic}' as ${sub.type}`);
    const sid = msg.id === undefined ? null : msg.id;
    if (!sub) {
      sub = new ClientSubscription(session, topic, type);
      subscriptions.set(topic, sub);
      sub.requests.set(sid, request);
      sub.update();
      try {
        sub.stop = await core.link.listen(topic, type, (batch) => sub.onBatch(batch));
      } catch (e) {
        subscriptions.delete(topic);
        throw e;
      }
      if (session.closed || subscriptions.get(topic) !== sub) sub.close();
    } else {
      sub.requests.set(sid, request);
      sub.update();
    }
    session.status('info', `Subscribed to ${topic}`, msg.id);
  });

  session.register('unsubscribe', (msg) => {
    const topic = rosName('unsubscribe', 'topic', field(msg, 'topic', 'string', { required: true }));
    const sub = subscriptions.get(topic);
    if (!sub) {
      session.status('warning', `unsubscribe: this client is not subscribed to '${topic}'`, msg.id);
      return;
    }
    if (msg.id === undefined || msg.id === null) sub.requests.clear();
    else sub.requests.delete(msg.id);
    if (sub.requests.size === 0) {
      subscriptions.delete(topic);
      sub.close();
    } else {
      sub.update();
    }
    session.status('info', `Unsubscribed from ${topic}`, msg.id);
  });

  const advertise = async (msg, topic, type) => {
    const qos = publisherQos({
      latch: field(msg, 'latch', 'bool', { fallback: false }),
      queueSize: field(msg, 'queue_size', 'int', { fallback: 100 }),
    });
    let entry = publishers.get(topic);
    if (entry) {
      if (entry.type !== type) throw new FieldError(msg.op, 'type', `is ${type}, but this client advertised '${topic}' as ${entry.type}`);
      entry.count++;
      return entry;
    }
    entry = { type, count: 1, handle: null, ready: core.link.publisher(topic, type, qos) };
    publishers.set(topic, entry);
    try {
      entry.handle = await entry.ready;
    } catch (e) {
      publishers.delete(topic);
      throw e;
    }
    if (session.closed) entry.handle.release();
    return entry;
  };

  session.register('advertise', async (msg) => {
    const topic = rosName('advertise', 'topic', field(msg, 'topic', 'string', { required: true }));
    if (!core.capabilities.allows('publish', topic)) throw new Error(core.capabilities.refusal('publish', topic));
    const type = messageType('advertise', field(msg, 'type', 'string', { required: true, what: 'the message type, e.g. std_msgs/msg/String' }));
    const inGraph = core.link.topicType(topic);
    if (inGraph && inGraph !== type) throw new FieldError('advertise', 'type', `is ${type}, but topic '${topic}' already has type ${inGraph}`);
    await advertise(msg, topic, type);
    session.status('info', `Advertised ${topic}`, msg.id);
  });

  session.register('unadvertise', (msg) => {
    const topic = rosName('unadvertise', 'topic', field(msg, 'topic', 'string', { required: true }));
    const entry = publishers.get(topic);
    if (!entry) {
      session.status('warning', `unadvertise: this client does not advertise '${topic}'`, msg.id);
      return;
    }
    if (--entry.count > 0) return;
    publishers.delete(topic);
    entry.ready.then((h) => h.release(), () => {});
  });

  session.register('publish', async (msg) => {
    const topic = rosName('publish', 'topic', field(msg, 'topic', 'string', { required: true }));
    if (!core.capabilities.allows('publish', topic)) throw new Error(core.capabilities.refusal('publish', topic));
    if (msg.msg === undefined) throw new FieldError('publish', 'msg', 'is missing (the message to publish)');
    let entry = publishers.get(topic);
    if (!entry) {
      const given = field(msg, 'type', 'string');
      const known = given ? messageType('publish', given) : core.link.topicType(topic);
      if (!known) throw new Error(`cannot infer the type of topic '${topic}': it is not in the graph; advertise it with a type first`);
      entry = await advertise(msg, topic, messageType('publish', known));
    } else if (!entry.handle) {
      await entry.ready;
    }
    const ttl = field(msg, 'ttl', 'number');
    if (ttl !== undefined && ttl <= 0) {
      session.stats.expired++;
      core.stats.expired++;
      return;
    }
    let bytes;
    const m = msg.msg;
    if (m && m.bytes instanceof Uint8Array && Object.keys(m).every((k) => k === 'bytes' || k === 'secs' || k === 'nsecs')) {
      bytes = m.bytes; // CBOR: the serialized message as it is (cbor-raw's form)
    } else {
      const value = core.converter.fromJson(entry.type, m);
      try {
        bytes = core.registry.encode(entry.type, value);
      } catch (e) {
        throw new FieldError('publish', 'msg', `does not fit ${entry.type}: ${e.message.replace(/^encoding [^:]+: /, '')}`);
      }
    }
    await entry.handle.publish(bytes);
  });

  session.onClose(() => {
    for (const sub of subscriptions.values()) sub.close();
    subscriptions.clear();
    for (const entry of publishers.values()) entry.ready.then((h) => h.release(), () => {});
    publishers.clear();
  });
}
