// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * A Foxglove WebSocket protocol server over the bus, in Node.js
 * (`colcon-wasm run|launch --foxglove [HOST:]PORT`): Foxglove and
 * Lichtblick see every topic as a channel (`cdr`, `ros2msg`, the complete
 * definition), get the CDR bytes of the bus as they are, publish
 * (cdr or json), call services, get, set and watch the nodes' parameters,
 * follow the connection graph, get the time of `/clock` when it is
 * published, and fetch `package://` assets (meshes of a URDF) from the
 * install space. The WebSocket, the bus link, the JSON to CDR converter and
 * the parameter client are the rosbridge bridge's (../rosbridge/).
 *
 * @module bridges/foxglove/server
 */

import http from 'node:http';

import { BusLink } from '../rosbridge/bus_link.mjs';
import { Converter } from '../rosbridge/convert.mjs';
import { closeAll, listen } from '../common/listen.mjs';
import { acceptWebSocket } from '../rosbridge/ws_node.mjs';
import { Assets } from './assets.mjs';
import { loadSchemas } from '../common/schema_texts.mjs';
import { Catalog, connectionGraph, connectionGraphUpdate } from './catalog.mjs';
import { Parameters } from './parameters.mjs';
import { Capability, StatusLevel, SUBPROTOCOLS, timeMessage } from './protocol.mjs';
import { Session } from './session.mjs';

/** A server that could not start (the port is taken, ...): the message says what to do. */
export class FoxgloveError extends Error {
  constructor(message) {
    super(message);
    this.name = 'FoxgloveError';
  }
}

/** The Foxglove server of one Runtime. */
export class FoxgloveServer {
  /**
   * Start listening.
   * @param {object} options
   * @param {import('../../runtime.mjs').Runtime} options.runtime
   * @param {import('../../cdr.mjs').TypeRegistry} options.registry the build's type descriptions
   * @param {string} [options.schemas] the JSON file of schema texts (colcon_wasm/launch/foxglove.py)
   * @param {Object<string, string>} [options.shares] package name -> share folder, for fetchAsset
   * @param {string} [options.host='127.0.0.1']
   * @param {number} [options.port=8765] 0 picks a free port
   * @param {number} [options.queueMessages=10] per subscription, before the oldest is dropped
   * @param {function(string, string): void} [options.log] (level, text)
   * @returns {Promise<FoxgloveServer>}
   * @throws {FoxgloveError} when the port cannot be had
   */
  static async start(options) {
    const server = new FoxgloveServer(options);
    await server._listen();
    return server;
  }

  constructor({ runtime, registry, schemas = null, shares = null, host = '127.0.0.1', port = 8765, queueMessages = 10, log = null }) {
    this.runtime = runtime;
    this.registry = registry;
    this.converter = new Converter(registry);
    this.host = host;
    this.port = port;
    this.queueMessages = queueMessages;
    this.callTimeoutMs = 10000;
    this.log = log || (() => {});
    this.sessions = new Set();
    this.sessionId = String(Date.now());
    this._nextId = 1;
    this.catalog = new Catalog(loadSchemas(schemas), (text) => this.log('warning', text));
    this.assets = new Assets(shares);
    this.link = null;
    this.parameters = null;
    this._clock = null;
    this._paramWatch = null;
    this._graphTimer = null;
    this.http = http.createServer((req, res) => {
      res.writeHead(426, { 'Content-Type': 'text/plain; charset=utf-8', Upgrade: 'websocket' });
      res.end('this is a Foxglove WebSocket server: open it in Foxglove or Lichtblick (Open connection, Foxglove WebSocket, ws://)\n');
    });
    this.http.on('upgrade', (req, socket, head) => this._upgrade(req, socket, head));
  }

  async _listen() {
    const tools = await this.runtime.tools();
    this.link = await BusLink.create({ runtime: this.runtime, tools, nodeName: 'foxglove_bridge' });
    this.parameters = new Parameters(this.link, this.registry);
    // from the start, not at a client's first subscribeParameterUpdates: a change made
    // right after it would come before the subscription is made
    if (this.parameters.available) this.watchParameters();
    this.runtime.onGraphChange(() => this._graphChanged());
    this.port = await listen(this.http, {
      host: this.host, port: this.port, option: '--foxglove', other: 'another Foxglove server or foxglove_bridge', ErrorClass: FoxgloveError,
    });
    this._refresh();
  }

  /** ws://host:port of the server. */
  get url() {
    const host = this.host.includes(':') ? `[${this.host}]` : this.host;
    return `ws://${host}:${this.port}`;
  }

  _capabilities() {
    const caps = [Capability.clientPublish, Capability.services, Capability.connectionGraph];
    if (this.parameters.available) caps.push(Capability.parameters, Capability.parametersSubscribe);
    if (this._clock) caps.push(Capability.time);
    if (this.assets.available) caps.push(Capability.assets);
    return caps;
  }

  _upgrade(request, socket, head) {
    const peer = `${socket.remoteAddress}:${socket.remotePort}`;
    const conn = acceptWebSocket(request, socket, head, {
      protocols: SUBPROTOCOLS, what: 'a Foxglove WebSocket server',
      refusal: `this Foxglove WebSocket server speaks the subprotocols ${SUBPROTOCOLS.join(' and ')}: offer one of them`,
    });
    if (!conn) {
      this.log('warning', `refused a client from ${peer}: it offered none of the subprotocols ${SUBPROTOCOLS.join(', ')}`);
      return;
    }
    this.attach(conn, peer);
  }

  /**
   * Serve one client on an open connection (after the subprotocol was
   * agreed): its messages go to the session's `receive()` (also the entry
   * point of tests/fuzz's driver); the server's greeting goes out first.
   * @param {object} conn a WebSocket (send, close, bufferedAmount, onmessage, onclose; `protocol`)
   * @param {string} peer the client's address, for logs
   * @returns {Session}
   */
  attach(conn, peer) {
    const session = new Session({ server: this, conn, id: this._nextId++, peer });
    this.sessions.add(session);
    this.log('info', `client ${session.id} connected from ${peer} (${conn.protocol}; ${this.sessions.size} connected)`);
    conn.onmessage = (e) => session.receive(e.data, e.binary);
    conn.onerror = () => {};
    conn.onclose = (e) => {
      this.sessions.delete(session);
      const drops = Object.entries(session.dropTotals()).filter(([, n]) => n > 0);
      session.end();
      this.log('info', `client ${session.id} disconnected (${e.code}${e.reason ? ` ${e.reason}` : ''}; ${this.sessions.size} connected)`
        + (drops.length ? `; dropped for it: ${drops.map(([t, n]) => `${n} of ${t}`).join(', ')}` : ''));
    };
    session.sendJson({
      op: 'serverInfo', name: 'colcon-wasm', capabilities: this._capabilities(),
      supportedEncodings: ['cdr', 'json'], metadata: { ROS_DISTRO: 'humble', bridge: 'colcon-wasm --foxglove' },
      sessionId: this.sessionId,
    });
    this._refresh();
    session.sendJson({ op: 'advertise', channels: [...this.catalog.channels.values()] });
    session.sendJson({ op: 'advertiseServices', services: [...this.catalog.services.values()] });
    return session;
  }

  _graphChanged() {
    if (this._graphTimer) return;
    this._graphTimer = setTimeout(() => {
      this._graphTimer = null;
      this._refresh();
    }, 30);
  }

  /** Look at the graph: new and gone channels and services, the connection graph, /clock. */
  _refresh() {
    const graph = this.link.graph();
    const { advertised, unadvertised, services, unservices } = this.catalog.update(graph);
    for (const s of this.sessions) {
      if (unadvertised.length) {
        s.channelsRemoved(unadvertised);
        s.sendJson({ op: 'unadvertise', channelIds: unadvertised });
      }
      if (advertised.length) s.sendJson({ op: 'advertise', channels: advertised });
      if (unservices.length) s.sendJson({ op: 'unadvertiseServices', serviceIds: unservices });
      if (services.length) s.sendJson({ op: 'advertiseServices', services });
      if (s.graphSubscribed) this.sendGraph(s, graph);
    }
    const clock = graph.topics.find((t) => t.name === '/clock' && t.publishers && t.types[0] === 'rosgraph_msgs/msg/Clock');
    if (clock && !this._clock && this.registry.has('rosgraph_msgs/msg/Clock')) this._watchClock();
  }

  /** Send a client what changed in the connection graph since it last heard. */
  sendGraph(session, graph = this.link.graph()) {
    const now = connectionGraph(graph);
    const update = connectionGraphUpdate(session.lastGraph, now);
    session.lastGraph = now;
    const empty = ['publishedTopics', 'subscribedTopics', 'advertisedServices', 'removedTopics', 'removedServices']
      .every((k) => update[k].length === 0);
    if (!empty || !session.graphSentOnce) session.sendJson(update);
    session.graphSentOnce = true;
  }

  _watchClock() {
    const type = 'rosgraph_msgs/msg/Clock';
    this._clock = this.link.listen('/clock', type, (batch) => {
      const last = batch[batch.length - 1];
      let t;
      try {
        t = this.registry.decode(type, last.data).clock;
      } catch {
        return;
      }
      const frame = timeMessage(BigInt(t.sec) * 1000000000n + BigInt(t.nanosec));
      for (const s of this.sessions) s.conn.send(frame);
    });
    this._clock.catch((e) => this.log('warning', `cannot follow /clock: ${e.message}`));
    this.log('info', '/clock is published: clients connecting from now on get the time capability');
  }

  /** Follow /parameter_events for the clients that subscribe to parameter updates. */
  watchParameters() {
    if (this._paramWatch) return;
    this._paramWatch = this.parameters.watch((changed) => {
      for (const s of this.sessions) s.parametersChanged(changed);
    });
    this._paramWatch.catch((e) => {
      this._paramWatch = null;
      for (const s of this.sessions) if (s.parameterNames.size) s.status(StatusLevel.WARNING, `cannot follow /parameter_events: ${e.message}`);
    });
  }

  /** Counters: clients, and per client what was sent and dropped per topic. */
  stats() {
    return { connected: this.sessions.size, sessions: [...this.sessions].map((s) => ({ id: s.id, peer: s.peer, drops: s.dropTotals() })) };
  }

  /** Stop listening and close every client (the closing handshake, at most `graceMs`). */
  async close(graceMs = 1000) {
    await closeAll(this.http, this.sessions, graceMs);
    for (const w of [this._clock, this._paramWatch]) if (w) w.then((stop) => stop(), () => {});
  }
}
