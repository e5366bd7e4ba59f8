// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * ROS protocols over plain topics and services, as rcl does them: action
 * goals (rcl_action's `_action/send_goal`, `_action/feedback`,
 * `_action/get_result`, `_action/cancel_goal`) and node parameters
 * (rcl_interfaces' `list_parameters`, `get_parameters`, `set_parameters`).
 *
 * Both take a `bus` with two operations, which the page and the Node tools
 * give them on top of the wasm_js tools process:
 *   bus.call(service, type, requestBytes, timeoutMs) -> Promise<Uint8Array>
 *   bus.subscribe(topic, type, onBatch([{bytes, time}])) -> {close(), ready?: Promise}
 * and a TypeRegistry (cdr.mjs) holding the needed type descriptions.
 */

/** The longest setTimeout delay: how long a goal's result is waited for. */
const RESULT_TIMEOUT_MS = 2 ** 31 - 1;

/** rcl_action goal status codes (action_msgs/msg/GoalStatus). */
export const GoalStatus = Object.freeze({
  0: 'UNKNOWN', 1: 'ACCEPTED', 2: 'EXECUTING', 3: 'CANCELING', 4: 'SUCCEEDED', 5: 'CANCELED', 6: 'ABORTED',
});

/** Derive the actions of a graph from their hidden `_action` services. */
export function actionsOf(services) {
  const actions = new Map();
  for (const s of services) {
    const m = /^(.*)\/_action\/send_goal$/.exec(s.name);
    if (!m) continue;
    const type = (s.types[0] || '').replace(/_SendGoal$/, '');
    actions.set(m[1], { name: m[1], type, servers: s.servers, clients: s.clients });
  }
  return [...actions.values()].sort((a, b) => a.name.localeCompare(b.name));
}

function randomUuid() {
  const bytes = new Uint8Array(16);
  crypto.getRandomValues(bytes);
  bytes[6] = (bytes[6] & 0x0f) | 0x40;
  bytes[8] = (bytes[8] & 0x3f) | 0x80;
  return bytes;
}

function sameUuid(a, b) {
  if (!a || !b || a.length !== b.length) return false;
  for (let i = 0; i < a.length; i++) if (a[i] !== b[i]) return false;
  return true;
}

/** One goal of an action: accepted or not, feedback, result, cancel. */
export class GoalHandle {
  constructor(client, uuid) {
    this.client = client;
    this.uuid = uuid;
    this.id = Array.from(uuid, (b) => b.toString(16).padStart(2, '0')).join('');
  }

  /** Ask the server to cancel this goal; resolves to the CancelGoal response. */
  async cancel(timeoutMs = 5000) {
    const { registry, bus, name } = this.client;
    const type = 'action_msgs/srv/CancelGoal';
    const request = registry.encode(registry.service(type).request,
      { goal_info: { goal_id: { uuid: this.uuid }, stamp: { sec: 0, nanosec: 0 } } });
    const bytes = await bus.call(`${name}/_action/cancel_goal`, type, request, timeoutMs);
    return registry.decode(registry.service(type).response, bytes);
  }
}

/** A client of one action (name and type, e.g. /fibonacci, example_interfaces/action/Fibonacci). */
export class ActionClient {
  constructor(bus, registry, name, type) {
    this.bus = bus;
    this.registry = registry;
    this.name = name;
    this.type = type;
    this.spec = registry.action(type);
  }

  /**
   * Send a goal. Feedback of this goal goes to `onFeedback(value)`.
   * @returns {Promise<{accepted, handle, result: Promise<{status, statusText, result}>}>}
   */
  async sendGoal(goal, { onFeedback = () => {}, timeoutMs = 10000 } = {}) {
    const { registry, bus, spec, name, type } = this;
    const uuid = randomUuid();
    const feedback = bus.subscribe(`${name}/_action/feedback`, spec.feedback_message, (batch) => {
      for (const m of batch) {
        const value = registry.decode(spec.feedback_message, m.bytes);
        if (sameUuid(value.goal_id.uuid, uuid)) onFeedback(value.feedback);
      }
    });
    let response;
    try {
      if (feedback.ready) await feedback.ready;  // hear the first feedback too
      const request = registry.encode(spec.send_goal.request, { goal_id: { uuid }, goal });
      const bytes = await bus.call(`${name}/_action/send_goal`, `${type}_SendGoal`, request, timeoutMs);
      response = registry.decode(spec.send_goal.response, bytes);
    } catch (e) {
      feedback.close();
      throw e;
    }
    const handle = new GoalHandle(this, uuid);
    if (!response.accepted) {
      feedback.close();
      return { accepted: false, handle, result: Promise.resolve(null) };
    }
    const result = (async () => {
      try {
        const request = registry.encode(spec.get_result.request, { goal_id: { uuid } });
        // the server answers when the goal ends: wait as long as a timer can (24.8 days)
        const bytes = await bus.call(`${name}/_action/get_result`, `${type}_GetResult`, request, RESULT_TIMEOUT_MS);
        const value = registry.decode(spec.get_result.response, bytes);
        return { status: value.status, statusText: GoalStatus[value.status] || String(value.status), result: value.result };
      } finally {
        feedback.close();
      }
    })();
    return { accepted: true, handle, stamp: response.stamp, result };
  }
}

/** rcl_interfaces/msg/ParameterType. */
export const ParameterType = Object.freeze({
  NOT_SET: 0, BOOL: 1, INTEGER: 2, DOUBLE: 3, STRING: 4, BYTE_ARRAY: 5, BOOL_ARRAY: 6,
  INTEGER_ARRAY: 7, DOUBLE_ARRAY: 8, STRING_ARRAY: 9,
});
const TYPE_NAMES = ['not set', 'bool', 'integer', 'double', 'string', 'byte[]', 'bool[]', 'integer[]', 'double[]', 'string[]'];
const VALUE_FIELDS = [null, 'bool_value', 'integer_value', 'double_value', 'string_value', 'byte_array_value',
  'bool_array_value', 'integer_array_value', 'double_array_value', 'string_array_value'];

/** The JS value of an rcl_interfaces/msg/ParameterValue, and its type name. */
export function parameterValue(pv) {
  const field = VALUE_FIELDS[pv.type];
  const value = field ? pv[field] : null;
  return { type: TYPE_NAMES[pv.type] || `type ${pv.type}`, value: ArrayBuffer.isView(value) ? Array.from(value) : value };
}

/** Make an rcl_interfaces/msg/ParameterValue from a JS value, as `ros2 param set` infers the type. */
export function toParameterValue(value) {
  const pv = { type: ParameterType.NOT_SET };
  const isInt = (v) => typeof v === 'bigint' || (typeof v === 'number' && Number.isInteger(v));
  if (typeof value === 'boolean') Object.assign(pv, { type: ParameterType.BOOL, bool_value: value });
  else if (isInt(value)) Object.assign(pv, { type: ParameterType.INTEGER, integer_value: BigInt(value) });
  else if (typeof value === 'number') Object.assign(pv, { type: ParameterType.DOUBLE, double_value: value });
  else if (typeof value === 'string') Object.assign(pv, { type: ParameterType.STRING, string_value: value });
  else if (Array.isArray(value)) {
    if (value.length && value.every((v) => typeof v === 'boolean')) Object.assign(pv, { type: ParameterType.BOOL_ARRAY, bool_array_value: value });
    else if (value.length && value.every(isInt)) Object.assign(pv, { type: ParameterType.INTEGER_ARRAY, integer_array_value: value.map(BigInt) });
    else if (value.length && value.every((v) => typeof v === 'number')) Object.assign(pv, { type: ParameterType.DOUBLE_ARRAY, double_array_value: value });
    else if (value.every((v) => typeof v === 'string')) Object.assign(pv, { type: ParameterType.STRING_ARRAY, string_array_value: value });
    else throw new Error('a parameter array must hold only bools, only integers, only numbers or only strings');
  } else if (value !== null) {
    throw new Error(`a parameter cannot hold ${typeof value === 'object' ? 'a mapping' : typeof value}`);
  }
  return pv;
}

/** The parameters of one node (fully qualified name, e.g. /talker). */
export class ParameterClient {
  constructor(bus, registry, node) {
    this.bus = bus;
    this.registry = registry;
    this.node = node;
  }

  async request(service, request, timeoutMs = 5000) {
    const type = `rcl_interfaces/srv/${service}`;
    const { registry } = this;
    const entry = registry.service(type);
    const name = `${this.node === '/' ? '' : this.node}/${service.replace(/([a-z])([A-Z])/g, '$1_$2').toLowerCase()}`;
    const bytes = await this.bus.call(name, type, registry.encode(entry.request, request), timeoutMs);
    return registry.decode(entry.response, bytes);
  }

  /** Names of all parameters (recursive). */
  async list() {
    const response = await this.request('ListParameters', { prefixes: [], depth: 0n });
    return response.result.names.slice().sort();
  }

  /**
   * Values of parameters: [{name, type, value}]. rclcpp answers no values at all when one of
   * the names is not declared: each name is then 'not set'.
   */
  async get(names) {
    const response = await this.request('GetParameters', { names });
    const unset = { type: ParameterType.NOT_SET };
    return names.map((name, i) => ({ name, ...parameterValue(response.values[i] || unset) }));
  }

  /** Set one parameter; resolves to {successful, reason}. */
  async set(name, value) {
    const response = await this.request('SetParameters', { parameters: [{ name, value: toParameterValue(value) }] });
    return response.results[0];
  }
}
