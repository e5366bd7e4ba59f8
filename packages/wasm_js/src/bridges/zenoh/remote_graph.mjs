// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The remote side of the Zenoh gateway: the rmw_zenoh participants' nodes
 * and endpoints, from their liveliness tokens (history first, then puts and
 * deletes). Tokens of the gateway's own session are left out; tokens that do
 * not parse are counted and named once in the log.
 *
 * @module bridges/zenoh/remote_graph
 */

import { Kind, parseToken } from './keys.mjs';

/** How many different malformed tokens are named in the log at most. */
const MAX_NAMED = 32;

/** Node fqn from namespace and name. */
export function fqn(namespace, node) {
  return `${namespace === '/' || !namespace ? '' : namespace}/${node}`;
}

/**
 * The entities remote rmw_zenoh participants announce.
 */
export class RemoteGraph {
  /**
   * @param {object} options
   * @param {number} options.domain only tokens of this domain
   * @param {function(): string} options.ownZid the gateway session's id (its tokens are local entities)
   * @param {function(string, string): void} options.log
   * @param {function(): void} options.onChange
   */
  constructor({ domain, ownZid, log, onChange }) {
    this.domain = domain;
    this.ownZid = ownZid;
    this.log = log;
    this.onChange = onChange;
    this.entities = new Map(); // token key -> parsed entity
    this.malformed = 0;
    this._named = new Set();
  }

  /** A liveliness sample: put (alive) or delete (gone). */
  sample({ kind, key }) {
    if (kind === 'delete') {
      if (this.entities.delete(key)) this.onChange();
      return;
    }
    let entity;
    try {
      entity = parseToken(key);
    } catch (error) {
      this.malformed += 1;
      // each kind of error named once; a peer that sends ever new bad keys is not remembered
      // past MAX_NAMED (the count goes on)
      if (!this._named.has(error.message) && this._named.size < MAX_NAMED) {
        this._named.add(error.message);
        this.log('warning', `ignoring a liveliness token: ${error.message}`
          + (this._named.size === MAX_NAMED ? ` (the next malformed tokens are counted, not named: ${MAX_NAMED} were)` : ''));
      }
      return;
    }
    if (entity.domain !== this.domain || entity.zid === this.ownZid()) return;
    if (this.entities.has(key)) return;
    this.entities.set(key, entity);
    this.onChange();
  }

  /** Forget everything (the session was lost: the router's history comes again). */
  clear() {
    if (!this.entities.size) return;
    this.entities.clear();
    this.onChange();
  }

  /** Remote endpoints of a kind on a name. */
  endpoints(kind, name) {
    return [...this.entities.values()].filter((e) => e.kind === kind && e.name === name);
  }

  /** The remote graph as the rosbridge client's remote view (remote_graph.mjs of rosbridge merges it). */
  view() {
    const nodes = new Set();
    const topics = new Map();
    const services = new Set();
    for (const e of this.entities.values()) {
      nodes.add(fqn(e.namespace, e.node));
      if (e.kind === Kind.PUBLISHER || e.kind === Kind.SUBSCRIPTION) {
        if (!topics.has(e.name)) topics.set(e.name, e.type);
      } else if (e.kind === Kind.SERVER || e.kind === Kind.CLIENT) {
        services.add(e.name);
      }
    }
    return {
      nodes: [...nodes].sort(),
      topics: [...topics].map(([name, type]) => ({ name, type })).sort((a, b) => (a.name < b.name ? -1 : 1)),
      services: [...services].sort(),
    };
  }
}
