// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * One Foxglove client of the server (server.mjs): its subscriptions, with
 * a send queue per subscription (send_queue.mjs), the channels it
 * publishes on, its service calls and parameter requests. A request that
 * cannot be read or run gets a status message; the connection stays up.
 *
 * @module bridges/foxglove/session
 */

import { normalizeTypeName } from '../../cdr.mjs';
import { publisherQos } from '../rosbridge/bus_link.mjs';
import { ClientBinary, fetchAssetResponse, messageData, parseClientBinary, serviceCallResponse, StatusLevel } from './protocol.mjs';
import { SendQueues } from './send_queue.mjs';

const dec = new TextDecoder();
const enc = new TextEncoder();

/** A request that is wrong: sent back as an error status. */
class RequestError extends Error {}

const list = (msg, key, what) => {
  if (!Array.isArray(msg[key])) throw new RequestError(`${msg.op} needs '${key}': an array of ${what}`);
  return msg[key];
};

/** A list whose items are JSON objects (subscriptions, channels, parameters). */
const objects = (msg, key, what) => {
  const items = list(msg, key, what);
  if (items.some((x) => x === null || typeof x !== 'object' || Array.isArray(x))) throw new RequestError(`${msg.op} needs '${key}': an array of ${what}`);
  return items;
};

/** A list of strings (parameter names). */
const strings = (msg, key, what) => {
  const items = list(msg, key, what);
  if (items.some((x) => typeof x !== 'string')) throw new RequestError(`${msg.op} needs '${key}': an array of ${what} (strings)`);
  return items;
};

/** The session of one WebSocket connection. */
export class Session {
  /**
   * @param {object} options
   * @param {import('./server.mjs').FoxgloveServer} options.server
   * @param {import('../rosbridge/ws_node.mjs').WebSocketConnection} options.conn
   * @param {number} options.id
   * @param {string} options.peer
   */
  constructor({ server, conn, id, peer }) {
    this.server = server;
    this.conn = conn;
    this.id = id;
    this.peer = peer;
    this.closed = false;
    this.subscriptions = new Map(); // subscription id -> {channelId, stop}
    this.clientChannels = new Map(); // client channel id -> {topic, type, encoding, publisher}
    this.parameterNames = new Set();
    this.graphSubscribed = false;
    this.lastGraph = null;
    this.queues = new SendQueues(conn, {
      maxMessages: server.queueMessages,
      onDrop: (topic, count) => this._dropped(topic, count),
    });
    this._dropReported = new Map();
    this._dropTotals = new Map();
  }

  /** Messages dropped for this client so far, per topic. */
  dropTotals() {
    return Object.fromEntries(this._dropTotals);
  }

  // ------------------------------------------------------------ sending

  /** Send a JSON message. */
  sendJson(obj) {
    if (!this.closed) this.conn.send(JSON.stringify(obj));
  }

  /** Send a status message. */
  status(level, message, id = undefined) {
    const out = { op: 'status', level, message };
    if (id !== undefined) out.id = id;
    this.sendJson(out);
  }

  _dropped(topic) {
    const total = (this._dropTotals.get(topic) || 0) + 1;
    this._dropTotals.set(topic, total);
    const now = Date.now();
    const last = this._dropReported.get(topic) || 0;
    if (now - last < 2000) return;
    this._dropReported.set(topic, now);
    this.status(StatusLevel.WARNING, `${total} message(s) of ${topic} dropped so far: this client reads slower than `
      + `the topic is published (each topic keeps its last ${this.server.queueMessages}; --foxglove-queue N)`, `dropped:${topic}`);
  }

  // ---------------------------------------------------------- receiving

  /** A message from the client (text: JSON, bytes: binary opcodes). */
  receive(data, binary) {
    if (this.closed) return;
    if (binary) {
      this._binary(data instanceof Uint8Array ? data : new Uint8Array(data));
      return;
    }
    let msg;
    try {
      msg = JSON.parse(data);
    } catch (e) {
      this.status(StatusLevel.ERROR, `malformed JSON: ${e.message}; the message was dropped`);
      return;
    }
    if (msg === null || typeof msg !== 'object' || Array.isArray(msg) || typeof msg.op !== 'string') {
      this.status(StatusLevel.ERROR, "a Foxglove message must be a JSON object with an 'op' string; the message was dropped");
      return;
    }
    const handler = this[`op_${msg.op}`];
    if (typeof handler !== 'function') {
      this.status(StatusLevel.ERROR, `unknown op '${msg.op}': this server handles subscribe, unsubscribe, advertise, `
        + 'unadvertise, getParameters, setParameters, subscribeParameterUpdates, unsubscribeParameterUpdates, '
        + 'subscribeConnectionGraph, unsubscribeConnectionGraph and fetchAsset');
      return;
    }
    Promise.resolve().then(() => handler.call(this, msg)).catch((e) => {
      if (!this.closed) this.status(StatusLevel.ERROR, `${msg.op}: ${e.message}`, typeof msg.id === 'string' ? msg.id : undefined);
    });
  }

  _binary(bytes) {
    let m;
    try {
      m = parseClientBinary(bytes);
    } catch (e) {
      this.status(StatusLevel.ERROR, e.message);
      return;
    }
    if (m.op === ClientBinary.MESSAGE_DATA) this._publish(m);
    else this._call(m).catch((e) => this._callFailure(m, e.message));
  }

  // ------------------------------------------------------------- topics

  async op_subscribe(msg) {
    const { catalog, link } = this.server;
    for (const s of objects(msg, 'subscriptions', '{id, channelId}')) {
      if (!Number.isInteger(s.id) || !Number.isInteger(s.channelId)) {
        throw new RequestError('each subscription needs an integer id and channelId');
      }
      if (this.subscriptions.has(s.id)) {
        this.status(StatusLevel.ERROR, `subscription id ${s.id} is in use: unsubscribe it first`);
        continue;
      }
      const channel = catalog.channels.get(s.channelId);
      if (!channel) {
        this.status(StatusLevel.ERROR, `subscribe: no channel ${s.channelId} (it was never advertised, or unadvertised)`);
        continue;
      }
      const entry = { channelId: channel.id, topic: channel.topic, stop: null };
      this.subscriptions.set(s.id, entry);
      const queue = this.queues.open(s.id, channel.topic);
      const stop = await link.listen(channel.topic, channel.schemaName, (batch) => {
        for (const m of batch) {
          const ns = BigInt(Math.round((m.info.sourceTime || Date.now()) * 1e6));
          queue.push(messageData(s.id, ns, m.data));
        }
      });
      if (this.subscriptions.get(s.id) !== entry || this.closed) stop();
      else entry.stop = stop;
    }
  }

  op_unsubscribe(msg) {
    for (const id of list(msg, 'subscriptionIds', 'subscription ids')) this._unsubscribe(id);
  }

  _unsubscribe(id) {
    const entry = this.subscriptions.get(id);
    if (!entry) return;
    this.subscriptions.delete(id);
    if (entry.stop) entry.stop();
    this.queues.close(id);
  }

  /** Channels that are gone: their subscriptions end. */
  channelsRemoved(ids) {
    for (const [subId, entry] of [...this.subscriptions]) if (ids.includes(entry.channelId)) this._unsubscribe(subId);
  }

  async op_advertise(msg) {
    const { converter, link } = this.server;
    for (const c of objects(msg, 'channels', '{id, topic, encoding, schemaName}')) {
      if (!Number.isInteger(c.id) || typeof c.topic !== 'string' || typeof c.schemaName !== 'string') {
        throw new RequestError('each channel needs an integer id, a topic and a schemaName (e.g. std_msgs/msg/String)');
      }
      if (c.encoding !== 'cdr' && c.encoding !== 'json') {
        this.status(StatusLevel.ERROR, `advertise ${c.topic}: encoding '${c.encoding}' is not supported: use cdr or json`);
        continue;
      }
      let type;
      try {
        type = normalizeTypeName(c.schemaName);
        converter.messageType(type);
      } catch (e) {
        this.status(StatusLevel.ERROR, `advertise ${c.topic}: unknown type '${c.schemaName}': ${e.message}`);
        continue;
      }
      if (this.clientChannels.has(c.id)) this._unadvertise(c.id);
      const entry = { topic: c.topic, type, encoding: c.encoding, publisher: link.publisher(c.topic, type, publisherQos()) };
      this.clientChannels.set(c.id, entry);
      entry.publisher.catch((e) => {
        this.clientChannels.delete(c.id);
        this.status(StatusLevel.ERROR, `advertise ${c.topic}: ${e.message}`);
      });
    }
  }

  op_unadvertise(msg) {
    for (const id of list(msg, 'channelIds', 'channel ids')) this._unadvertise(id);
  }

  _unadvertise(id) {
    const entry = this.clientChannels.get(id);
    if (!entry) return;
    this.clientChannels.delete(id);
    entry.publisher.then((p) => p.release(), () => {});
  }

  _publish({ channelId, data }) {
    const entry = this.clientChannels.get(channelId);
    if (!entry) {
      this.status(StatusLevel.ERROR, `message data for channel ${channelId}, which this client has not advertised`);
      return;
    }
    let bytes = data.slice();
    if (entry.encoding === 'json') {
      const { converter, registry } = this.server;
      try {
        bytes = registry.encode(entry.type, converter.fromJson(entry.type, JSON.parse(dec.decode(data))));
      } catch (e) {
        this.status(StatusLevel.ERROR, `a JSON message on ${entry.topic} does not fit ${entry.type}: ${e.message}`);
        return;
      }
    }
    entry.publisher.then((p) => p.publish(bytes)).catch((e) => {
      this.status(StatusLevel.ERROR, `publishing on ${entry.topic} failed: ${e.message}`);
    });
  }

  // ----------------------------------------------------------- services

  async _call({ serviceId, callId, encoding, data }) {
    const { catalog, link, registry, converter } = this.server;
    const service = catalog.services.get(serviceId);
    if (!service) throw new Error(`no service ${serviceId} (never advertised, or unadvertised)`);
    const requestType = service.request.schemaName;
    const responseType = service.response.schemaName;
    let request = data.slice();
    if (encoding === 'json') {
      request = registry.encode(requestType, converter.fromJson(requestType, JSON.parse(dec.decode(data) || '{}')));
    } else if (encoding !== 'cdr') {
      throw new Error(`encoding '${encoding}' is not supported: use cdr or json`);
    }
    const response = await link.call(service.name, service.type, request, this.server.callTimeoutMs);
    if (this.closed) return;
    const out = encoding === 'json'
      ? enc.encode(converter.jsonWriter(responseType)(registry.decode(responseType, response)))
      : response;
    this.conn.send(serviceCallResponse(serviceId, callId, encoding, out));
  }

  _callFailure({ serviceId, callId }, message) {
    this.sendJson({ op: 'serviceCallFailure', serviceId, callId, message });
  }

  // --------------------------------------------------------- parameters

  _parameters() {
    const p = this.server.parameters;
    if (!p.available) throw new RequestError('parameters need the rcl_interfaces type descriptions: build rcl_interfaces with colcon build --wasm');
    return p;
  }

  async op_getParameters(msg) {
    const names = strings(msg, 'parameterNames', 'parameter names (/node.param)');
    const { parameters, errors } = await this._parameters().get(names);
    for (const e of errors) this.status(StatusLevel.ERROR, `getParameters: ${e}`, typeof msg.id === 'string' ? msg.id : undefined);
    const out = { op: 'parameterValues', parameters };
    if (msg.id !== undefined) out.id = msg.id;
    this.sendJson(out);
  }

  async op_setParameters(msg) {
    const params = objects(msg, 'parameters', '{name, value}');
    if (params.some((x) => typeof x.name !== 'string')) throw new RequestError("setParameters needs a 'name' string in each parameter");
    const p = this._parameters();
    const errors = await p.set(params);
    for (const e of errors) this.status(StatusLevel.ERROR, `setParameters: ${e}`, typeof msg.id === 'string' ? msg.id : undefined);
    if (msg.id !== undefined) {
      const { parameters } = await p.get(params.map((x) => x.name));
      this.sendJson({ op: 'parameterValues', parameters, id: msg.id });
    }
  }

  op_subscribeParameterUpdates(msg) {
    this._parameters();
    for (const n of strings(msg, 'parameterNames', 'parameter names')) this.parameterNames.add(n);
    this.server.watchParameters(); // followed from the start; again if that failed
  }

  op_unsubscribeParameterUpdates(msg) {
    for (const n of list(msg, 'parameterNames', 'parameter names')) this.parameterNames.delete(n);
  }

  /** Parameters changed (from /parameter_events). */
  parametersChanged(changed) {
    const mine = changed.filter((p) => this.parameterNames.has(p.name));
    if (mine.length) this.sendJson({ op: 'parameterValues', parameters: mine });
  }

  // ---------------------------------------------------- connection graph

  op_subscribeConnectionGraph() {
    this.graphSubscribed = true;
    this.lastGraph = null;
    this.server.sendGraph(this);
  }

  op_unsubscribeConnectionGraph() {
    this.graphSubscribed = false;
  }

  // ------------------------------------------------------------- assets

  /** fetchAsset: the file of a package:// URI, or an error response with the same requestId. */
  async op_fetchAsset(msg) {
    if (!Number.isInteger(msg.requestId) || msg.requestId < 0) {
      throw new RequestError("fetchAsset needs an integer 'requestId' (the response carries it)");
    }
    const assets = this.server.assets;
    let data = null;
    let error = null;
    if (!assets.available) {
      error = `fetchAsset ${msg.uri}: this server has no install space to serve assets from (no 'assets' capability)`;
    } else {
      try {
        data = await assets.fetch(msg.uri);
      } catch (e) {
        error = e.message;
      }
    }
    if (!this.closed) this.conn.send(fetchAssetResponse(msg.requestId, error, data || undefined));
  }

  /** End the session: subscriptions, publishers. */
  end() {
    if (this.closed) return;
    this.closed = true;
    for (const id of [...this.subscriptions.keys()]) this._unsubscribe(id);
    for (const id of [...this.clientChannels.keys()]) this._unadvertise(id);
    this.queues.closeAll();
  }
}
