// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * What a Foxglove server advertises, from the bus graph: one channel per
 * published topic (encoding `cdr`, schemaEncoding `ros2msg`, the complete
 * definition as rosbag2 writes it) and one service per served service,
 * with ids that stay the same while the topic keeps its type. The schema
 * texts come from the file the Python launcher wrote
 * (colcon_wasm/launch/foxglove.py, colcon_wasm/ros2msg.py): they are not
 * assembled here.
 *
 * @module bridges/foxglove/catalog
 */

/** The channels and services of the graph, and what changed since the last look. */
export class Catalog {
  /**
   * @param {{messages: object, errors: object}} schemas
   * @param {function(string): void} warn told once per topic whose schema is unknown
   */
  constructor(schemas, warn) {
    this.schemas = schemas;
    this.warn = warn;
    this.channels = new Map(); // id -> channel
    this.services = new Map(); // id -> service
    this._channelIds = new Map(); // topic\ttype -> id
    this._serviceIds = new Map();
    this._nextChannel = 1;
    this._nextService = 1;
    this._warned = new Set();
  }

  _schema(type, what) {
    const text = this.schemas.messages[type];
    if (text !== undefined) return text;
    const key = `${what}\t${type}`;
    if (!this._warned.has(key)) {
      this._warned.add(key);
      this.warn(`${what} is not advertised: ${this.schemas.errors[type]
        || `no type description of ${type} in the install space (build its interface package with colcon build --wasm)`}`);
    }
    return null;
  }

  /**
   * Look at the graph again.
   * @param {object} graph graphModel() of the bus
   * @returns {{advertised: object[], unadvertised: number[], services: object[], unservices: number[]}}
   */
  update(graph) {
    const seen = new Set();
    const advertised = [];
    for (const t of graph.topics) {
      if (!t.publishers || !t.types.length) continue;
      const type = t.types[0];
      const key = `${t.name}\t${type}`;
      let id = this._channelIds.get(key);
      if (id === undefined) {
        const schema = this._schema(type, `topic ${t.name} (${type})`);
        if (schema === null) continue;
        id = this._nextChannel++;
        this._channelIds.set(key, id);
        const channel = { id, topic: t.name, encoding: 'cdr', schemaName: type, schemaEncoding: 'ros2msg', schema };
        this.channels.set(id, channel);
        advertised.push(channel);
      }
      seen.add(id);
    }
    const unadvertised = [];
    for (const [key, id] of this._channelIds) {
      if (!seen.has(id)) {
        this._channelIds.delete(key);
        this.channels.delete(id);
        unadvertised.push(id);
      }
    }
    const seenServices = new Set();
    const services = [];
    for (const s of graph.services) {
      if (!s.servers || !s.types.length) continue;
      const type = s.types[0];
      const key = `${s.name}\t${type}`;
      let id = this._serviceIds.get(key);
      if (id === undefined) {
        const request = this._schema(`${type}_Request`, `service ${s.name} (${type})`);
        const response = request === null ? null : this._schema(`${type}_Response`, `service ${s.name} (${type})`);
        if (request === null || response === null) continue;
        id = this._nextService++;
        this._serviceIds.set(key, id);
        const part = (name, schema) => ({ encoding: 'cdr', schemaName: name, schemaEncoding: 'ros2msg', schema });
        const service = {
          id, name: s.name, type,
          request: part(`${type}_Request`, request), response: part(`${type}_Response`, response),
          requestSchema: request, responseSchema: response,
        };
        this.services.set(id, service);
        services.push(service);
      }
      seenServices.add(id);
    }
    const unservices = [];
    for (const [key, id] of this._serviceIds) {
      if (!seenServices.has(id)) {
        this._serviceIds.delete(key);
        this.services.delete(id);
        unservices.push(id);
      }
    }
    return { advertised, unadvertised, services, unservices };
  }
}

/**
 * The connection graph as Foxglove's connectionGraphUpdate carries it:
 * {topic: [node, ...]} of publishers and subscribers (both with every
 * topic, empty when it has none), {service: [node, ...]}.
 */
export function connectionGraph(graph) {
  const published = new Map();
  const subscribed = new Map();
  const services = new Map();
  const add = (map, name, node) => {
    if (!map.has(name)) map.set(name, []);
    if (!map.get(name).includes(node)) map.get(name).push(node);
  };
  for (const n of graph.nodes) {
    for (const e of n.publishers) add(published, e.name, n.fqn);
    for (const e of n.subscriptions) add(subscribed, e.name, n.fqn);
    for (const e of n.services) add(services, e.name, n.fqn);
  }
  // as foxglove_bridge: every topic has both lists, so a topic whose last
  // subscriber (or publisher) left is sent with an empty one
  for (const name of [...published.keys(), ...subscribed.keys()]) {
    if (!published.has(name)) published.set(name, []);
    if (!subscribed.has(name)) subscribed.set(name, []);
  }
  return { published, subscribed, services };
}

/** What changed between two connectionGraph() results, as a connectionGraphUpdate. */
export function connectionGraphUpdate(before, after) {
  const changed = (a, b) => [...b].filter(([name, ids]) => {
    const old = a && a.get(name);
    return !old || old.join('\n') !== ids.join('\n');
  });
  const removed = (a, b) => (a ? [...a.keys()].filter((name) => !b.has(name)) : []);
  const topicsBefore = before ? new Set([...before.published.keys(), ...before.subscribed.keys()]) : null;
  const topicsAfter = new Set([...after.published.keys(), ...after.subscribed.keys()]);
  return {
    op: 'connectionGraphUpdate',
    publishedTopics: changed(before && before.published, after.published).map(([name, ids]) => ({ name, publisherIds: ids })),
    subscribedTopics: changed(before && before.subscribed, after.subscribed).map(([name, ids]) => ({ name, subscriberIds: ids })),
    advertisedServices: changed(before && before.services, after.services).map(([name, ids]) => ({ name, providerIds: ids })),
    removedTopics: topicsBefore ? [...topicsBefore].filter((n) => !topicsAfter.has(n)) : [],
    removedServices: removed(before && before.services, after.services),
  };
}
