// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * 64-bit fields the bridges write from a double: a bus time in nanoseconds
 * (MCAP's Message records, rmw_zenoh's attachment), a length or an offset.
 * Two 32-bit halves rather than a BigInt, which would feed the garbage
 * collector once per message.
 *
 * @module bridges/common/little_endian
 */

const TWO_32 = 4294967296;

/**
 * Write `x`, a whole number below 2^64 held in a double, at `at` of `view`
 * as a little-endian uint64. Exact: each half fits in the double, and the
 * low half is a difference of two doubles within a factor of two.
 * @param {DataView} view
 * @param {number} at
 * @param {number} x
 */
export function setUint64(view, at, x) {
  const high = Math.floor(x / TWO_32);
  view.setUint32(at, x - high * TWO_32, true);
  view.setUint32(at + 4, high, true);
}
