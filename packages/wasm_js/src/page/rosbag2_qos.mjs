// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * QoS profiles as rosbag2 stores them in a channel's metadata
 * (`offered_qos_profiles`), for the page's recorder and player: a port of
 * colcon_wasm/record/qos.py (`to_rosbag2`, `from_rosbag2`, `player_qos`),
 * which serve's recorder and player use. Humble writes a YAML list, one
 * entry per publisher, the policies as rmw's enum numbers and durations as
 * `{sec, nsec}` (`9223372036`/`854775807` for none); Iron and later write
 * the policy names. Both are read; the Humble form is written. A profile
 * in JS is the object of ../qos.mjs (durations in milliseconds, 0: none).
 *
 * @module page/rosbag2_qos
 */

import { formatYaml, parseYaml } from './yaml.mjs';

const HISTORY = { system_default: 0, keep_last: 1, keep_all: 2, unknown: 3 };
const RELIABILITY = { system_default: 0, reliable: 1, best_effort: 2, unknown: 3, best_available: 4 };
const DURABILITY = { system_default: 0, transient_local: 1, volatile: 2, unknown: 3, best_available: 4 };
const LIVELINESS = {
  system_default: 0, automatic: 1, manual_by_node: 2, manual_by_topic: 3, unknown: 4, best_available: 5,
};

/** rosbag2's "infinite" duration (Humble: RMW_DURATION_INFINITE split). */
const INFINITE = Object.freeze({ sec: 9223372036, nsec: 854775807 });

/** The depth a player's publisher gets when the bag does not tell one. */
export const DEFAULT_DEPTH = 10;

function duration(ms) {
  if (!ms || ms === Infinity || ms < 0) return { ...INFINITE };
  const ns = Math.round(ms * 1e6);
  return { sec: Math.floor(ns / 1e9), nsec: ns % 1e9 };
}

function milliseconds(value) {
  if (value === null || typeof value !== 'object' || Array.isArray(value)) return 0;
  const sec = Number(value.sec ?? 0);
  const nsec = Number(value.nsec ?? 0);
  // a recorded duration that is not two integers reads as none (a bag's metadata is not trusted)
  if (!Number.isInteger(sec) || !Number.isInteger(nsec)) return 0;
  if ((sec === INFINITE.sec && nsec === INFINITE.nsec) || sec >= 2147483647 || (sec === 0 && nsec === 0)) return 0;
  return (sec * 1e9 + nsec) / 1e6;
}

function depthOf(value) {
  const depth = Number(value || 0);
  return Number.isInteger(depth) && depth >= 0 && depth < 2 ** 31 ? depth : 0;
}

function policy(value, table) {
  if (typeof value === 'number' || typeof value === 'bigint') {
    const found = Object.entries(table).find(([, number]) => BigInt(number) === BigInt(value));
    return found ? found[0] : 'unknown';
  }
  return typeof value === 'string' ? value.toLowerCase() : 'unknown';
}

/**
 * The `offered_qos_profiles` YAML of Humble's rosbag2 for some publishers' QoS,
 * the text colcon_wasm/record/qos.py's `to_rosbag2` writes.
 * @param {object[]} profiles the QoS of a topic's publishers (../qos.mjs form)
 * @returns {string} '' for none
 */
export function toRosbag2(profiles) {
  const entries = profiles.map((q) => ({
    history: HISTORY[q.history ?? 'keep_last'] ?? 1,
    depth: Math.trunc(Number(q.depth ?? DEFAULT_DEPTH)),
    reliability: RELIABILITY[q.reliability ?? 'reliable'] ?? 1,
    durability: DURABILITY[q.durability ?? 'volatile'] ?? 2,
    deadline: duration(q.deadlineMs),
    lifespan: duration(q.lifespanMs),
    liveliness: LIVELINESS[q.liveliness ?? 'automatic'] ?? 1,
    liveliness_lease_duration: duration(q.leaseMs),
    avoid_ros_namespace_conventions: false,
  }));
  return entries.length ? formatYaml(entries, { maxArray: Infinity }) : '';
}

/**
 * Read `offered_qos_profiles` (either form) into profiles of policy names.
 * @param {string} text
 * @returns {object[]} `[{history, depth, reliability, durability, deadlineMs, lifespanMs,
 *   liveliness, leaseMs}]`; [] for none or unreadable text
 */
export function fromRosbag2(text) {
  if (!text) return [];
  let items;
  try {
    items = parseYaml(text);
  } catch {
    return [];
  }
  if (!Array.isArray(items)) return [];
  return items.filter((item) => item !== null && typeof item === 'object' && !Array.isArray(item)).map((item) => ({
    history: policy(item.history, HISTORY),
    depth: depthOf(item.depth),
    reliability: policy(item.reliability, RELIABILITY),
    durability: policy(item.durability, DURABILITY),
    deadlineMs: milliseconds(item.deadline),
    lifespanMs: milliseconds(item.lifespan),
    liveliness: policy(item.liveliness, LIVELINESS),
    leaseMs: milliseconds(item.liveliness_lease_duration),
  }));
}

/**
 * The QoS of a player's publisher for a topic, from its recorded offers, as
 * rosbag2's player adapts it (and colcon_wasm/record/qos.py's `player_qos`):
 * reliability and durability kept when every offer agrees (reliable and
 * volatile otherwise), keep_last with the largest recorded depth
 * (`DEFAULT_DEPTH` when the bag tells none), lifespan kept when the offers agree.
 * @param {string} text the channel's `offered_qos_profiles`
 */
export function playerQos(text) {
  const offers = fromRosbag2(text);
  const agreed = (field, allowed, fallback) => {
    const values = new Set(offers.map((o) => o[field]));
    const [only] = values;
    return values.size === 1 && allowed.includes(only) ? only : fallback;
  };
  const depths = offers.filter((o) => o.depth > 0 && o.history === 'keep_last').map((o) => o.depth);
  const qos = {
    history: 'keep_last',
    depth: depths.length ? Math.max(...depths) : DEFAULT_DEPTH,
    reliability: agreed('reliability', ['reliable', 'best_effort'], 'reliable'),
    durability: agreed('durability', ['volatile', 'transient_local'], 'volatile'),
  };
  const lifespans = new Set(offers.map((o) => o.lifespanMs));
  if (lifespans.size === 1 && !lifespans.has(0)) [qos.lifespanMs] = lifespans;
  return qos;
}
