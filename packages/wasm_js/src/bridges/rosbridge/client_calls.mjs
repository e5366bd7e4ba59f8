// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The services and actions of the rosbridge client (client.mjs), which
 * mixes these methods into RosbridgeClient: a local service or action
 * server advertised remotely (remote calls and goals made locally), and a
 * remote one served locally for local callers (calls and goals made
 * remotely, retried while the remote service does not exist yet).
 *
 * @module bridges/rosbridge/client_calls
 */

import { normalizeTypeName } from '../../cdr.mjs';
import { ActionClient } from '../../page/ros_clients.mjs';
import { BusActionServer } from './action_server.mjs';
import { parseJson, stringifyJson } from './json.mjs';

/** Methods of RosbridgeClient (`this` is the client). */
export class ClientCalls {
  // ----------------------------------------------------------- services

  _startServed(service, { type }) {
    const s = { service, type };
    this._advertiseService(s);
    return s;
  }

  _advertiseService(s) {
    this._send({ op: 'advertise_service', service: s.service, type: s.type });
  }

  _stopServed(s) {
    this._send({ op: 'unadvertise_service', service: s.service });
  }

  async _remoteCall(msg) {
    const s = this.served.get(msg.service);
    const reply = (values, result) => this._send({ op: 'service_response', id: msg.id, service: msg.service, values, result });
    if (!s) {
      reply(`${msg.service} is not served here`, false);
      return;
    }
    try {
      const entry = this.registry.service(s.type);
      const request = this.registry.encode(entry.request, this.converter.fromJson(entry.request, msg.args || {}));
      const response = await this.link.call(msg.service, s.type, request, this.limits.callTimeoutMs);
      const json = this.converter.jsonWriter(entry.response)(this.registry.decode(entry.response, response));
      this._sendRaw(`{"op":"service_response","id":${stringifyJson(msg.id)},"service":${JSON.stringify(msg.service)},"values":${json},"result":true}`);
    } catch (e) {
      reply(e.message, false);
    }
  }

  _startProxied(service, { type }) {
    const p = { service, type, server: null, waiting: [] };
    const entry = this.registry.service(type);
    p.ready = this.link.serve(service, type, (requests) => {
      for (const r of requests) {
        p.waiting.push({ r, at: Date.now() });
        if (this.connected) this._sendWaitingCalls(p);
      }
    }, undefined);
    p.ready.then((server) => {
      if (this.proxied.get(service) !== p) server.close().catch(() => {});
      else p.server = server;
    }, (e) => this.log('error', `cannot serve ${service} for ${this.displayUrl}: ${e.message}`));
    p.entry = entry;
    return p;
  }

  _sendWaitingCalls(p) {
    const waiting = p.waiting.splice(0);
    for (const { r, at } of waiting) {
      if (Date.now() - at > this.limits.callTimeoutMs) {
        this.counters.lost++;
        this.log('warning', `a call of ${p.service} waited more than ${this.limits.callTimeoutMs} ms for ${this.displayUrl} and was dropped`);
        continue;
      }
      let args;
      try {
        args = parseJson(this.converter.jsonWriter(p.entry.request)(this.registry.decode(p.entry.request, r.data)));
      } catch (e) {
        this.log('error', `a call of ${p.service} could not be decoded: ${e.message}`);
        continue;
      }
      this._call(p.service, args).then(async (values) => {
        const bytes = this.registry.encode(p.entry.response, this.converter.fromJson(p.entry.response, values || {}));
        const server = p.server || await p.ready;
        await server.respond(r.id, bytes);
      }, (e) => {
        // the remote server may not be there yet: try again within the caller's time
        if (/does not exist/.test(e.message) && Date.now() - at + 250 < this.limits.callTimeoutMs) {
          const t = setTimeout(() => {
            p.waiting.push({ r, at });
            if (this.connected) this._sendWaitingCalls(p);
          }, 250);
          if (t.unref) t.unref();
          return;
        }
        this.log('warning', `${p.service} on ${this.displayUrl} failed: ${e.message} (the local caller gets no response)`);
      });
    }
  }

  _stopProxied(p) {
    p.ready.then((s) => s.close(), () => {}).catch(() => {});
  }

  // ----------------------------------------------------------- actions

  _startActionServed(action, { type }) {
    const a = { action, type };
    this._advertiseAction(a);
    return a;
  }

  _advertiseAction(a) {
    this._send({ op: 'advertise_action', action: a.action, type: a.type });
  }

  /** A remote client's goal for a local action server. */
  async _remoteGoal(msg) {
    const a = this.actionsServed.get(msg.action);
    const fail = (text) => this._send({ op: 'action_result', id: msg.id, action: msg.action, values: text, status: 0, result: false });
    if (!a) {
      fail(`${msg.action} is not served here`);
      return;
    }
    const spec = this.registry.action(a.type);
    const client = new ActionClient(this.link.clientBus(), this.registry, msg.action, a.type);
    let sent;
    try {
      sent = await client.sendGoal(this.converter.fromJson(spec.goal, msg.args || {}), {
        timeoutMs: this.limits.callTimeoutMs,
        onFeedback: (value) => this._sendRaw(`{"op":"action_feedback","id":${stringifyJson(msg.id)},"action":${JSON.stringify(msg.action)},"values":${this.converter.jsonWriter(spec.feedback)(value)}}`),
      });
    } catch (e) {
      fail(e.message);
      return;
    }
    if (!sent.accepted) {
      fail('Action goal was rejected');
      return;
    }
    this.remoteGoals.set(String(msg.id), sent.handle);
    try {
      const r = await sent.result;
      this._sendRaw(`{"op":"action_result","id":${stringifyJson(msg.id)},"action":${JSON.stringify(msg.action)},"values":${this.converter.jsonWriter(spec.result)(r.result)},"status":${r.status},"result":true}`);
    } catch (e) {
      fail(e.message);
    } finally {
      this.remoteGoals.delete(String(msg.id));
    }
  }

  _remoteCancel(msg) {
    const handle = this.remoteGoals.get(String(msg.id));
    if (handle) handle.cancel(this.limits.callTimeoutMs).catch((e) => this.log('warning', `cancel of ${msg.action}: ${e.message}`));
  }

  /** A remote action server, served locally for local action clients. */
  _startActionProxied(action, { type }) {
    const full = normalizeTypeName(type).replace('/msg/', '/action/');
    const a = { action, type: full, server: null };
    a.server = new BusActionServer({
      link: this.link, registry: this.registry, converter: this.converter, action, full, spec: this.registry.action(full),
      onGoal: (rid, goalJson) => {
        if (!this._sendRaw(`{"op":"send_action_goal","id":${JSON.stringify(rid)},"action":${JSON.stringify(action)},"action_type":${JSON.stringify(full)},"args":${goalJson},"feedback":true}`)) {
          const g = a.server.byRid.get(rid);
          if (g) a.server.finish(g, 6, {}).catch(() => {});
          this.log('warning', `a goal of ${action} was aborted: ${this.displayUrl} is not connected`);
        }
      },
      onCancel: (rid) => this._send({ op: 'cancel_action_goal', id: rid, action }),
      onError: (text) => this.log('error', text),
    });
    a.server.start().catch((e) => this.log('error', `cannot serve ${action} for ${this.displayUrl}: ${e.message}`));
    return a;
  }

  _proxiedGoal(msg) {
    const a = this.actionsProxied.get(msg.action);
    const g = a && a.server.byRid.get(String(msg.id));
    return g ? { a, g } : null;
  }

  _proxiedFeedback(msg) {
    const p = this._proxiedGoal(msg);
    if (p) p.a.server.feedback(p.g, msg.values || {}).catch((e) => this.log('error', `feedback of ${msg.action}: ${e.message}`));
  }

  _proxiedResult(msg) {
    const p = this._proxiedGoal(msg);
    if (!p) return;
    const ok = msg.result && msg.values && typeof msg.values === 'object';
    p.a.server.finish(p.g, ok ? msg.status : 6, ok ? msg.values : {}).catch((e) => this.log('error', `result of ${msg.action}: ${e.message}`));
    if (!msg.result) this.log('warning', `a goal of ${msg.action} failed on ${this.displayUrl}: ${msg.values}`);
  }
}
