// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The topics of the rosbridge client (client.mjs), which mixes these
 * methods into RosbridgeClient: a topic local nodes publish (advertised
 * remotely; its messages queued while disconnected, KEEP_LAST keeping the
 * last n, RELIABLE KEEP_ALL up to the byte bound; sent in order once the
 * remote topic has a subscriber; echoes recognised) and a topic local
 * nodes subscribe to (subscribed remotely, CDR bytes published locally).
 *
 * @module bridges/rosbridge/client_topics
 */

import { gidHex } from './bus_link.mjs';
import { CborWriter } from './cbor.mjs';

/** The nodes of the bridges themselves: what they do is not bridged again. */
export const BRIDGE_NODES = new Set(['/rosbridge_client', '/rosbridge_websocket']);
const IN_QOS = { history: 'keep_last', depth: 10, reliability: 'reliable', durability: 'transient_local' };
/** What a publish carries until the relay says otherwise (and always for other servers). */
const JSON_ONLY = Object.freeze({ json: true, cdr: false });

/**
 * The CBOR bytes of a publish of CDR bytes, `{op, topic, msg: {bytes, secs,
 * nsecs}, ttl?}` (cbor-raw's form, which rosbridge servers and serve's relay take).
 */
export function cdrPublish(topic, bytes, timeMs, ttl) {
  const w = new CborWriter(bytes.length + 96);
  const secs = Math.floor(timeMs / 1000);
  w.map(ttl === undefined ? 3 : 4);
  w.string('op'); w.string('publish');
  w.string('topic'); w.string(topic);
  w.string('msg');
  w.map(3);
  w.string('bytes'); w.byteString(bytes);
  w.string('secs'); w.int(secs);
  w.string('nsecs'); w.int(Math.round((timeMs - secs * 1000) * 1e6));
  if (ttl !== undefined) { w.string('ttl'); w.int(ttl); }
  return w.result();
}

/** A cheap fingerprint of bytes (FNV-1a over length and every byte). */
export function fingerprint(bytes) {
  let h = 0x811c9dc5 ^ bytes.length;
  for (let i = 0; i < bytes.length; i++) h = Math.imul(h ^ bytes[i], 16777619);
  return `${bytes.length}:${h >>> 0}`;
}

/** Methods of RosbridgeClient (`this` is the client). */
export class ClientTopics {
  // ----------------------------------------------------------- topics out

  _startOut(topic, { type, publishers }) {
    const b = { topic, type, publishers, queue: [], stop: null, lifespans: new Map(), echoes: new Map(), flushing: false };
    this._advertise(b);
    // hear every message the publishers keep: KEEP_ALL publishers wait for a KEEP_ALL reader
    const qos = publishers.map((e) => e.qos || {});
    const keepAll = qos.some((q) => q.history === 'keep_all' && q.reliability !== 'best_effort');
    const tapQos = {
      history: keepAll ? 'keep_all' : 'keep_last', depth: Math.max(100, ...qos.map((q) => q.depth || 0)),
      reliability: qos.some((q) => q.reliability === 'best_effort') ? 'best_effort' : 'reliable',
      durability: qos.length && qos.every((q) => q.durability === 'transient_local') ? 'transient_local' : 'volatile',
    };
    this.link.listen(topic, type, (batch) => this._localMessages(b, batch), tapQos).then((stop) => {
      if (this.out.get(topic) !== b) stop();
      else b.stop = stop;
    }, (e) => this.log('error', `cannot bridge ${topic}: ${e.message}`));
    return b;
  }

  _stopOut(b) {
    if (b.stop) b.stop();
    if (b.kick) clearTimeout(b.kick);
    if (b.queue.length && !this.closed) {
      // the publisher is gone, what it sent is not: deliver it, then unadvertise
      b.draining = true;
      this.draining.add(b);
      if (this.connected) this._flushWhenHeard(b);
      return;
    }
    this._send({ op: 'unadvertise', topic: b.topic });
  }

  _advertise(b) {
    const q = (b.publishers[0] && b.publishers[0].qos) || {};
    this._send({
      op: 'advertise', topic: b.topic, type: b.type, latch: q.durability === 'transient_local',
      queue_size: q.depth || 10,
    });
  }

  _publisherQos(b, gid) {
    const hex = gidHex(gid);
    const p = b.publishers.find((e) => e.gid === hex) || b.publishers[0] || {};
    return p.qos || {};
  }

  _localMessages(b, batch) {
    for (const m of batch) {
      const qos = this._publisherQos(b, m.info.publisherGid);
      const lifespan = Number.isFinite(qos.lifespanMs) && qos.lifespanMs > 0 ? qos.lifespanMs : 0;
      const entry = { data: m.data, time: m.info.sourceTime, expires: lifespan ? m.info.sourceTime + lifespan : Infinity, qos };
      if (this.connected && !b.queue.length && !b.flushing && this.ws.bufferedAmount < this.limits.highWaterBytes) this._publishOut(b, entry);
      else this._enqueue(b, entry);
    }
    if (b.queue.length && this.connected && !b.flushing && !b.kick) {
      b.kick = setTimeout(() => { b.kick = null; this._flush(b); }, 10);
    }
  }

  _enqueue(b, entry) {
    const qos = entry.qos;
    if (qos.reliability === 'best_effort') {
      this.counters.dropped++;
      return;
    }
    if (qos.history !== 'keep_all') {
      const depth = Math.max(1, qos.depth || 10);
      while (b.queue.length >= depth) {
        const old = b.queue.shift();
        this.queuedBytes -= old.data.length;
        this.counters.replaced++;
        b.replaced = (b.replaced || 0) + 1;
      }
    } else if (this.queuedBytes + entry.data.length > this.limits.maxQueuedBytes) {
      this.counters.lost++;
      b.lost = (b.lost || 0) + 1;
      return;
    }
    b.queue.push(entry);
    this.queuedBytes += entry.data.length;
    this.counters.queued++;
  }

  _dropQueue(b) {
    for (const e of b.queue) this.queuedBytes -= e.data.length;
    b.queue = [];
  }

  _publishOut(b, entry) {
    if (Date.now() > entry.expires) {
      this.counters.expired++;
      return true;
    }
    // serve's relay says which forms its other clients need: CDR (cbor-raw), JSON, both or none
    const forms = (this.relayVersion >= 2 && this.forms.get(b.topic)) || JSON_ONLY;
    const ttl = entry.expires === Infinity ? undefined : Math.max(1, Math.round(entry.expires - Date.now()));
    let sent = true;
    if (forms.cdr) sent = this._sendRaw(cdrPublish(b.topic, entry.data, entry.time, ttl));
    if (!forms.json) return sent;
    let json;
    try {
      json = this.converter.jsonWriter(b.type)(this.registry.decode(b.type, entry.data));
    } catch (e) {
      this.log('error', `cannot bridge a message of ${b.topic}: ${e.message}`);
      return true;
    }
    if (this.in.has(b.topic) && !this.relay) this._expectEcho(b, entry.data); // the relay never echoes
    const ttlText = ttl === undefined ? '' : `,"ttl":${ttl}`;
    return this._sendRaw(`{"op":"publish","topic":${JSON.stringify(b.topic)},"msg":${json}${ttlText}}`) && sent;
  }

  _expectEcho(b, data) {
    const key = fingerprint(data);
    const now = Date.now();
    const list = b.echoes.get(key) || [];
    list.push(now + this.limits.echoWindowMs);
    b.echoes.set(key, list);
  }

  /** After (re)connecting: send the queue once the remote topic has a subscriber. */
  async _flushWhenHeard(b) {
    if (!b.queue.length || b.flushing) return;
    b.flushing = true;
    const deadline = Date.now() + this.limits.flushWaitMs;
    try {
      while (this.connected && Date.now() < deadline) {
        let subscribers;
        try {
          subscribers = (await this._call('/rosapi/subscribers', { topic: b.topic }, 3000)).subscribers || [];
        } catch {
          break; // no rosapi: send now
        }
        if (subscribers.some((n) => n !== '/rosbridge_websocket')) break;
        await new Promise((r) => setTimeout(r, 100));
      }
    } finally {
      b.flushing = false;
    }
    this._flush(b);
  }

  _flush(b) {
    if (b.replaced || b.lost) {
      this.log('warning', `${b.topic}: ${b.replaced || 0} older messages were replaced (KEEP_LAST) and ${b.lost || 0} lost `
        + `(past the bound of ${this.limits.maxQueuedBytes} bytes) while ${this.displayUrl} was unreachable`);
      b.replaced = 0;
      b.lost = 0;
    }
    while (b.queue.length && this.connected) {
      if (this.ws.bufferedAmount >= this.limits.highWaterBytes) {
        setTimeout(() => this._flush(b), 20);
        return;
      }
      const entry = b.queue.shift();
      this.queuedBytes -= entry.data.length;
      this._publishOut(b, entry);
    }
    if (b.draining && !b.queue.length) {
      this.draining.delete(b);
      if (!this.out.has(b.topic)) this._send({ op: 'unadvertise', topic: b.topic });
    }
  }

  // ----------------------------------------------------------- topics in

  _startIn(topic, { type }) {
    const b = { topic, type, publisher: null, ready: null };
    b.ready = this.link.publisher(topic, type, IN_QOS).then((p) => {
      if (this.in.get(topic) !== b) p.release();
      else b.publisher = p;
      return p;
    });
    b.ready.catch((e) => this.log('error', `cannot bridge ${topic} in: ${e.message}`));
    this._subscribe(b);
    return b;
  }

  _stopIn(b) {
    b.ready.then((p) => p.release(), () => {});
    this._send({ op: 'unsubscribe', topic: b.topic, id: `bridge:${b.topic}` });
  }

  _subscribe(b) {
    // CDR bytes as they are, unless the server is an older relay of serve (version 1: JSON only);
    // serve's relay of version 2 sends cbor-raw from colcon-wasm publishers and JSON from others
    const jsonOnly = this.relay && this.relayVersion < 2;
    this._send({ op: 'subscribe', id: `bridge:${b.topic}`, topic: b.topic, type: b.type, compression: jsonOnly ? 'none' : 'cbor-raw' });
  }

  /**
   * The server is `colcon-wasm serve --rosbridge`'s relay (it said so): it
   * shows the nodes each client reports in its rosapi; from version 2 it
   * forwards CDR between colcon-wasm clients and tells each publisher which
   * forms its subscribers need (`colcon_wasm_forms`); version 1 forwards JSON.
   */
  _relayMode(msg) {
    const version = Number.isInteger(msg && msg.version) ? msg.version : 1;
    const wasJsonOnly = this.relay && this.relayVersion < 2;
    this.relay = true;
    this.relayVersion = version;
    if ((version < 2) !== wasJsonOnly) for (const b of this.in.values()) this._subscribe(b);
    this._reported = null; // on every greeting: a reconnected relay has forgotten our nodes
    this._reportGraph();
    this._scheduleSync(); // the relay gets the parameter services and /parameter_events too
  }

  /** `{"op": "colcon_wasm_forms", "topic", "json", "cdr"}`: what the relay needs of a topic we publish. */
  _relayForms(msg) {
    if (typeof msg.topic !== 'string') return;
    this.forms.set(msg.topic, { json: msg.json === true, cdr: msg.cdr === true });
  }

  /**
   * Tell the relay our nodes and which of them holds which endpoint:
   * `{"op": "colcon_wasm_graph", "nodes", "endpoints": {node: {publishing,
   * subscribing, services}}, "version": 2}` (all of each node's topics and
   * the services it serves, bridged or not, as rosapi's node_details lists them).
   */
  _reportGraph() {
    if (!this.relay || !this.connected) return;
    const nodes = this.link.graph().nodes.filter((n) => !BRIDGE_NODES.has(n.fqn));
    const names = (list) => list.map((e) => e.name);
    const endpoints = Object.fromEntries(nodes.map((n) => [n.fqn, {
      publishing: names(n.publishers), subscribing: names(n.subscriptions), services: names(n.services),
    }]));
    const key = JSON.stringify(endpoints);
    if (key === this._reported) return;
    this._reported = key;
    this._send({ op: 'colcon_wasm_graph', nodes: nodes.map((n) => n.fqn), endpoints, version: 2 });
  }

  _remotePublish(msg) {
    const b = this.in.get(msg.topic);
    if (!b) return;
    if (typeof msg.ttl === 'number' && msg.ttl <= 0) {
      this.counters.expired++;
      return;
    }
    let bytes;
    if (msg.msg && msg.msg.bytes instanceof Uint8Array) bytes = msg.msg.bytes;
    else {
      try {
        bytes = this.registry.encode(b.type, this.converter.fromJson(b.type, msg.msg));
      } catch (e) {
        this.log('error', `a message of ${msg.topic} from ${this.displayUrl} does not fit ${b.type}: ${e.message}`);
        return;
      }
    }
    const out = this.out.get(msg.topic);
    if (out && out.echoes.size) {
      const key = fingerprint(bytes);
      const list = out.echoes.get(key);
      const now = Date.now();
      if (list) {
        while (list.length && list[0] < now) list.shift();
        if (list.length) {
          list.shift();
          if (!list.length) out.echoes.delete(key);
          this.counters.echoes++;
          return;
        }
        out.echoes.delete(key);
      }
    }
    if (b.publisher) b.publisher.publish(bytes).catch(() => {});
    else b.ready.then((p) => p.publish(bytes)).catch(() => {});
  }
}
