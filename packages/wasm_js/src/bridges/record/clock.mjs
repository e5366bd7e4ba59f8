// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * `/clock` of a bag being played (`--clock`, the page's Play bag…):
 * rosgraph_msgs/msg/Clock with the bag time, as `ros2 bag play --clock`
 * publishes it. One definition for the Node.js player (./player.mjs) and the
 * page's (templates/launcher/bag.mjs).
 *
 * @module bridges/record/clock
 */

/** Reliable, depth 1: it matches reliable and best-effort clock subscriptions. */
export const CLOCK_QOS = Object.freeze({ history: 'keep_last', depth: 1, reliability: 'reliable', durability: 'volatile' });

/**
 * rosgraph_msgs/msg/Clock in CDR: the encapsulation header (little endian),
 * int32 sec, uint32 nanosec.
 * @param {bigint} ns the time in nanoseconds
 * @returns {Uint8Array}
 */
export function clockMessage(ns) {
  const out = new Uint8Array(12);
  const view = new DataView(out.buffer);
  out[1] = 1; // CDR little endian
  view.setInt32(4, Number(ns / 1000000000n), true);
  view.setUint32(8, Number(ns % 1000000000n), true);
  return out;
}
