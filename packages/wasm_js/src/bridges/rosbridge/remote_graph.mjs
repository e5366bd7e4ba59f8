// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The remote side of a rosbridge client in the local graph views: the
 * nodes, topics and services the remote server's rosapi lists (polled by
 * the client, `client.remote`) are added to a graph model (page/graph.mjs)
 * with `remote: true` and the server's URL as their process, when the local
 * graph does not have them already.
 *
 * @module bridges/rosbridge/remote_graph
 */

/**
 * Add a client's remote endpoints to a graph model (in place).
 * @param {object} model graphModel()'s result
 * @param {{remote: {nodes: string[], topics: {name, type}[], services: string[]}, displayUrl: string, state: string}} client
 * @returns {object} the model
 */
export function mergeRemote(model, client) {
  if (!client || client.state !== 'connected') return model;
  const where = `remote ${client.displayUrl}`;
  const nodes = new Set(model.nodes.map((n) => n.fqn));
  for (const fqn of client.remote.nodes || []) {
    if (nodes.has(fqn)) continue;
    const i = fqn.lastIndexOf('/');
    model.nodes.push({
      fqn, name: fqn.slice(i + 1), namespace: fqn.slice(0, i) || '/', process: where, pid: -1, remote: true,
      publishers: [], subscriptions: [], services: [], clients: [],
    });
  }
  const topics = new Map(model.topics.map((t) => [t.name, t]));
  for (const t of client.remote.topics || []) {
    const local = topics.get(t.name);
    if (local) local.remoteToo = true;
    else {
      model.topics.push({
        name: t.name, types: [t.type], publishers: 0, subscribers: 0, hidden: false, publisherQos: [], remote: true,
      });
    }
  }
  const services = new Set(model.services.map((s) => s.name));
  for (const name of client.remote.services || []) {
    if (!services.has(name) && !name.startsWith('/rosapi/')) {
      model.services.push({ name, types: [], servers: 0, clients: 0, hidden: false, remote: true });
    }
  }
  const byName = (a, b) => (a.name < b.name ? -1 : a.name > b.name ? 1 : 0);
  model.nodes.sort((a, b) => (a.fqn < b.fqn ? -1 : 1));
  model.topics.sort(byName);
  model.services.sort(byName);
  return model;
}
