// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * What the Zenoh gateway (core.mjs) carries, one object per topic or
 * service and direction, each restarted on a new session:
 * - TopicOut: local publishers -> a Zenoh publisher on the rmw_zenoh key;
 *   each sample carries the attachment (the local publisher's sequence
 *   number, source time and gid). While there is no session, RELIABLE
 *   messages wait (bounded in bytes, oldest dropped and counted), sent in
 *   order once the session is back; BEST_EFFORT ones are counted as lost.
 * - TopicIn: local subscriptions <- a Zenoh subscriber; CDR bytes published
 *   locally by the gateway's node, one local publisher per remote one.
 * - ServiceServed: a local server answers rmw_zenoh clients' queries.
 * - ServiceProxied: local clients reach a remote rmw_zenoh server through a
 *   local server of the gateway's node.
 *
 * @module bridges/zenoh/bridges
 */

import { setUint64 } from '../common/little_endian.mjs';
import { TakeMode } from './gateway_bus.mjs';
import { dataKey, decodeAttachment, encodeAttachment, nowNs } from './keys.mjs';
import { randomZid } from './session.mjs';

/** An action's result is asked for when the goal starts: its call lasts as long as the goal (rmw_zenoh: no timeout). */
const LONG_CALL = /\/_action\/get_result$/;
const LONG_CALL_MS = 24 * 3600 * 1000;

/** How long a new Zenoh publisher holds messages while the router declares its subscribers. */
const MATCH_GRACE_MS = 1000;

/** How long a call of `service` may take. */
function callTimeout(gateway, service) {
  return LONG_CALL.test(service) ? LONG_CALL_MS : gateway.limits.callTimeoutMs;
}

/** Bytes of the attachment written ahead of a payload in the session's scratch buffer (33, padded). */
const ATTACHMENT_ROOM = 36;

/**
 * Local publishers' messages, to Zenoh: the gateway's subscription takes
 * each message straight into zenoh-pico's memory, its attachment beside it,
 * and puts it, in one zenoh-pico batch per wake-up (as few socket writes as
 * the messages fit in). The attachment's sequence number is the local
 * publisher's publication sequence number, its gid the publisher's.
 */
export class TopicOut {
  constructor(gateway, topic, { type, publishers }) {
    this.gateway = gateway;
    this.topic = topic;
    this.type = type;
    this.publishers = publishers;
    this.key = dataKey(gateway.domain, topic, type);
    this.queue = [];
    this.queuedBytes = 0;
    this.zenoh = null;
    this.sub = null;
    this._view = null;
    const qos = publishers.map((e) => e.qos || {});
    this.reliable = qos.some((q) => q.reliability !== 'best_effort');
    // TRANSIENT_LOCAL publishers: an advanced publisher keeps their last samples for late remote subscribers
    const latched = qos.filter((q) => q.durability === 'transient_local');
    this.cacheDepth = latched.length ? Math.max(1, ...latched.map((q) => q.depth || 1)) : 0;
    const keepAll = qos.some((q) => q.history === 'keep_all');
    const tapQos = {
      history: keepAll ? 'keep_all' : 'keep_last', depth: Math.max(100, ...qos.map((q) => q.depth || 0)),
      reliability: this.reliable ? 'reliable' : 'best_effort',
      durability: qos.length && qos.every((q) => q.durability === 'transient_local') ? 'transient_local' : 'volatile',
    };
    gateway.log('debug', `${topic}: listening with ${JSON.stringify(tapQos)}`);
    try {
      this.sub = gateway.bus.subscribe(topic, type, tapQos, () => this._drain());
    } catch (e) {
      gateway.log('error', `cannot bridge ${topic} to Zenoh: ${e.message}`);
    }
  }

  /**
   * Declare the Zenoh publisher on a (new) session. zenoh-pico drops puts
   * until the router has declared the matching subscribers, so messages are
   * held until the publisher matches (or MATCH_GRACE_MS passes: then there
   * is no subscriber, and zenoh drops them as it would), and sent in order.
   */
  attach(session) {
    this.zenoh = null;
    this.holding = true;
    const release = () => this._release();
    try {
      const onMatching = (matching) => { if (matching) release(); };
      this.zenoh = this.cacheDepth
        ? session.advancedPublisher(this.key, { reliable: this.reliable, depth: this.cacheDepth, onMatching })
        : session.publisher(this.key, { reliable: this.reliable, onMatching });
      this.gateway.log('debug', `${this.topic}: ${this.cacheDepth ? `advanced publisher (cache ${this.cacheDepth})` : 'publisher'} on ${this.key}`);
    } catch (error) {
      this.gateway.log('error', `cannot publish ${this.topic} on Zenoh: ${error.message}`);
      return;
    }
    clearTimeout(this.graceTimer);
    this.graceTimer = setTimeout(release, MATCH_GRACE_MS);
  }

  _release() {
    clearTimeout(this.graceTimer);
    if (!this.holding || !this.zenoh) return;
    this.holding = false;
    const waiting = this.queue;
    this.queue = [];
    this.queuedBytes = 0;
    if (waiting.length) this.gateway.log('debug', `${this.topic}: sending the ${waiting.length} messages that waited`);
    const session = this.gateway.session;
    if (session && session.up) session.batch(() => { for (const m of waiting) this._put(m); });
    else for (const m of waiting) this._wait(m);
    this._drain(); // what came meanwhile
  }

  detach() {
    this.zenoh = null;
    clearTimeout(this.graceTimer);
  }

  /** Take what the subscription has: to Zenoh, or to the queue while there is no publisher to send it. */
  _drain() {
    if (!this.sub || this.closed) return;
    const session = this.gateway.session;
    try {
      if (this.zenoh && !this.holding && session && session.up) session.batch(() => this._sendAll(session));
      else this._queueAll();
    } catch (error) {
      this.gateway.log('error', `cannot send ${this.topic} to Zenoh: ${error.stack || error.message}`);
    }
  }

  _sendAll(session) {
    const client = this.gateway.bus.client;
    const ep = this.sub.ep;
    const counters = this.gateway.counters;
    for (;;) {
      const len = client.takeBegin(ep, TakeMode.MESSAGE);
      if (len < 0) return;
      const at = session.scratch(ATTACHMENT_ROOM + len);
      const heap = session.module.HEAPU8;
      if (!client.takeCopy(heap, at + ATTACHMENT_ROOM)) continue;
      this._attachment(heap, at, client.info);
      const ret = this.zenoh.putAt(at + ATTACHMENT_ROOM, len, at, 33);
      if (!this.announced) {
        this.announced = true;
        this.gateway.log('debug', `${this.topic}: first message out (${len} bytes, zenoh-pico ${ret})`);
      }
      if (ret === 0) counters.sent += 1;
      else this._wait(this._entry(session.module.HEAPU8.slice(at + ATTACHMENT_ROOM, at + ATTACHMENT_ROOM + len), client.info));
      if (!this.zenoh || !session.up) {
        this._queueAll();
        return;
      }
    }
  }

  _queueAll() {
    const client = this.gateway.bus.client;
    let data;
    while ((data = client.take(this.sub.ep, TakeMode.MESSAGE))) this._wait(this._entry(data, client.info));
  }

  /** rmw_zenoh's attachment of a message taken (info: the bus client's) at `at` of the module's memory. */
  _attachment(heap, at, info) {
    if (!this._view || this._view.buffer !== heap.buffer) this._view = new DataView(heap.buffer);
    const v = this._view;
    v.setUint32(at, info.pubSeqLo >>> 0, true);
    v.setUint32(at + 4, info.pubSeqHi >>> 0, true);
    setUint64(v, at + 8, Math.round(info.sourceTime * 1e6));
    heap[at + 16] = 16;
    const g = info.gid;
    for (let i = 0; i < 4; i++) v.setInt32(at + 17 + 4 * i, g[i], true);
  }

  /** A message kept to be sent later (no session, or a publisher not matched yet). */
  _entry(data, info) {
    return {
      data, seq: info.pubSeqHi * 4294967296 + (info.pubSeqLo >>> 0), timeNs: Math.round(info.sourceTime * 1e6),
      gid: new Uint8Array(Int32Array.from(info.gid).buffer),
    };
  }

  _put(entry) {
    const ret = this.zenoh && this.gateway.session && this.gateway.session.up
      ? this.zenoh.put(entry.data, encodeAttachment(entry.seq, entry.timeNs, entry.gid)) : -1;
    if (ret === 0) this.gateway.counters.sent += 1;
    else this._wait(entry);
  }

  _wait(entry) {
    // BEST_EFFORT messages wait only for a new publisher to match, not for a session
    if (!this.reliable && !(this.holding && this.zenoh)) {
      this.gateway.counters.lost += 1;
      return;
    }
    const limit = this.gateway.limits.queueBytes;
    this.queue.push(entry);
    this.queuedBytes += entry.data.length;
    while (this.queuedBytes > limit && this.queue.length) {
      const old = this.queue.shift();
      this.queuedBytes -= old.data.length;
      this.gateway.counters.lost += 1;
    }
    this.gateway.counters.queued += 1;
  }

  close() {
    this.closed = true;
    clearTimeout(this.graceTimer);
    if (this.sub) this.sub.close();
    if (this.zenoh) this.zenoh.close();
    this.zenoh = null;
  }
}

/**
 * Remote publishers' messages, to local subscriptions: a Zenoh subscriber,
 * and one local publisher of the gateway's node per remote publisher (a
 * remote publisher that goes is one publisher less alive for the local
 * subscriptions: their liveliness changes, the graph follows). Samples are
 * published by the first; the others stand for the other remote publishers
 * (which one sent a sample, a token does not say).
 */
export class TopicIn {
  constructor(gateway, topic, { type, qos, remotes = 1 }) {
    this.gateway = gateway;
    this.topic = topic;
    this.type = type;
    this.qos = qos;
    this.key = dataKey(gateway.domain, topic, type);
    this.zenoh = null;
    this.proxies = [];
    this.noAttachment = 0;
    this.setRemotes(remotes);
  }

  /** Have `count` local publishers (at least one while the bridge lives). */
  setRemotes(count) {
    const want = Math.max(1, count);
    while (this.proxies.length < want && !this.closed) {
      try {
        this.proxies.push(this.gateway.bus.publisher(this.topic, this.type, this.qos));
      } catch (e) {
        this.gateway.log('error', `cannot publish ${this.topic} locally: ${e.message}`);
        return;
      }
    }
    // the first, which has published (its TRANSIENT_LOCAL history), goes last
    while (this.proxies.length > want) this.proxies.pop().close();
  }

  attach(session) {
    this.zenoh = null;
    try {
      const onSample = (sample) => this._sample(sample);
      // TRANSIENT_LOCAL subscriptions: an advanced subscriber asks the remote caches for their history
      this.zenoh = this.qos.durability === 'transient_local'
        ? session.advancedSubscribe(this.key, onSample, { reliable: this.qos.reliability !== 'best_effort', depth: this.qos.depth })
        : session.subscribe(this.key, onSample);
    } catch (error) {
      this.gateway.log('error', `cannot subscribe to ${this.topic} on Zenoh: ${error.message}`);
    }
  }

  detach() {
    this.zenoh = null;
  }

  _sample(sample) {
    if (sample.kind !== 'put' || this.closed || !this.proxies.length) return;
    try {
      decodeAttachment(sample.attachment);
    } catch (error) {
      // rmw_zenoh drops samples without its attachment; so does the gateway, and says so once per topic
      this.gateway.counters.malformed += 1;
      if (!this.noAttachment++) this.gateway.log('warning', `dropping a sample on ${this.topic} from Zenoh: ${error.message}`);
      return;
    }
    this.gateway.counters.received += 1;
    try {
      this.proxies[0].publish(sample.payload);
    } catch (e) {
      this.gateway.log('error', `cannot publish ${this.topic} locally: ${e.message}`);
    }
  }

  close() {
    this.closed = true;
    if (this.zenoh) this.zenoh.close();
    for (const p of this.proxies.splice(0)) p.close();
  }
}

/** A local service server, answering rmw_zenoh clients. */
export class ServiceServed {
  constructor(gateway, service, { type }) {
    this.gateway = gateway;
    this.service = service;
    this.type = type;
    this.key = dataKey(gateway.domain, service, type);
    this.zenoh = null;
  }

  attach(session) {
    this.zenoh = null;
    try {
      this.zenoh = session.queryable(this.key, (query) => this._query(query));
    } catch (error) {
      this.gateway.log('error', `cannot serve ${this.service} on Zenoh: ${error.message}`);
    }
  }

  detach() {
    this.zenoh = null;
  }

  async _query(query) {
    let request;
    try {
      request = decodeAttachment(query.attachment);
    } catch (error) {
      this.gateway.counters.malformed += 1;
      this.gateway.log('warning', `refusing a call of ${this.service} from Zenoh: ${error.message}`);
      query.drop();
      return;
    }
    try {
      const response = await this.gateway.bus.call(this.service, this.type, query.payload, callTimeout(this.gateway, this.service));
      query.reply(this.key, response, encodeAttachment(request.sequence, nowNs(), request.gid));
      this.gateway.counters.calls += 1;
    } catch (error) {
      this.gateway.log('warning', `a call of ${this.service} from Zenoh failed: ${error.message}`);
      query.drop();
    }
  }

  close() {
    if (this.zenoh) this.zenoh.close();
    this.zenoh = null;
  }
}

/** A remote rmw_zenoh server, offered to local clients by the gateway's node. */
export class ServiceProxied {
  constructor(gateway, service, { type }) {
    this.gateway = gateway;
    this.service = service;
    this.type = type;
    this.key = dataKey(gateway.domain, service, type);
    this.sequence = 0n;
    this.gid = randomZid(); // the proxy's client gid: 16 random bytes, as a zid
    this.server = null;
    try {
      this.server = gateway.bus.serve(service, type, (request) => this._request(request));
    } catch (e) {
      gateway.log('error', `cannot offer ${service} locally: ${e.message}`);
    }
  }

  attach() {}

  detach() {}

  async _request(request) {
    const session = this.gateway.session;
    if (!session || !session.up) {
      this.gateway.log('warning', `a local call of ${this.service} waits for no one: the Zenoh session is down`);
      return;
    }
    this.sequence += 1n;
    const replies = await session.get(this.key, {
      payload: request.data, attachment: encodeAttachment(this.sequence, nowNs(), this.gid),
      timeoutMs: callTimeout(this.gateway, this.service),
    });
    const ok = replies.find((r) => r.ok);
    if (!ok) {
      this.gateway.log('warning', `no rmw_zenoh server answered a call of ${this.service}`);
      return;
    }
    this.gateway.counters.calls += 1;
    if (this.server && !this.closed) this.server.respond(request.id, ok.payload);
  }

  close() {
    this.closed = true;
    if (this.server) this.server.close();
  }
}
