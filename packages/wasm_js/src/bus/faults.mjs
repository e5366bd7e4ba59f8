// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Fault points: named points inside the bus operations where a test stops
 * a thread, so that it can kill the thread's worker right there, at the
 * operation's worst moment (tests/js/bus_faults.mjs, docs/faults.md).
 *
 * Off unless a test arms one: each point is a `bus.faultPoint !== null`
 * check of the thread's own Bus (a field that stays null), nothing else.
 * Armed, the thread that reaches the point (after `skip` earlier hits)
 * sets the first word of the test's flag to 1, notifies it, and sleeps
 * there until its worker is terminated.
 *
 * @module bus/faults
 */

/** Every fault point: name -> where the thread stops. */
export const FAULT_POINTS = Object.freeze({
  'publish.locked': 'writer lock held, the slot not yet marked (publish, request, response)',
  'publish.writing': 'slot marked as being written, payload copied, not committed',
  'publish.committed': 'slot committed, the writer\'s HEAD not yet advanced',
  'publish.unrung': 'HEAD advanced, writer lock released, the readers not yet rung',
  'publish.blocked': 'blocked on a full RELIABLE KEEP_ALL reader (writer lock held)',
  'publish.renewing': 'registry and writer lock held: the slot\'s old block freed, no new one yet',
  'take.found': 'the next message found, not yet copied',
  'take.copied': 'the message copied, the reader\'s cursor not yet advanced',
  'take.consumed': 'the cursor advanced, a waiting writer not yet rung',
  'take.reaping': 'registry lock held: dropping the links of a drained zombie writer',
  'graph.locked': 'registry lock held, the change (node, endpoint) not begun',
  'graph.node_written': 'registry lock held: a node record written, not committed',
  'graph.endpoint_written': 'registry lock held: an endpoint record, strings and ring written, not committed',
  'graph.matching': 'registry lock held: a new endpoint committed, one link of several made',
  'graph.removing': 'registry lock held: an endpoint being removed, one of its links dropped',
  'graph.changed': 'registry lock held: the change made, the graph version not bumped',
  'arena.freeing': 'registry lock held: a freed block linked behind the quarantine tail, the tail not moved',
  'arena.releasing': 'registry lock held: a block taken off the quarantine, not on a free list',
  'event.locked': 'an endpoint\'s event lock held (QoS event status)',
  'wait.sleeping': 'registered as a sleeper of the process, about to sleep on its doorbell',
});

/**
 * Arm a fault point on this thread's attachment to the bus (tests only).
 * @param {import('../bus.mjs').Bus} bus
 * @param {object} spec
 * @param {string} spec.point a key of FAULT_POINTS
 * @param {Int32Array|SharedArrayBuffer} spec.flag two words of shared memory: the first is
 *   set to 1 (and notified) when the thread stops at the point
 * @param {number} [spec.skip=0] hits of the point to let pass first
 */
export function armFaultPoint(bus, { point, flag, skip = 0 }) {
  if (!(point in FAULT_POINTS)) {
    throw new Error(`unknown fault point '${point}' (known: ${Object.keys(FAULT_POINTS).join(', ')})`);
  }
  const words = flag instanceof Int32Array ? flag : new Int32Array(flag, 0, 2);
  let left = skip;
  bus.faultPoint = (name) => {
    if (name !== point || left-- > 0) return;
    bus.faultPoint = null;
    Atomics.store(words, 0, 1);
    Atomics.notify(words, 0);
    // Bounded sleeps: the worker's termination ends the loop between two at the latest.
    for (;;) Atomics.wait(words, 1, 0, 10);
  };
}

/** Disarm this thread's fault point. */
export function disarmFaultPoint(bus) {
  bus.faultPoint = null;
}
