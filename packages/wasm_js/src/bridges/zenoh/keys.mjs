// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * rmw_zenoh's wire conventions on Humble (rmw_zenoh_cpp 0.1.2 and later,
 * src/detail/liveliness_utils.cpp and attachment_helpers.cpp): the key
 * expressions of topics and services, the liveliness tokens of nodes and
 * endpoints with their QoS text, and the attachment of every sample, query
 * and reply. docs/zenoh.md has the worked examples.
 *
 * @module bridges/zenoh/keys
 */

/** Humble has no type hashes: rmw_zenoh writes this in their place. */
export const TYPE_HASH = 'TypeHashNotSupported';

/** The admin prefix of the liveliness tokens. */
export const LIVELINESS_PREFIX = '@ros2_lv';

/** Entity kinds in tokens, and the local graph's names for them. */
export const Kind = Object.freeze({ NODE: 'NN', PUBLISHER: 'MP', SUBSCRIPTION: 'MS', SERVER: 'SS', CLIENT: 'SC' });

/**
 * rmw_zenoh's type name: `pkg/msg/Type` -> `pkg::msg::dds_::Type_`; a
 * service type names the service (`pkg::srv::dds_::AddTwoInts_`).
 */
export function ddsTypeName(type) {
  const parts = String(type).split('/');
  if (parts.length !== 3 || parts.some((p) => !p)) throw new Error(`'${type}' is not a ROS interface type (pkg/msg/Type)`);
  return `${parts[0]}::${parts[1]}::dds_::${parts[2]}_`;
}

/** The ROS type of an rmw_zenoh type name, or null when it is not one. */
export function rosTypeName(dds) {
  const m = /^([A-Za-z0-9_]+)::([A-Za-z0-9_]+)::dds_::([A-Za-z0-9_]+)_$/.exec(String(dds));
  return m ? `${m[1]}/${m[2]}/${m[3]}` : null;
}

/** Drop one leading and one trailing '/', as rmw_zenoh's strip_slashes. */
function stripSlashes(name) {
  let s = String(name);
  if (s.startsWith('/')) s = s.slice(1);
  if (s.endsWith('/')) s = s.slice(0, -1);
  return s;
}

/**
 * The key expression of a topic or service: `<domain>/<name>/<type>/<hash>`.
 * @param {number} domain
 * @param {string} name the fully qualified name (`/chatter`)
 * @param {string} type `pkg/msg/Type` or `pkg/srv/Type`
 */
export function dataKey(domain, name, type) {
  return `${domain}/${stripSlashes(name)}/${ddsTypeName(type)}/${TYPE_HASH}`;
}

/** `/` -> `%` inside a token field; an empty field (the default namespace) is `%`. */
export function mangle(text) {
  const s = String(text || '').replace(/\//g, '%');
  return s || '%';
}

/** `%` -> `/` (the reverse of mangle). */
export function demangle(text) {
  return String(text).replace(/%/g, '/');
}

const RELIABILITY = { reliable: 1, best_effort: 2 };
const DURABILITY = { transient_local: 1, volatile: 2 };
const HISTORY = { keep_last: 1, keep_all: 2 };
const LIVELINESS = { automatic: 1, manual_by_topic: 3 };
const DEFAULT_DEPTH = 42;

function durationField(ms) {
  if (!Number.isFinite(ms) || ms <= 0) return ',';
  const s = Math.floor(ms / 1000);
  return `${s},${Math.round((ms - s * 1000) * 1e6)}`;
}

/**
 * The QoS text of a token, `R:D:H,depth:DLs,DLns:LSs,LSns:LV,LLs,LLns`, a
 * field empty when it is rmw_zenoh's default (reliable, volatile,
 * keep_last, depth 42, no deadline, lifespan or lease, automatic).
 * @param {import('../../qos.mjs').QosProfile} qos
 */
export function qosText(qos = {}) {
  const rel = RELIABILITY[qos.reliability] === 2 ? '2' : '';
  const dur = DURABILITY[qos.durability] === 1 ? '1' : '';
  const hist = HISTORY[qos.history] === 2 ? '2' : '';
  const depth = qos.history === 'keep_all' || !qos.depth || qos.depth === DEFAULT_DEPTH ? '' : String(qos.depth);
  const live = LIVELINESS[qos.liveliness] === 3 ? '3' : '';
  return `${rel}:${dur}:${hist},${depth}:${durationField(qos.deadlineMs)}:${durationField(qos.lifespanMs)}:${live},${durationField(qos.leaseMs)}`;
}

function parseDuration(s, ns) {
  if (!s && !ns) return 0;
  return Number(s || 0) * 1000 + Number(ns || 0) / 1e6;
}

/**
 * Parse a token's QoS text.
 * @returns {import('../../qos.mjs').QosProfile}
 * @throws {Error} when it does not have rmw_zenoh's six fields
 */
export function parseQosText(text) {
  const groups = String(text).split(':');
  if (groups.length !== 6) throw new Error(`'${text}' is not rmw_zenoh's QoS text (6 ':'-separated fields)`);
  const [rel, dur, histDepth, deadline, lifespan, live] = groups;
  const [hist, depth] = histDepth.split(',');
  const [dls, dlns] = deadline.split(',');
  const [lss, lsns] = lifespan.split(',');
  const [lv, lls, llns] = live.split(',');
  const pick = (table, value, fallback) => Object.keys(table).find((k) => String(table[k]) === value) || fallback;
  return {
    reliability: pick(RELIABILITY, rel, 'reliable'),
    durability: pick(DURABILITY, dur, 'volatile'),
    history: pick(HISTORY, hist, 'keep_last'),
    depth: depth ? Number(depth) : DEFAULT_DEPTH,
    deadlineMs: parseDuration(dls, dlns),
    lifespanMs: parseDuration(lss, lsns),
    liveliness: pick(LIVELINESS, lv, 'automatic'),
    leaseMs: parseDuration(lls, llns),
  };
}

/**
 * The liveliness token of a node or an endpoint.
 * @param {object} e
 * @param {number} e.domain
 * @param {string} e.zid the session's Zenoh id (as zenoh prints it)
 * @param {number} e.nodeId
 * @param {number} e.id the entity id (a node's own id for NN)
 * @param {string} e.kind Kind.*
 * @param {string} [e.enclave='/']
 * @param {string} e.namespace
 * @param {string} e.node the node name
 * @param {string} [e.name] topic or service (endpoints)
 * @param {string} [e.type] `pkg/msg/Type` (endpoints)
 * @param {object} [e.qos]
 */
export function tokenKey(e) {
  const head = [LIVELINESS_PREFIX, e.domain, e.zid, e.nodeId, e.id, e.kind,
    mangle(e.enclave === '/' ? '' : e.enclave), mangle(e.namespace === '/' ? '' : e.namespace), mangle(e.node)];
  if (e.kind === Kind.NODE) return head.join('/');
  return [...head, mangle(e.name), ddsTypeName(e.type), TYPE_HASH, qosText(e.qos)].join('/');
}

/**
 * Parse a liveliness token (a remote entity), as rmw_zenoh's Entity::make.
 * @returns {{domain: number, zid: string, nodeId: string, id: string, kind: string, enclave: string,
 *   namespace: string, node: string, name?: string, type?: string, qos?: object}}
 * @throws {Error} naming what is wrong
 */
export function parseToken(key) {
  const parts = String(key).split('/');
  if (parts[0] !== LIVELINESS_PREFIX) throw new Error(`'${key}' is not an rmw_zenoh liveliness token`);
  if (parts.length < 9 || parts.slice(0, 9).some((p) => !p)) throw new Error(`'${key}' has fewer than 9 fields`);
  const kind = parts[5];
  if (!Object.values(Kind).includes(kind)) throw new Error(`'${key}' has an unknown entity kind '${kind}'`);
  const entity = {
    domain: Number(parts[1]), zid: parts[2], nodeId: parts[3], id: parts[4], kind,
    enclave: demangle(parts[6]), namespace: demangle(parts[7]), node: demangle(parts[8]),
  };
  if (kind === Kind.NODE) return entity;
  if (parts.length < 13 || parts.slice(9, 13).some((p) => !p)) throw new Error(`'${key}' is an endpoint token with fewer than 13 fields`);
  const type = rosTypeName(parts[10]);
  if (!type) throw new Error(`'${key}' has a type '${parts[10]}' that is not rmw_zenoh's pkg::msg::dds_::Type_`);
  return { ...entity, name: demangle(parts[9]), type, qos: parseQosText(parts[12]) };
}

/**
 * The attachment of a sample, query or reply (zenoh-ext serialization):
 * int64 sequence number, int64 source timestamp (ns since the epoch), and
 * the 16-byte gid as a sequence (its LEB128 length, 0x10, then the bytes).
 * @param {number|bigint} sequence
 * @param {number|bigint} timestampNs
 * @param {Uint8Array} gid 16 bytes
 * @returns {Uint8Array} 33 bytes
 */
export function encodeAttachment(sequence, timestampNs, gid) {
  if (!gid || gid.length !== 16) throw new Error('an rmw_zenoh gid has 16 bytes');
  const out = new Uint8Array(33);
  const view = new DataView(out.buffer);
  view.setBigInt64(0, BigInt(sequence), true);
  view.setBigInt64(8, BigInt(timestampNs), true);
  out[16] = 16;
  out.set(gid, 17);
  return out;
}

/**
 * Parse an attachment.
 * @returns {{sequence: bigint, timestampNs: bigint, gid: Uint8Array}}
 * @throws {Error} when it is not rmw_zenoh's 33 bytes
 */
export function decodeAttachment(bytes) {
  if (!bytes || bytes.length !== 33 || bytes[16] !== 16) {
    throw new Error(`an attachment of ${bytes ? bytes.length : 0} bytes is not rmw_zenoh's (33: sequence, timestamp, gid)`);
  }
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.length);
  return { sequence: view.getBigInt64(0, true), timestampNs: view.getBigInt64(8, true), gid: bytes.slice(17, 33) };
}

/** The local gid (4 words, as graph snapshots give it in hex) as 16 bytes. */
export function gidBytes(hex) {
  const out = new Uint8Array(16);
  for (let i = 0; i < 16; i++) out[i] = parseInt(String(hex).slice(2 * i, 2 * i + 2), 16) || 0;
  return out;
}

/** Now, in nanoseconds since the epoch. */
export function nowNs() {
  return BigInt(Date.now()) * 1000000n;
}
