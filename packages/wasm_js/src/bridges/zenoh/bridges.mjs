// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * What the Zenoh gateway (gateway.mjs) carries, one object per topic or
 * service and direction, each restarted on a new session:
 * - TopicOut: local publishers -> a Zenoh publisher on the rmw_zenoh key;
 *   each sample carries the attachment (the local publisher's sequence
 *   number, source time and gid). While there is no session, RELIABLE
 *   messages wait (bounded in bytes, oldest dropped and counted), sent in
 *   order once the session is back; BEST_EFFORT ones are counted as lost.
 * - TopicIn: local subscriptions <- a Zenoh subscriber; CDR bytes published
 *   locally by the gateway's node.
 * - ServiceServed: a local server answers rmw_zenoh clients' queries.
 * - ServiceProxied: local clients reach a remote rmw_zenoh server through a
 *   local server of the gateway's node.
 *
 * @module bridges/zenoh/bridges
 */

import { gidHex } from '../rosbridge/bus_link.mjs';
import { dataKey, decodeAttachment, encodeAttachment, gidBytes, nowNs } from './keys.mjs';
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

/** Local publishers' messages, to Zenoh. */
export class TopicOut {
  constructor(gateway, topic, { type, publishers }) {
    this.gateway = gateway;
    this.topic = topic;
    this.type = type;
    this.publishers = publishers;
    this.key = dataKey(gateway.domain, topic, type);
    this.queue = [];
    this.queuedBytes = 0;
    this.sequences = new Map(); // local publisher gid (bytes) -> last sequence sent
    this.gids = new Map(); // local publisher gid words -> bytes
    this.zenoh = null;
    this.stop = null;
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
    const onBatch = (batch) => {
      try {
        this._local(batch);
      } catch (error) {
        gateway.log('error', `cannot send ${topic} to Zenoh: ${error.stack || error.message}`);
      }
    };
    gateway.log('debug', `${topic}: listening with ${JSON.stringify(tapQos)}`);
    gateway.link.listen(topic, type, onBatch, tapQos).then((stop) => {
      if (this.closed) stop();
      else this.stop = stop;
    }, (e) => gateway.log('error', `cannot bridge ${topic} to Zenoh: ${e.message}`));
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
    this._batched(waiting.length, () => { for (const m of waiting) this._put(m); });
  }

  /** Run `fn`, which sends `count` messages, in one zenoh-pico batch when there are several. */
  _batched(count, fn) {
    const session = this.gateway.session;
    if (count > 1 && this.zenoh && session) session.batch(fn);
    else fn();
  }

  detach() {
    this.zenoh = null;
    clearTimeout(this.graceTimer);
  }

  _local(batch) {
    this._batched(batch.length, () => this._send(batch));
  }

  _send(batch) {
    for (const m of batch) {
      const gid = this._gid(m.info.publisherGid);
      const seq = (this.sequences.get(gid) || 0) + 1;
      this.sequences.set(gid, seq);
      const entry = { data: m.data, seq, timeNs: BigInt(Math.round(m.info.sourceTime * 1e6)), gid };
      if (this.zenoh && !this.holding && this.gateway.session && this.gateway.session.up) this._put(entry);
      else this._wait(entry, Boolean(this.holding && this.zenoh));
    }
  }

  /** A local publisher's gid (4 words) as 16 bytes, computed once per publisher. */
  _gid(words) {
    const key = `${words[0]},${words[1]},${words[2]},${words[3]}`;
    let bytes = this.gids.get(key);
    if (!bytes) {
      bytes = gidBytes(gidHex(words));
      this.gids.set(key, bytes);
    }
    return bytes;
  }

  _put(entry) {
    const ret = this.zenoh.put(entry.data, encodeAttachment(entry.seq, entry.timeNs, entry.gid));
    if (!this.announced) {
      this.announced = true;
      this.gateway.log('debug', `${this.topic}: first message out (${entry.data.length} bytes, zenoh-pico ${ret})`);
    }
    if (ret === 0) this.gateway.counters.sent += 1;
    else this._wait(entry);
  }

  _wait(entry, briefly = false) {
    // BEST_EFFORT messages wait only for a new publisher to match, not for a session
    if (!this.reliable && !briefly) {
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
    if (this.stop) this.stop();
    if (this.zenoh) this.zenoh.close();
    this.zenoh = null;
  }
}

/** Remote publishers' messages, to local subscriptions. */
export class TopicIn {
  constructor(gateway, topic, { type, qos }) {
    this.gateway = gateway;
    this.topic = topic;
    this.type = type;
    this.qos = qos;
    this.key = dataKey(gateway.domain, topic, type);
    this.zenoh = null;
    this.ready = gateway.link.publisher(topic, type, qos);
    this.ready.then((p) => { if (this.closed) p.release(); }, (e) => gateway.log('error', `cannot publish ${topic} locally: ${e.message}`));
    this.noAttachment = 0;
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
    if (sample.kind !== 'put' || this.closed) return;
    try {
      decodeAttachment(sample.attachment);
    } catch (error) {
      // rmw_zenoh drops samples without its attachment; so does the gateway, and says so once per topic
      this.gateway.counters.malformed += 1;
      if (!this.noAttachment++) this.gateway.log('warning', `dropping a sample on ${this.topic} from Zenoh: ${error.message}`);
      return;
    }
    this.gateway.counters.received += 1;
    this.ready.then((p) => p.publish(sample.payload)).catch((e) => this.gateway.log('error', `cannot publish ${this.topic} locally: ${e.message}`));
  }

  close() {
    this.closed = true;
    if (this.zenoh) this.zenoh.close();
    this.ready.then((p) => p.release(), () => {});
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
      const response = await this.gateway.link.call(this.service, this.type, query.payload, callTimeout(this.gateway, this.service));
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
    this.server = gateway.link.serve(service, type, (requests) => { for (const r of requests) this._request(r); });
    this.server.catch((e) => gateway.log('error', `cannot offer ${service} locally: ${e.message}`));
  }

  attach() {}

  detach() {}

  async _request(request) {
    const server = await this.server;
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
    await server.respond(request.id, ok.payload);
  }

  close() {
    this.server.then((s) => s.close(), () => {});
  }
}
