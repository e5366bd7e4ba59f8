// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Detached pthreads that ended, told to the program's main thread through
 * shared memory instead of a message, so that their workers go back to the
 * pool while main() blocks on the bus.
 *
 * Emscripten 3.1.6 recycles the worker of a detached thread (a
 * `std::thread(...).detach()`, as rclcpp's action server examples make one
 * per goal) only when the main thread handles the worker's
 * `{cmd: 'cleanupThread'}` message, on its event loop. A node's main thread
 * rarely gets back to its event loop: it blocks in Atomics waits on the bus.
 * So the workers of ended threads were never returned, and once the pool
 * (`--wasm-pthread-pool-size`, 4) was used up, the next `pthread_create`
 * waited forever for a new worker to load (which also needs the event
 * loop): an action server executed its first three goals and no more.
 *
 * Here a pre-started pthread worker (pthread_stub_node.mjs,
 * pthread_stub_web.js) writes the ended thread into a ring in a
 * SharedArrayBuffer instead of posting the message, and the main thread
 * reads the ring before it takes a worker (Emscripten's
 * `PThread.getNewWorker`) and hands each entry to Emscripten's own message
 * handler, as if the message had come. A full ring falls back to the
 * message. A thread started while every worker is busy gets a new worker
 * that runs it as soon as it has loaded; such a worker is not a pre-started
 * one, and goes back to the pool only when the main thread's event loop
 * turns (Emscripten's message), so their number stays that of the most
 * threads alive at once beyond the pool.
 *
 * Ring layout (Int32Array): [0] entries written (claimed), [1] entries read,
 * [2 ...] slots; a claimed slot holds 0 until its writer stores the thread.
 *
 * @module pthread_exits
 */

/** Slots of a ring: more detached threads ending between two thread starts fall back. */
export const EXIT_RING_SLOTS = 256;

const WRITTEN = 0;
const READ = 1;
const FIRST_SLOT = 2;

/**
 * A new, empty ring.
 * @param {number} [slots]
 * @returns {Int32Array}
 */
export function createExitRing(slots = EXIT_RING_SLOTS) {
  return new Int32Array(new SharedArrayBuffer((FIRST_SLOT + slots) * 4));
}

/**
 * Worker side: record that `thread` (its `struct pthread` address) ended.
 * pthread_stub_web.js has a copy of this function (a classic script cannot
 * import a module); change both.
 * @param {Int32Array} ring
 * @param {number} thread
 * @returns {boolean} false when the ring is full (post the message instead)
 */
export function pushExit(ring, thread) {
  const slots = ring.length - FIRST_SLOT;
  for (;;) {
    const written = Atomics.load(ring, WRITTEN);
    if (written - Atomics.load(ring, READ) >= slots) return false;
    if (Atomics.compareExchange(ring, WRITTEN, written, written + 1) === written) {
      Atomics.store(ring, FIRST_SLOT + (written % slots), thread);
      return true;
    }
  }
}

/**
 * Main side: call `fn(thread)` for each ended thread written so far, in order
 * (an entry claimed but not yet stored waits for the next call).
 * @param {Int32Array} ring
 * @param {function(number): void} fn
 */
export function drainExits(ring, fn) {
  const slots = ring.length - FIRST_SLOT;
  for (;;) {
    const read = Atomics.load(ring, READ);
    if (read === Atomics.load(ring, WRITTEN)) return;
    const slot = FIRST_SLOT + (read % slots);
    const thread = Atomics.exchange(ring, slot, 0);
    if (thread === 0) return;
    Atomics.store(ring, READ, read + 1);
    fn(thread);
  }
}

/**
 * Worker side, once Emscripten's worker script has loaded: send its
 * `cleanupThread` messages through the ring.
 * @param {object} scope the worker's global scope (whose postMessage the glue calls)
 * @param {Int32Array} ring
 */
export function sendCleanupsThroughRing(scope, ring) {
  const post = scope.postMessage;
  scope.postMessage = function postOrRing(msg, ...rest) {
    if (msg && msg.cmd === 'cleanupThread' && msg.thread && pushExit(ring, msg.thread)) return undefined;
    return post.call(this, msg, ...rest);
  };
}

/**
 * Main side, after the glue has run: before Emscripten takes a worker for a
 * new thread, return the workers of the threads that ended (Emscripten's
 * handler of a `cleanupThread` message does it).
 * @param {object} PThread the glue's PThread object
 * @param {Int32Array} ring
 * @param {function(number): void} [onNewWorker] called with the number of threads
 *   running when none of the workers is free (a new one is started)
 * @returns {boolean} false when the glue is not one this knows (nothing installed)
 */
export function recycleEndedThreads(PThread, ring, onNewWorker) {
  if (!PThread || typeof PThread.getNewWorker !== 'function' || !PThread.pthreads) return false;
  const cleanup = (thread) => {
    const pthread = PThread.pthreads[thread];
    // already cleaned up (a message that came after all, or a join)
    if (!pthread || !pthread.worker || typeof pthread.worker.onmessage !== 'function') return;
    pthread.worker.onmessage({ data: { cmd: 'cleanupThread', thread } });
  };
  const getNewWorker = PThread.getNewWorker;
  PThread.getNewWorker = function getNewWorkerAfterCleanups(...args) {
    drainExits(ring, cleanup);
    if (onNewWorker && PThread.unusedWorkers && PThread.unusedWorkers.length === 0) {
      onNewWorker(PThread.runningWorkers ? PThread.runningWorkers.length : 0);
    }
    const worker = getNewWorker.apply(this, args);
    // A new worker (more threads at once than the pool has): Emscripten would
    // post its thread's 'run' on the worker's 'loaded' reply, which a main()
    // blocked on the bus never handles. 'run' can follow 'load' at once (the
    // worker holds it until it has attached to the bus, library_wasm_bus.js;
    // program_worker.mjs' deferPthreadWorkerLoads does the same).
    if (worker) worker.loaded = true;
    return worker;
  };
  return true;
}
