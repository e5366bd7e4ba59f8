// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The `_colcon_wasm_bus` functions colcon-wasm's rclpy calls (rclpy/_bus.py):
 * nodes, endpoints, publish and take with cdr.mjs, waits and the graph. A
 * Python node's worker gives them to Pyodide (python_worker.mjs); the build
 * host's rclpy, in a Python launch file, calls them over a socket
 * (launch/host_link_worker.mjs), with the async waits.
 *
 * @module python/bus_module
 */

import {
  KIND_CLIENT, KIND_PUBLISHER, KIND_SERVICE, KIND_SUBSCRIPTION, TakeMode, WAIT_ITEM_WORDS, WaitKind,
} from '../bus_client.mjs';
import { normalizeTypeName } from '../cdr.mjs';
import { HEADER } from '../layout.mjs';

const WAIT_KINDS = {
  subscription: WaitKind.SUBSCRIPTION, service: WaitKind.SERVICE, client: WaitKind.CLIENT, event: WaitKind.EVENT,
};

/**
 * The `_colcon_wasm_bus` module: what rclpy calls (plain values in, plain values out).
 * `stdinPipe`: the process' standard input when it has one (the page's console), else null.
 * `log(stream, text)`: the process' output.
 */
export function busModule(client, registry, context, settle, stdinPipe, log) {
  // the memory of a 'graph' wait item (a graph guard condition at byte 0)
  const graphWord = new Int32Array(new SharedArrayBuffer(16));
  let items = new Int32Array(0);
  /** Fill `items` (and the graph word) for a wait; returns the number of items. */
  const prepareWait = (handles, kinds, eventTypes) => {
    const list = Array.from(handles);
    const kindList = Array.from(kinds);
    const types = eventTypes ? Array.from(eventTypes) : [];
    const n = list.length;
    if (items.length < n * WAIT_ITEM_WORDS) items = new Int32Array(n * WAIT_ITEM_WORDS);
    graphWord.fill(0);
    for (let i = 0; i < n; i++) {
      const o = i * WAIT_ITEM_WORDS;
      const graph = kindList[i] === 'graph';
      const kind = graph ? WaitKind.GUARD_CONDITION : WAIT_KINDS[kindList[i]];
      if (kind === undefined) throw new TypeError(`wait: unknown item kind ${JSON.stringify(kindList[i])}`);
      if (graph) {
        // rcl's graph guard condition (client/wait.mjs): word 0 says "graph", word 2 the version seen
        graphWord[0] = 1;
        graphWord[2] = types[i] || 0;
      }
      items[o] = kind;
      items[o + 1] = graph ? 0 : list[i];
      items[o + 2] = graph ? 0 : types[i] || 0;
      items[o + 3] = 0;
    }
    return n;
  };
  const readyFlags = (n) => {
    const ready = [];
    for (let i = 0; i < n; i++) ready.push(items[i * WAIT_ITEM_WORDS + 3] !== 0);
    return ready;
  };
  return {
    create_node(name, namespace, domain) {
      return client.createNode({ name, namespace, domain, context }).index;
    },
    destroy_node(index) {
      client.destroyNode(index);
    },
    create_publisher(node, topic, type, qosJson) {
      registry.codec(type); // an unknown type fails here, naming its package
      return client.createEndpoint({ kind: KIND_PUBLISHER, node, name: topic, type, qos: JSON.parse(qosJson) }).index;
    },
    create_subscription(node, topic, type, qosJson) {
      registry.codec(type);
      return client.createEndpoint({ kind: KIND_SUBSCRIPTION, node, name: topic, type, qos: JSON.parse(qosJson) }).index;
    },
    destroy_endpoint(index) {
      client.destroyEndpoint(index);
    },
    /** Encode (cdr.mjs) and publish; returns the sequence number. */
    publish(ep, type, value) {
      return client.publish(ep, registry.encode(type, value), 10000);
    },
    /** The next message of a subscription, decoded, or undefined (None in Python). */
    take(ep, type) {
      const data = client.take(ep, TakeMode.MESSAGE);
      return data === null ? undefined : registry.decode(type, data);
    },
    create_service(node, name, type, qosJson) {
      registry.service(type);
      return client.createEndpoint({ kind: KIND_SERVICE, node, name, type, qos: JSON.parse(qosJson) }).index;
    },
    create_client(node, name, type, qosJson) {
      registry.service(type);
      return client.createEndpoint({ kind: KIND_CLIENT, node, name, type, qos: JSON.parse(qosJson) }).index;
    },
    /** The next request of a service: {value, id} (id: for send_response), or undefined. */
    take_request(ep, type) {
      const data = client.take(ep, TakeMode.REQUEST);
      if (data === null) return undefined;
      const i = client.info;
      return { value: registry.decode(type, data), id: { gid: Array.from(i.gid), seqLo: i.reqLo, seqHi: i.reqHi } };
    },
    send_response(ep, id, type, value) {
      return client.sendResponse(ep, id.gid, id.seqLo, id.seqHi, registry.encode(type, value), 10000);
    },
    /** Send a request; returns its sequence number (the response carries it). */
    send_request(ep, type, value) {
      return client.publish(ep, registry.encode(type, value), 10000);
    },
    /** The next response of a client: {value, seq}, or undefined. */
    take_response(ep, type) {
      const data = client.take(ep, TakeMode.RESPONSE);
      if (data === null) return undefined;
      const i = client.info;
      return { value: registry.decode(type, data), seq: i.reqHi * 4294967296 + (i.reqLo >>> 0) };
    },
    server_available(ep) {
      return client.serverAvailable(ep);
    },
    /**
     * Block until a client has a server or `timeoutMs` passed (< 0: forever):
     * sleeps on the bus' graph version, which every graph change bumps.
     */
    wait_for_server(ep, timeoutMs) {
      const i32 = client.bus.i32;
      const end = timeoutMs < 0 ? Infinity : performance.now() + timeoutMs;
      for (;;) {
        const version = Atomics.load(i32, HEADER.GRAPH_VERSION);
        if (client.serverAvailable(ep)) return true;
        const left = end - performance.now();
        if (left <= 0) return false;
        settle();
        Atomics.wait(i32, HEADER.GRAPH_VERSION, version, left);
      }
    },
    matched_count(ep) {
      return client.matchedCount(ep);
    },
    /** A QoS event's status, its changes reset: {changed, total, change, alive, ...}. */
    event_status(ep, type) {
      return client.eventStatus(ep, type, true);
    },
    assert_liveliness(ep) {
      client.assertLiveliness(ep);
    },
    /** The bus' graph version (every graph change bumps it). */
    graph_version() {
      return client.graphVersion();
    },
    /**
     * Block until one of the endpoints has something to take or the timeout
     * passes (< 0: forever). `kinds`: 'subscription', 'service', 'client'
     * or 'event', one per handle, or 'graph' (one at most: ready once the graph
     * version differs from its `eventTypes` entry); `eventTypes`: the EventType
     * of each 'event' (0 for the others). Returns the ready flags, one per handle.
     */
    wait(handles, kinds, timeoutMs, eventTypes) {
      const n = prepareWait(handles, kinds, eventTypes);
      if (n === 0) {
        // nothing to wait for but time: sleep on the doorbell (a stop still ends the worker)
        settle();
        client.register();
        const bell = client.bell();
        client.sleep(bell, timeoutMs < 0 ? Infinity : timeoutMs);
        client.unregister();
        return [];
      }
      client.wait(items, 0, n, timeoutMs, graphWord);
      return readyFlags(n);
    },
    /**
     * wait(), for a process that must go on receiving calls while it waits (the
     * build host's rclpy, launch/host_link_worker.mjs): the same items, checked at each
     * wake-up of the doorbell, which it sleeps on with Atomics.waitAsync.
     * @returns {Promise<boolean[]>}
     */
    async wait_async(handles, kinds, timeoutMs, eventTypes) {
      const end = timeoutMs < 0 ? Infinity : performance.now() + timeoutMs;
      const i32 = client.bus.i32;
      for (;;) {
        client.register();
        const bell = client.bell();
        const n = prepareWait(handles, kinds, eventTypes);
        const ready = n > 0 && client.wait(items, 0, n, 0, graphWord) > 0;
        const left = end - performance.now();
        if (ready || left <= 0) {
          client.unregister();
          return readyFlags(n);
        }
        const sleep = Atomics.waitAsync(i32, client.bellIndex, bell, left === Infinity ? undefined : left);
        if (sleep.async) await sleep.value;
        client.unregister();
      }
    },
    /** wait_for_server(), sleeping with Atomics.waitAsync (see wait_async). */
    async wait_for_server_async(ep, timeoutMs) {
      const i32 = client.bus.i32;
      const end = timeoutMs < 0 ? Infinity : performance.now() + timeoutMs;
      for (;;) {
        const version = Atomics.load(i32, HEADER.GRAPH_VERSION);
        if (client.serverAvailable(ep)) return true;
        const left = end - performance.now();
        if (left <= 0) return false;
        const sleep = Atomics.waitAsync(i32, HEADER.GRAPH_VERSION, version, left === Infinity ? undefined : left);
        if (sleep.async) await sleep.value;
      }
    },
    /**
     * The graph of a domain as one JSON text, for rclpy's graph queries:
     * {nodes: [{name, namespace}], endpoints: [{kind, name, type, node,
     * namespace, gid, qos}]}, kind one of publisher, subscription,
     * service, client, types as `pkg/msg/Name`.
     */
    graph_json(domain) {
      const g = client.graph({ domain });
      return JSON.stringify({
        nodes: g.nodes.map((n) => ({ name: n.name, namespace: n.namespace })),
        endpoints: g.endpoints.map((e) => ({
          kind: e.kindName, name: e.name, type: normalizeTypeName(e.type), node: e.node,
          namespace: e.namespace, gid: Array.from(e.gid), qos: e.qos,
        })),
      });
    },
    /** The type descriptions as one JSON text: {messages, services, actions}. */
    types_json() {
      return JSON.stringify({
        messages: Object.fromEntries(registry.messages),
        services: Object.fromEntries(registry.services),
        actions: Object.fromEntries(registry.actions),
      });
    },
    has_type(type) {
      return registry.has(type);
    },
    /** Whether a read of standard input would return now: bytes or its end are there. */
    stdin_ready() {
      return !!stdinPipe && (stdinPipe.available() > 0 || stdinPipe.closed());
    },
    log,
  };
}
