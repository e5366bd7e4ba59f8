// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Time on the bus: the wall clock every record and message carries, and a
 * bounded Atomics.waitAsync.
 *
 * @module bus/clock
 */

/**
 * Atomics.waitAsync for at most `ms`, with a timer beside it: a pending
 * waitAsync does not keep Node.js's event loop alive, so a process whose
 * only pending work is this wait would otherwise quit in the middle of it
 * (exit code 13). The timer also bounds the wait where the notify never
 * comes (an owner that died holding the lock).
 * @param {Int32Array} i32
 * @param {number} index
 * @param {number} value
 * @param {number} ms
 * @returns {Promise<void>}
 */
export async function waitAsyncAlive(i32, index, value, ms) {
  const r = Atomics.waitAsync(i32, index, value, ms);
  if (!r.async) return;
  let timer;
  const alive = new Promise((resolve) => {
    timer = setTimeout(resolve, ms + 1);
  });
  try {
    await Promise.race([r.value, alive]);
  } finally {
    clearTimeout(timer);
  }
}

// The Performance object, looked up once: in a Chromium worker the global
// `performance` getter alone costs ~100-200 ns per read (a clock read with
// it: 210-340 ns, without it: 90-120 ns), and publish reads the clock for
// every message.
const PERF = typeof performance !== 'undefined' ? performance : null;
const ORIGIN = (PERF && PERF.timeOrigin) || 0;
/** Wall-clock milliseconds since the epoch with sub-millisecond resolution. */
export const now = ORIGIN ? () => ORIGIN + PERF.now() : () => Date.now();
