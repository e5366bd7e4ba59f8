// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * The one futex lock of the bus, over any word of shared memory: the
 * registry lock (HEADER.LOCK), an endpoint's writer lock (ENDPOINT.WLOCK)
 * and its event lock (ENDPOINT.EVLOCK).
 *
 * The word holds 0 when the lock is free, else its owner's process id,
 * with LOCK_CONTENDED set once a thread may sleep on it: the unlock then
 * wakes one sleeper. Owners are process ids, so that a lock whose owner
 * died can be found and stolen (registry lock, see Bus.lockAsync); threads
 * of one process share the id, and the lock excludes them from each other
 * all the same.
 *
 * @module bus/lock
 */

import { LOCK_CONTENDED, LOCK_OWNER_MASK } from '../layout.mjs';

/** CAS attempts before a blocking lock marks the word contended and sleeps. */
const SPINS = 64;

/**
 * Take the lock at `index`, sleeping while another owner holds it (workers only).
 * @param {Int32Array} i32 the bus words
 * @param {number} index the lock word
 * @param {number} owner the caller's process id (> 0)
 */
export function lock(i32, index, owner) {
  for (let spin = 0; spin < SPINS; spin++) {
    if (Atomics.compareExchange(i32, index, 0, owner) === 0) return;
  }
  for (;;) {
    let v = Atomics.load(i32, index);
    if (v === 0) {
      // Once we may have slept, take it marked contended: other threads may
      // still sleep, and our unlock() must wake one of them.
      if (Atomics.compareExchange(i32, index, 0, owner | LOCK_CONTENDED) === 0) return;
      continue;
    }
    if (!(v & LOCK_CONTENDED)) {
      if (Atomics.compareExchange(i32, index, v, v | LOCK_CONTENDED) !== v) continue;
      v |= LOCK_CONTENDED;
    }
    Atomics.wait(i32, index, v);
  }
}

/**
 * Take the lock at `index` if it is free, without blocking.
 * @param {Int32Array} i32
 * @param {number} index
 * @param {number} owner
 * @returns {boolean}
 */
export function tryLock(i32, index, owner) {
  return Atomics.compareExchange(i32, index, 0, owner) === 0;
}

/**
 * One step of a lock that must not block: take the lock if it is free, or
 * mark it contended. The caller sleeps (Atomics.waitAsync) on the returned
 * value and calls again.
 * @param {Int32Array} i32
 * @param {number} index
 * @param {number} owner
 * @returns {number} 0 when the lock was taken, else the word to wait on
 */
export function lockStep(i32, index, owner) {
  for (;;) {
    const v = Atomics.load(i32, index);
    if (v === 0) {
      if (Atomics.compareExchange(i32, index, 0, owner | LOCK_CONTENDED) === 0) return 0;
      continue;
    }
    if (v & LOCK_CONTENDED) return v;
    if (Atomics.compareExchange(i32, index, v, v | LOCK_CONTENDED) === v) return v | LOCK_CONTENDED;
  }
}

/**
 * Release the lock at `index` if `owner` holds it, waking one sleeper.
 * @param {Int32Array} i32
 * @param {number} index
 * @param {number} owner
 * @returns {boolean} false when another owner holds it (then it is left alone)
 */
export function unlock(i32, index, owner) {
  for (;;) {
    const v = Atomics.load(i32, index);
    if ((v & LOCK_OWNER_MASK) !== owner) return false;
    if (Atomics.compareExchange(i32, index, v, 0) !== v) continue; // a waiter marked it contended
    if (v & LOCK_CONTENDED) Atomics.notify(i32, index, 1);
    return true;
  }
}

/**
 * The process id that holds the lock at `index`, or 0.
 * @param {Int32Array} i32
 * @param {number} index
 * @returns {number}
 */
export function lockOwner(i32, index) {
  return Atomics.load(i32, index) & LOCK_OWNER_MASK;
}
