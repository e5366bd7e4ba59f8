// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * Foxglove's parameters over the nodes' rcl parameter services, with the
 * ParameterClient the rosbridge rosapi code uses (page/ros_clients.mjs).
 * A Foxglove parameter name is `<node>.<parameter>`, as foxglove_bridge
 * spells it (`/talker.rate`); values are JSON, with `type: float64` for a
 * double that looks like an integer, `float64_array`, and `byte_array`
 * (base64). Updates come from `/parameter_events`, which rclcpp nodes
 * publish when a parameter changes.
 *
 * @module bridges/foxglove/parameters
 */

import { ParameterClient, ParameterType } from '../../page/ros_clients.mjs';
import { fromBase64, toBase64 } from '../rosbridge/convert.mjs';

/** Split `/node.param` at the first dot after the node name. */
export function splitName(name) {
  const full = name.startsWith('/') ? name : `/${name}`;
  const slash = full.lastIndexOf('/');
  const dot = full.indexOf('.', slash);
  if (dot < 0) throw new Error(`parameter name '${name}' is not <node>.<parameter> (e.g. /talker.rate)`);
  return [full.slice(0, dot), full.slice(dot + 1)];
}

/** A Foxglove parameter of an rcl_interfaces/msg/ParameterValue (null for NOT_SET). */
export function fromRcl(name, pv) {
  const num = (v) => (typeof v === 'bigint' ? Number(v) : v);
  switch (pv.type) {
    case ParameterType.BOOL: return { name, value: pv.bool_value };
    case ParameterType.INTEGER: return { name, value: num(pv.integer_value) };
    case ParameterType.DOUBLE: return { name, value: pv.double_value, type: 'float64' };
    case ParameterType.STRING: return { name, value: pv.string_value };
    case ParameterType.BYTE_ARRAY: return { name, value: toBase64(Uint8Array.from(pv.byte_array_value)), type: 'byte_array' };
    case ParameterType.BOOL_ARRAY: return { name, value: Array.from(pv.bool_array_value) };
    case ParameterType.INTEGER_ARRAY: return { name, value: Array.from(pv.integer_array_value, num) };
    case ParameterType.DOUBLE_ARRAY: return { name, value: Array.from(pv.double_array_value), type: 'float64_array' };
    case ParameterType.STRING_ARRAY: return { name, value: Array.from(pv.string_array_value) };
    default: return null;
  }
}

/** An rcl_interfaces/msg/ParameterValue of a Foxglove parameter. */
export function toRcl({ name, value, type }) {
  const isInt = (v) => typeof v === 'number' && Number.isInteger(v);
  if (value === undefined || value === null) return { type: ParameterType.NOT_SET };
  if (type === 'byte_array') {
    const bytes = fromBase64(String(value));
    if (!bytes) throw new Error(`parameter '${name}': a byte_array value must be base64 text`);
    return { type: ParameterType.BYTE_ARRAY, byte_array_value: bytes };
  }
  if (type === 'float64') return { type: ParameterType.DOUBLE, double_value: Number(value) };
  if (type === 'float64_array') return { type: ParameterType.DOUBLE_ARRAY, double_array_value: value.map(Number) };
  if (typeof value === 'boolean') return { type: ParameterType.BOOL, bool_value: value };
  if (isInt(value)) return { type: ParameterType.INTEGER, integer_value: BigInt(value) };
  if (typeof value === 'number') return { type: ParameterType.DOUBLE, double_value: value };
  if (typeof value === 'string') return { type: ParameterType.STRING, string_value: value };
  if (Array.isArray(value)) {
    if (value.every((v) => typeof v === 'boolean')) return { type: ParameterType.BOOL_ARRAY, bool_array_value: value };
    if (value.every(isInt)) return { type: ParameterType.INTEGER_ARRAY, integer_array_value: value.map(BigInt) };
    if (value.every((v) => typeof v === 'number')) return { type: ParameterType.DOUBLE_ARRAY, double_array_value: value };
    if (value.every((v) => typeof v === 'string')) return { type: ParameterType.STRING_ARRAY, string_array_value: value };
  }
  throw new Error(`parameter '${name}': ${JSON.stringify(value)} is no ROS 2 parameter value (a bool, number, string, `
    + 'or an array of only one of these)');
}

/** The parameters of the nodes of one bus link. */
export class Parameters {
  /**
   * @param {import('../rosbridge/bus_link.mjs').BusLink} link
   * @param {import('../../cdr.mjs').TypeRegistry} registry
   */
  constructor(link, registry) {
    this.link = link;
    this.registry = registry;
  }

  /** Can the build talk to parameter services (rcl_interfaces described)? */
  get available() {
    try {
      this.registry.service('rcl_interfaces/srv/GetParameters');
      this.registry.service('rcl_interfaces/srv/SetParameters');
      return true;
    } catch {
      return false;
    }
  }

  _client(node) {
    return new ParameterClient(this.link.clientBus(), this.registry, node);
  }

  _nodesWithParameters() {
    const g = this.link.graph();
    return g.nodes.filter((n) => n.fqn !== this.link.nodeName
      && n.services.some((s) => s.name === `${n.fqn}/get_parameters`)).map((n) => n.fqn);
  }

  /** Group `/node.param` names (or {name} objects) by node; a node the graph lacks is an error. */
  _byNode(items, what, errors) {
    const present = new Set(this._nodesWithParameters());
    const byNode = new Map();
    for (const item of items) {
      const [node, param] = splitName(typeof item === 'string' ? item : item.name);
      if (!present.has(node)) {
        if (!byNode.has(node)) errors.push(`cannot ${what} the parameters of ${node}: no node ${node} with parameter services is on the graph`);
        byNode.set(node, null);
      } else if (byNode.get(node) !== null) {
        if (!byNode.has(node)) byNode.set(node, []);
        byNode.get(node).push([param, item]);
      }
    }
    for (const [node, list] of byNode) if (list === null) byNode.delete(node);
    return byNode;
  }

  /**
   * Values of parameters; no names: every parameter of every node.
   * @returns {Promise<{parameters: object[], errors: string[]}>}
   */
  async get(names) {
    const byNode = new Map();
    const errors = [];
    if (!names || names.length === 0) {
      await Promise.all(this._nodesWithParameters().map(async (node) => {
        try {
          byNode.set(node, await this._client(node).list());
        } catch (e) {
          errors.push(`cannot list the parameters of ${node}: ${e.message}`);
        }
      }));
    } else {
      for (const [node, list] of this._byNode(names, 'get', errors)) byNode.set(node, list.map(([param]) => param));
    }
    const parameters = [];
    await Promise.all([...byNode].map(async ([node, params]) => {
      if (!params.length) return;
      try {
        const response = await this._client(node).request('GetParameters', { names: params });
        params.forEach((p, i) => {
          const v = fromRcl(`${node}.${p}`, response.values[i]);
          if (v) parameters.push(v);
        });
      } catch (e) {
        errors.push(`cannot get parameters of ${node}: ${e.message}`);
      }
    }));
    parameters.sort((a, b) => (a.name < b.name ? -1 : a.name > b.name ? 1 : 0));
    return { parameters, errors };
  }

  /**
   * Set parameters; resolves to the errors (a node that refused, ...).
   * @returns {Promise<string[]>}
   */
  async set(parameters) {
    const errors = [];
    const byNode = new Map();
    for (const [node, list] of this._byNode(parameters, 'set', errors)) {
      byNode.set(node, list.map(([param, p]) => ({ name: param, value: toRcl(p) })));
    }
    await Promise.all([...byNode].map(async ([node, list]) => {
      try {
        const response = await this._client(node).request('SetParameters', { parameters: list });
        response.results.forEach((r, i) => {
          if (!r.successful) errors.push(`setting ${node}.${list[i].name} failed: ${r.reason || 'refused by the node'}`);
        });
      } catch (e) {
        errors.push(`cannot set parameters of ${node}: ${e.message}`);
      }
    }));
    return errors;
  }

  /**
   * Hear parameter changes (from /parameter_events).
   * @param {function(object[]): void} onChange Foxglove parameters (deleted ones with no value)
   * @returns {Promise<function(): void>} stop
   */
  watch(onChange) {
    const type = 'rcl_interfaces/msg/ParameterEvent';
    const qos = { history: 'keep_last', depth: 100, reliability: 'reliable', durability: 'volatile' };
    return this.link.listen('/parameter_events', type, (batch) => {
      const changed = [];
      for (const m of batch) {
        let event;
        try {
          event = this.registry.decode(type, m.data);
        } catch {
          continue;
        }
        const node = event.node.startsWith('/') ? event.node : `/${event.node}`;
        for (const p of [...event.new_parameters, ...event.changed_parameters]) {
          const v = fromRcl(`${node}.${p.name}`, p.value);
          if (v) changed.push(v);
        }
        for (const p of event.deleted_parameters) changed.push({ name: `${node}.${p.name}` });
      }
      if (changed.length) onChange(changed);
    }, qos);
  }
}
