// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The rosbridge v2 protocol's vocabulary (ROSBRIDGE_PROTOCOL.md of
 * RobotWebTools/rosbridge_suite): operations, status levels, compressions,
 * and the checks of a request's fields. Wire format only.
 *
 * @module bridges/rosbridge/protocol
 */

/** Operations a client sends. */
export const CLIENT_OPS = Object.freeze([
  'advertise', 'unadvertise', 'publish', 'subscribe', 'unsubscribe',
  'call_service', 'advertise_service', 'unadvertise_service', 'service_response',
  'send_action_goal', 'cancel_action_goal', 'advertise_action', 'unadvertise_action',
  'action_feedback', 'action_result', 'fragment', 'set_level', 'status',
]);

/** Status levels, least verbose first (a client's level shows its own and those before it). */
export const LEVELS = Object.freeze(['none', 'error', 'warning', 'info']);

export const COMPRESSIONS = Object.freeze(['none', 'png', 'cbor', 'cbor-raw']);

/** action_msgs/msg/GoalStatus codes. */
export const GoalStatus = Object.freeze({
  UNKNOWN: 0, ACCEPTED: 1, EXECUTING: 2, CANCELING: 3, SUCCEEDED: 4, CANCELED: 5, ABORTED: 6,
});

/** A request field that is missing or of the wrong type: a status error names it. */
export class FieldError extends Error {
  constructor(op, field, message) {
    super(`${op}: field '${field}' ${message}`);
    this.name = 'FieldError';
    this.field = field;
  }
}

const KINDS = {
  string: [(v) => typeof v === 'string', 'a string'],
  int: [(v) => (typeof v === 'number' && Number.isInteger(v)) || typeof v === 'bigint', 'an integer'],
  number: [(v) => typeof v === 'number', 'a number'],
  bool: [(v) => typeof v === 'boolean', 'a boolean'],
  object: [(v) => v !== null && typeof v === 'object' && !Array.isArray(v) && !ArrayBuffer.isView(v), 'a JSON object'],
  id: [(v) => typeof v === 'string' || typeof v === 'number', 'a string or a number'],
};

/**
 * Read a field of a request, checking its type.
 * @param {object} msg the request
 * @param {string} name
 * @param {'string'|'int'|'number'|'bool'|'object'|'id'} kind
 * @param {object} [options] {required=false, fallback, what: the field's meaning, for the error}
 */
export function field(msg, name, kind, { required = false, fallback = undefined, what = '' } = {}) {
  const v = msg[name];
  if (v === undefined || (v === null && !required)) {
    if (required) throw new FieldError(msg.op, name, `is missing${what ? ` (${what})` : ''}`);
    return fallback;
  }
  const [ok, label] = KINDS[kind];
  if (!ok(v)) {
    const got = v === null ? 'null' : Array.isArray(v) ? 'an array' : typeof v === 'object' ? 'an object' : `${typeof v} ${JSON.stringify(String(v)).slice(0, 40)}`;
    throw new FieldError(msg.op, name, `must be ${label}${what ? ` (${what})` : ''}, got ${got}`);
  }
  return typeof v === 'bigint' ? Number(v) : v;
}

/** A ROS name made absolute, or an error for a name ROS would refuse. */
export function rosName(op, fieldName, name) {
  const full = name.startsWith('/') ? name : `/${name}`;
  if (!/^(\/[A-Za-z_~][A-Za-z0-9_]*)+$/.test(full)) {
    throw new FieldError(op, fieldName, `is not a valid ROS name: '${name}' (parts of letters, digits and '_', not starting with a digit, separated by '/')`);
  }
  return full;
}
