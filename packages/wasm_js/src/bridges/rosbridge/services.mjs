// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * Service operations of a session: call_service (a bus service, or one of
 * the rosapi services, rosapi.mjs), advertise_service /
 * unadvertise_service (the client serves a service on the bus) and
 * service_response (its answers).
 *
 * rowe's RPC rules: every call has an id the reply carries; a call that is
 * not answered in time (the request's `timeout` in seconds, else
 * `limits.callTimeoutMs`) gets `service_response` with `result: false` and
 * a status error, never silence; requests to a client-served service are
 * matched to its responses by their ids, so many callers at once each get
 * their own answer, and one that the client does not answer within
 * `limits.serveTimeoutMs` is dropped with a warning (ROS 2 services have no
 * error reply).
 *
 * @module bridges/rosbridge/services
 */

import { stringifyJson } from './json.mjs';
import { field, FieldError, rosName } from './protocol.mjs';
import { isRosapi, rosapiCall } from './rosapi.mjs';

const FOREVER_MS = 2 ** 31 - 1;

/** The request value of rosbridge `args`: an object, or a list in field order. */
export function requestArgs(registry, requestType, args, op = 'call_service') {
  if (args === undefined || args === null) return {};
  if (Array.isArray(args)) {
    const fields = registry.message(requestType).fields;
    if (args.length > fields.length) throw new FieldError(op, 'args', `has ${args.length} values, but ${requestType} has ${fields.length} fields`);
    const out = {};
    args.forEach((v, i) => { out[fields[i].name] = v; });
    return out;
  }
  if (typeof args !== 'object') throw new FieldError(op, 'args', `must be a JSON object (or a list in field order), got ${typeof args}`);
  return args;
}

/**
 * Register the service operations on a session.
 * @param {import('./session.mjs').Session} session
 */
export function installServices(session) {
  const { core } = session;
  const { converter, registry, link } = core;
  const advertised = new Map();

  const serviceEntry = (op, type) => {
    try {
      return { full: type.replace(/^([^/]+)\/([^/]+)$/, '$1/srv/$2'), entry: registry.service(type) };
    } catch (e) {
      throw new FieldError(op, 'type', `names an unknown service type: ${e.message}`);
    }
  };

  const respondFailure = (msg, service, text) => {
    const out = { op: 'service_response', service, values: text, result: false };
    if (msg.id !== undefined) out.id = msg.id;
    session.sendJson(out);
    session.status('error', `call_service ${service}: ${text}`, msg.id);
  };

  session.register('call_service', async (msg) => {
    const given = field(msg, 'service', 'string', { required: true, what: 'the service to call' });
    const service = rosName('call_service', 'service', given.split('#')[0]);
    if (!core.capabilities.allows('call', service)) throw new Error(core.capabilities.refusal('call', service));
    const timeoutS = field(msg, 'timeout', 'number');
    const timeoutMs = timeoutS === undefined ? core.limits.callTimeoutMs : timeoutS > 0 ? Math.min(timeoutS * 1000, FOREVER_MS) : FOREVER_MS;
    if (isRosapi(service)) {
      let values;
      try {
        values = await rosapiCall(core, service, msg.args || {});
      } catch (e) {
        respondFailure(msg, given, e.message);
        return;
      }
      const out = { op: 'service_response', service: given, values, result: true };
      if (msg.id !== undefined) out.id = msg.id;
      session.sendJson(out);
      return;
    }
    const typeName = field(msg, 'type', 'string') || link.serviceType(service);
    if (!typeName || !link.hasServer(service)) {
      respondFailure(msg, given, `service '${service}' does not exist (no server in the graph)`);
      return;
    }
    const { full, entry } = serviceEntry('call_service', typeName);
    const value = converter.fromJson(entry.request, requestArgs(registry, entry.request, msg.args));
    let request;
    try {
      request = registry.encode(entry.request, value);
    } catch (e) {
      throw new FieldError('call_service', 'args', `do not fit ${entry.request}: ${e.message.replace(/^encoding [^:]+: /, '')}`);
    }
    let response;
    try {
      response = await link.call(service, full, request, timeoutMs);
    } catch (e) {
      respondFailure(msg, given, e.message);
      return;
    }
    if (session.closed) return;
    const json = converter.jsonWriter(entry.response)(registry.decode(entry.response, response));
    const id = msg.id === undefined ? '' : `,"id":${stringifyJson(msg.id)}`;
    session.sendText(`{"op":"service_response","service":${JSON.stringify(given)},"values":${json},"result":true${id}}`,
      field(msg, 'fragment_size', 'int') || session.fragmentSize, msg.id);
  });

  session.register('advertise_service', async (msg) => {
    const service = rosName('advertise_service', 'service', field(msg, 'service', 'string', { required: true }));
    if (!core.capabilities.allows('advertise', service)) throw new Error(core.capabilities.refusal('advertise', service));
    const typeName = field(msg, 'type', 'string', { required: true, what: 'the service type, e.g. example_interfaces/srv/AddTwoInts' });
    const { full, entry } = serviceEntry('advertise_service', typeName);
    const previous = core.services.get(service);
    if (previous) {
      previous.session.status('warning', `service ${service} was advertised again by another client: this client no longer serves it`);
      previous.close();
    }
    let seq = 0;
    const pending = new Map();
    const state = { session, close: null };
    const server = await link.serve(service, full, (requests) => {
      for (const r of requests) {
        const rid = `service_request:${service}:${++seq}`;
        let args;
        try {
          args = converter.jsonWriter(entry.request)(registry.decode(entry.request, r.data));
        } catch (e) {
          session.status('error', `a request to ${service} could not be decoded: ${e.message}`);
          continue;
        }
        const timer = setTimeout(() => {
          pending.delete(rid);
          core.stats.unanswered++;
          session.status('warning', `request '${rid}' was not answered within ${core.limits.serveTimeoutMs} ms: its caller gets no response`, rid);
        }, core.limits.serveTimeoutMs);
        if (timer.unref) timer.unref();
        pending.set(rid, { id: r.id, timer });
        session.sendText(`{"op":"call_service","id":${JSON.stringify(rid)},"service":${JSON.stringify(service)},"args":${args}}`);
      }
    });
    state.close = () => {
      if (core.services.get(service) === state) core.services.delete(service);
      advertised.delete(service);
      for (const p of pending.values()) clearTimeout(p.timer);
      pending.clear();
      server.close().catch(() => {});
    };
    state.respond = async (rid, values, result) => {
      const p = pending.get(rid);
      if (!p) throw new FieldError('service_response', 'id', `'${rid}' names no pending request of ${service}`);
      pending.delete(rid);
      clearTimeout(p.timer);
      const value = converter.fromJson(entry.response, values && typeof values === 'object' ? values : {});
      let bytes;
      try {
        bytes = registry.encode(entry.response, value);
      } catch (e) {
        throw new FieldError('service_response', 'values', `do not fit ${entry.response}: ${e.message.replace(/^encoding [^:]+: /, '')}`);
      }
      if (!result) session.status('warning', `service_response ${rid}: result false; ROS 2 has no error responses, so the caller gets ${values && typeof values === 'object' ? 'these values' : 'a default response'}`, rid);
      await server.respond(p.id, bytes);
    };
    core.services.set(service, state);
    advertised.set(service, state);
    session.status('info', `Advertised service ${service}`, msg.id);
  });

  session.register('unadvertise_service', (msg) => {
    const service = rosName('unadvertise_service', 'service', field(msg, 'service', 'string', { required: true }));
    const state = advertised.get(service);
    if (!state) {
      session.status('warning', `unadvertise_service: this client does not serve '${service}'`, msg.id);
      return;
    }
    state.close();
  });

  session.register('service_response', async (msg) => {
    const service = rosName('service_response', 'service', field(msg, 'service', 'string', { required: true }));
    const rid = field(msg, 'id', 'id', { required: true, what: 'the id of the call_service it answers' });
    const result = field(msg, 'result', 'bool', { required: true });
    const state = advertised.get(service);
    if (!state) throw new Error(`service ${service} has not been advertised by this client`);
    await state.respond(String(rid), msg.values, result);
  });

  session.onClose(() => {
    for (const state of [...advertised.values()]) state.close();
  });
}

export { FOREVER_MS };
