// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The local graph as rmw_zenoh participants see it: one liveliness token per
 * local node and per publisher, subscription, service server and client
 * (the gateway's own node aside), declared when they appear and withdrawn
 * when they go. Ids are per session, as rmw_zenoh's entity counter: a node
 * keeps its id while it lives.
 *
 * @module bridges/zenoh/tokens
 */

import { Kind, tokenKey } from './keys.mjs';

const KINDS = [['publishers', Kind.PUBLISHER], ['subscriptions', Kind.SUBSCRIPTION]];
const SERVICE_KINDS = [['servers', Kind.SERVER], ['clients', Kind.CLIENT]];

/**
 * The tokens of the local entities on one session.
 */
export class LocalTokens {
  /**
   * @param {object} options
   * @param {number} options.domain
   * @param {function(object): boolean} options.skip endpoints and nodes not announced (the gateway's)
   * @param {function(string, string): void} options.log
   */
  constructor({ domain, skip, log }) {
    this.domain = domain;
    this.skip = skip;
    this.log = log;
    this.session = null;
    this.tokens = new Map(); // token key -> handle
    this.ids = new Map(); // gid hex -> entity id
    this.nextId = 0;
  }

  /** Use a new session (after a (re)connect): everything is declared again on the next sync. */
  attach(session) {
    this.session = session;
    this.tokens.clear();
    this.ids.clear();
    this.nextId = 0;
  }

  _id(gid) {
    if (!this.ids.has(gid)) this.ids.set(gid, this.nextId++);
    return this.ids.get(gid);
  }

  /** The token keys the local graph wants now. */
  wanted(raw) {
    const want = new Set();
    const zid = this.session.zid;
    const nodes = new Map();
    for (const n of raw.nodes) {
      if (n.domain !== this.domain || this.skip(n)) continue;
      const nodeId = this._id(n.gid);
      nodes.set(`${n.namespace}\u0000${n.name}`, nodeId);
      want.add(tokenKey({ domain: this.domain, zid, nodeId, id: nodeId, kind: Kind.NODE, enclave: n.enclave || '/', namespace: n.namespace, node: n.name }));
    }
    const endpoint = (entry, e, kind) => {
      const nodeId = nodes.get(`${e.namespace}\u0000${e.node}`);
      if (nodeId === undefined) return;
      want.add(tokenKey({
        domain: this.domain, zid, nodeId, id: this._id(e.gid), kind, enclave: '/', namespace: e.namespace,
        node: e.node, name: entry.name, type: e.type, qos: e.qos,
      }));
    };
    for (const t of raw.topics) {
      if (t.domain !== this.domain) continue;
      for (const [field, kind] of KINDS) for (const e of t[field]) endpoint(t, e, kind);
    }
    for (const s of raw.services) {
      if (s.domain !== this.domain) continue;
      for (const [field, kind] of SERVICE_KINDS) for (const e of s[field]) endpoint(s, e, kind);
    }
    return want;
  }

  /** Declare the tokens of new entities, withdraw those of entities gone. */
  sync(raw) {
    if (!this.session || !this.session.up) return;
    const want = this.wanted(raw);
    for (const [key, handle] of this.tokens) {
      if (!want.has(key)) {
        handle.close();
        this.tokens.delete(key);
      }
    }
    for (const key of want) {
      if (this.tokens.has(key)) continue;
      try {
        this.tokens.set(key, this.session.token(key));
      } catch (error) {
        this.log('warning', `cannot announce ${key}: ${error.message}`);
      }
    }
  }
}
