// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The ROS view of a bus graph snapshot (`runtime.graph()`): nodes with their
 * endpoints, topics with types and publisher/subscriber counts, services,
 * and actions (recognised by their hidden `_action` services). Names with a
 * part starting with '_' are hidden, as `ros2 topic list` hides them.
 */

import { actionsOf } from './ros_clients.mjs';

const isHidden = (name) => name.split('/').some((part) => part.startsWith('_'));

function fqn(namespace, name) {
  return `${namespace === '/' || !namespace ? '' : namespace}/${name}`;
}

/**
 * @param raw the Runtime's graph snapshot (null before the runtime starts)
 * @param processes Map of the page's processes (to name the process of a node)
 */
export function graphModel(raw, processes) {
  const model = { nodes: [], topics: [], services: [], actions: [] };
  if (!raw) return model;
  const byProcess = new Map();
  for (const p of processes.values()) if (p.handle && p.handle.processId !== undefined) byProcess.set(p.handle.processId, p.label);
  const nodes = new Map();
  for (const n of raw.nodes || []) {
    const name = fqn(n.namespace, n.name);
    nodes.set(n.id ?? name, {
      fqn: name, name: n.name, namespace: n.namespace, process: byProcess.get(n.process) || null,
      hidden: n.name.startsWith('_'), publishers: [], subscriptions: [], services: [], clients: [],
    });
  }
  const topics = new Map();
  const services = new Map();
  const entry = (map, name) => {
    if (!map.has(name)) map.set(name, { name, types: [], publishers: 0, subscribers: 0, servers: 0, clients: 0, hidden: isHidden(name) });
    return map.get(name);
  };
  for (const e of raw.endpoints || []) {
    const isTopic = e.kind === 'publisher' || e.kind === 'subscription';
    const item = entry(isTopic ? topics : services, e.name);
    if (e.type && !item.types.includes(e.type)) item.types.push(e.type);
    const counter = { publisher: 'publishers', subscription: 'subscribers', service: 'servers', client: 'clients' }[e.kind];
    if (counter) item[counter]++;
    const node = nodes.get(e.node);
    const list = { publisher: 'publishers', subscription: 'subscriptions', service: 'services', client: 'clients' }[e.kind];
    if (node && list && !node[list].some((x) => x.name === e.name)) node[list].push({ name: e.name, type: e.type });
  }
  const byName = (a, b) => a.name.localeCompare(b.name);
  model.nodes = [...nodes.values()].filter((n) => !n.hidden).sort((a, b) => a.fqn.localeCompare(b.fqn));
  for (const n of model.nodes) for (const k of ['publishers', 'subscriptions', 'services', 'clients']) n[k].sort(byName);
  model.topics = [...topics.values()].sort(byName);
  model.services = [...services.values()].sort(byName);
  model.actions = actionsOf(model.services);
  return model;
}
