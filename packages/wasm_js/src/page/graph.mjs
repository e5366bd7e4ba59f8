// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The ROS view of a Runtime graph snapshot (`runtime.graph()`: nodes, and
 * topics and services with their endpoints): nodes with their endpoints,
 * topics with types and publisher/subscriber counts, services, and actions
 * (recognised by their hidden `_action` services). Names with a part that
 * starts with '_' are hidden, as `ros2 topic list` hides them. The tools
 * process's own node is left out (and the Zenoh gateway's).
 */

import { actionsOf } from './ros_clients.mjs';

const isHidden = (name) => name.split('/').some((part) => part.startsWith('_'));

/** The fully qualified name of a node. */
export function nodeName(namespace, name) {
  return `${namespace === '/' || !namespace ? '' : namespace}/${name}`;
}

/**
 * @param raw the Runtime's graph snapshot (null before the runtime starts)
 * @param {object} [options]
 * @param {number} [options.toolsPid] the bus process id of the tools process
 * @param {number[]} [options.hiddenPids] other processes left out as the tools process is
 *   (the Zenoh gateway's)
 */
export function graphModel(raw, { toolsPid, hiddenPids = [] } = {}) {
  const model = { nodes: [], topics: [], services: [], actions: [] };
  if (!raw) return model;
  const hidden = new Set(hiddenPids);
  if (toolsPid !== undefined) hidden.add(toolsPid);
  const nodes = new Map();
  for (const n of raw.nodes || []) {
    if (hidden.has(n.pid)) continue;
    const fqn = nodeName(n.namespace, n.name);
    nodes.set(fqn, {
      fqn, name: n.name, namespace: n.namespace, process: n.process || null, pid: n.pid,
      publishers: [], subscriptions: [], services: [], clients: [],
    });
  }
  const attach = (endpoints, list, name) => {
    let count = 0;
    for (const e of endpoints) {
      if (hidden.has(e.pid)) continue;
      count++;
      const node = nodes.get(nodeName(e.namespace, e.node));
      if (node && !node[list].some((x) => x.name === name)) node[list].push({ name, type: e.type });
    }
    return count;
  };
  for (const t of raw.topics || []) {
    const publishers = attach(t.publishers, 'publishers', t.name);
    const subscribers = attach(t.subscriptions, 'subscriptions', t.name);
    if (publishers + subscribers === 0) continue;
    const publisherQos = t.publishers.filter((e) => !hidden.has(e.pid))
      .map((e) => e.qos).filter(Boolean);
    model.topics.push({
      name: t.name, types: t.types, publishers, subscribers, hidden: isHidden(t.name), publisherQos,
    });
  }
  for (const s of raw.services || []) {
    const servers = attach(s.servers, 'services', s.name);
    const clients = attach(s.clients, 'clients', s.name);
    if (servers + clients === 0) continue;
    model.services.push({ name: s.name, types: s.types, servers, clients, hidden: isHidden(s.name) });
  }
  const byName = (a, b) => (a.name < b.name ? -1 : a.name > b.name ? 1 : 0);
  model.nodes = [...nodes.values()].sort((a, b) => (a.fqn < b.fqn ? -1 : 1));
  for (const n of model.nodes) for (const k of ['publishers', 'subscriptions', 'services', 'clients']) n[k].sort(byName);
  model.topics.sort(byName);
  model.services.sort(byName);
  model.actions = actionsOf(model.services);
  return model;
}

/**
 * The QoS a tool subscribes with to hear every publisher of a topic, as
 * `ros2 topic echo` chooses it: BEST_EFFORT when a publisher is best effort,
 * TRANSIENT_LOCAL when every publisher keeps its history for late joiners,
 * else RELIABLE and VOLATILE; KEEP_LAST with a depth for bursts.
 */
export function subscriptionQos(publisherQos = [], depth = 100) {
  const all = (field, value) => publisherQos.length > 0 && publisherQos.every((q) => q[field] === value);
  return {
    history: 'keep_last',
    depth,
    reliability: publisherQos.some((q) => q.reliability === 'best_effort') ? 'best_effort' : 'reliable',
    durability: all('durability', 'transient_local') ? 'transient_local' : 'volatile',
  };
}
