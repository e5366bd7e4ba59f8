// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * QoS profiles: the 12-word wire form shared with wasm_cpp, the JS object
 * form of the BusClient API, and the DDS/ROS compatibility rules.
 *
 * @module qos
 */

import {
  Durability, History, Liveliness, PolicyKind, QOS, QOS_FLAG_AVOID_ROS_NAMESPACE, Reliability,
} from './abi/bus_abi.mjs';

/** Policy values (equal to rmw's enums): abi/bus_abi.mjs. */
export { Durability, History, Liveliness, PolicyKind, Reliability };

const NS_PER_MS = 1e6;
const TWO32 = 4294967296;

/**
 * A QoS profile as JS code writes it. Durations are milliseconds; 0 or
 * Infinity mean "no limit".
 * @typedef {object} QosProfile
 * @property {'keep_last'|'keep_all'} [history='keep_last']
 * @property {number} [depth=10]
 * @property {'reliable'|'best_effort'} [reliability='reliable']
 * @property {'volatile'|'transient_local'} [durability='volatile']
 * @property {number} [deadlineMs=0]
 * @property {number} [lifespanMs=0]
 * @property {'automatic'|'manual_by_topic'} [liveliness='automatic']
 * @property {number} [leaseMs=0]
 */

const NAMES = {
  history: { keep_last: History.KEEP_LAST, keep_all: History.KEEP_ALL, system_default: 0 },
  reliability: {
    reliable: Reliability.RELIABLE, best_effort: Reliability.BEST_EFFORT, system_default: 0,
  },
  durability: {
    volatile: Durability.VOLATILE, transient_local: Durability.TRANSIENT_LOCAL, system_default: 0,
  },
  liveliness: {
    automatic: Liveliness.AUTOMATIC, manual_by_topic: Liveliness.MANUAL_BY_TOPIC, system_default: 0,
  },
};

function policyValue(field, value, fallback) {
  if (value === undefined) return fallback;
  const table = NAMES[field];
  const key = String(value).toLowerCase();
  if (!(key in table)) {
    throw new TypeError(
      `invalid QoS ${field} ${JSON.stringify(value)}: expected one of ${Object.keys(table).join(', ')}`);
  }
  return table[key];
}

function writeDurationMs(words, lo, ms, field) {
  if (ms === undefined || ms === 0 || ms === Infinity) {
    words[lo] = 0;
    words[lo + 1] = 0;
    return;
  }
  if (typeof ms !== 'number' || !(ms > 0)) {
    throw new TypeError(`invalid QoS ${field} ${JSON.stringify(ms)}: expected a positive number of milliseconds`);
  }
  const ns = Math.round(ms * NS_PER_MS);
  words[lo] = ns % TWO32;
  words[lo + 1] = Math.floor(ns / TWO32);
}

/**
 * Encode a JS QoS profile into the 12-word wire form.
 * @param {QosProfile} [profile]
 * @returns {Int32Array}
 */
export function encodeQos(profile = {}) {
  if (profile === null || typeof profile !== 'object') {
    throw new TypeError(`invalid QoS ${JSON.stringify(profile)}: expected an object`);
  }
  const w = new Int32Array(QOS.WORDS);
  w[QOS.HISTORY] = policyValue('history', profile.history, History.KEEP_LAST);
  const depth = profile.depth === undefined ? 10 : profile.depth;
  if (!Number.isInteger(depth) || depth < 0 || depth > 0x7fffffff) {
    throw new TypeError(`invalid QoS depth ${JSON.stringify(profile.depth)}: expected an integer >= 0`);
  }
  w[QOS.DEPTH] = depth;
  w[QOS.RELIABILITY] = policyValue('reliability', profile.reliability, Reliability.RELIABLE);
  w[QOS.DURABILITY] = policyValue('durability', profile.durability, Durability.VOLATILE);
  w[QOS.LIVELINESS] = policyValue('liveliness', profile.liveliness, Liveliness.AUTOMATIC);
  w[QOS.FLAGS] = profile.avoidRosNamespaceConventions ? QOS_FLAG_AVOID_ROS_NAMESPACE : 0;
  writeDurationMs(w, QOS.DEADLINE_LO, profile.deadlineMs, 'deadlineMs');
  writeDurationMs(w, QOS.LIFESPAN_LO, profile.lifespanMs, 'lifespanMs');
  writeDurationMs(w, QOS.LEASE_LO, profile.leaseMs, 'leaseMs');
  return w;
}

/**
 * Milliseconds of a wire duration; Infinity for "unspecified" (0) and "infinite" (INT64_MAX).
 * @param {number} lo low word (any sign)
 * @param {number} hi high word
 */
export function durationMs(lo, hi) {
  const l = lo >>> 0;
  const h = hi | 0;
  if ((l === 0 && h === 0) || h < 0 || (h === 0x7fffffff && l === 0xffffffff)) return Infinity;
  // rmw's RMW_DURATION_INFINITE is {9223372036 s, 854775807 ns}, i.e. INT64_MAX ns.
  return (h * TWO32 + l) / NS_PER_MS;
}

/**
 * Replace SYSTEM_DEFAULT values by the bus defaults (rmw_qos_profile_default), in place.
 * @param {Int32Array|number[]} w wire QoS words
 */
export function resolveQos(w) {
  if (w[QOS.HISTORY] === History.SYSTEM_DEFAULT) w[QOS.HISTORY] = History.KEEP_LAST;
  if (w[QOS.HISTORY] === History.KEEP_LAST && w[QOS.DEPTH] === 0) w[QOS.DEPTH] = 10;
  if (w[QOS.RELIABILITY] === Reliability.SYSTEM_DEFAULT) w[QOS.RELIABILITY] = Reliability.RELIABLE;
  if (w[QOS.DURABILITY] === Durability.SYSTEM_DEFAULT) w[QOS.DURABILITY] = Durability.VOLATILE;
  if (w[QOS.LIVELINESS] === Liveliness.SYSTEM_DEFAULT) w[QOS.LIVELINESS] = Liveliness.AUTOMATIC;
  if (w[QOS.LIVELINESS] === Liveliness.MANUAL_BY_NODE) w[QOS.LIVELINESS] = Liveliness.MANUAL_BY_TOPIC;
  return w;
}

/**
 * Check that wire QoS words hold known policy values; returns an error text or ''.
 * @param {Int32Array|number[]} w
 */
export function validateQos(w) {
  if (w[QOS.HISTORY] < 0 || w[QOS.HISTORY] > 2) return `unknown history policy ${w[QOS.HISTORY]}`;
  if (w[QOS.RELIABILITY] < 0 || w[QOS.RELIABILITY] > 2) {
    return `unknown reliability policy ${w[QOS.RELIABILITY]}`;
  }
  if (w[QOS.DURABILITY] < 0 || w[QOS.DURABILITY] > 2) return `unknown durability policy ${w[QOS.DURABILITY]}`;
  if (w[QOS.LIVELINESS] < 0 || w[QOS.LIVELINESS] > 3) return `unknown liveliness policy ${w[QOS.LIVELINESS]}`;
  if (w[QOS.DEPTH] < 0) return `negative history depth ${w[QOS.DEPTH]}`;
  return '';
}

/**
 * Decode wire QoS words into a JS profile (for graph snapshots).
 * @param {Int32Array|number[]} w
 * @returns {QosProfile}
 */
export function decodeQos(w) {
  const name = (field, v) => Object.keys(NAMES[field]).find((k) => NAMES[field][k] === v) || 'unknown';
  const ms = (lo) => {
    const d = durationMs(w[lo], w[lo + 1]);
    return d === Infinity ? 0 : d;
  };
  return {
    history: name('history', w[QOS.HISTORY]),
    depth: w[QOS.DEPTH],
    reliability: name('reliability', w[QOS.RELIABILITY]),
    durability: name('durability', w[QOS.DURABILITY]),
    deadlineMs: ms(QOS.DEADLINE_LO),
    lifespanMs: ms(QOS.LIFESPAN_LO),
    liveliness: name('liveliness', w[QOS.LIVELINESS]),
    leaseMs: ms(QOS.LEASE_LO),
  };
}

/**
 * Check whether a writer and a reader with these (resolved) profiles may match.
 * Same rules as rmw_qos_profile_check_compatible.
 * @param {Int32Array|number[]} pub resolved writer QoS words
 * @param {Int32Array|number[]} sub resolved reader QoS words
 * @returns {{ok: boolean, policy: number, reason: string}}
 */
export function checkCompatible(pub, sub) {
  if (pub[QOS.RELIABILITY] === Reliability.BEST_EFFORT && sub[QOS.RELIABILITY] === Reliability.RELIABLE) {
    return { ok: false, policy: PolicyKind.RELIABILITY, reason: 'best effort publisher and reliable subscription' };
  }
  if (pub[QOS.DURABILITY] === Durability.VOLATILE && sub[QOS.DURABILITY] === Durability.TRANSIENT_LOCAL) {
    return { ok: false, policy: PolicyKind.DURABILITY, reason: 'volatile publisher and transient local subscription' };
  }
  const pubDeadline = durationMs(pub[QOS.DEADLINE_LO], pub[QOS.DEADLINE_HI]);
  const subDeadline = durationMs(sub[QOS.DEADLINE_LO], sub[QOS.DEADLINE_HI]);
  if (pubDeadline > subDeadline) {
    return {
      ok: false,
      policy: PolicyKind.DEADLINE,
      reason: pubDeadline === Infinity
        ? 'subscription has a deadline, but publisher does not'
        : 'subscription deadline is less than publisher deadline',
    };
  }
  if (pub[QOS.LIVELINESS] === Liveliness.AUTOMATIC && sub[QOS.LIVELINESS] === Liveliness.MANUAL_BY_TOPIC) {
    return {
      ok: false, policy: PolicyKind.LIVELINESS,
      reason: "publisher's liveliness is automatic and subscription's is manual by topic",
    };
  }
  const pubLease = durationMs(pub[QOS.LEASE_LO], pub[QOS.LEASE_HI]);
  const subLease = durationMs(sub[QOS.LEASE_LO], sub[QOS.LEASE_HI]);
  if (pubLease > subLease) {
    return {
      ok: false,
      policy: PolicyKind.LIVELINESS_LEASE_DURATION,
      reason: pubLease === Infinity
        ? 'subscription has a liveliness lease duration, but publisher does not'
        : 'subscription liveliness lease duration is less than publisher',
    };
  }
  return { ok: true, policy: 0, reason: '' };
}
