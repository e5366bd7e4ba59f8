// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * A pre-started Emscripten pthread worker for Node.js (see pthread_pool.mjs):
 * booted and with the bus client imported before the program starts; told
 * Emscripten's worker script, it loads it the way Node.js would have (as a
 * CommonJS module), and that script takes over the messages. Its threads'
 * ends go to the main thread through shared memory (pthread_exits.mjs).
 *
 * @module pthread_stub_node
 */

import { createRequire } from 'node:module';
import { parentPort } from 'node:worker_threads';

import { sendCleanupsThroughRing } from './pthread_exits.mjs';

// Taken before the import failed: Emscripten's script owns the messages
// now, and an error message would confuse it.
let taken = false;

const onMessage = (msg) => {
  if (msg && typeof msg.colconWasmPreload === 'string') {
    const { state } = msg;
    import(msg.colconWasmPreload).then(() => {
      Atomics.store(state, 0, 1);
      Atomics.notify(state, 0);
    }, (err) => {
      Atomics.store(state, 0, 2);
      Atomics.notify(state, 0);
      if (!taken) parentPort.postMessage({ colconWasmError: String(err && err.message || err) });
    });
    return;
  }
  if (msg && typeof msg.colconWasmWorkerScript === 'string') {
    taken = true;
    parentPort.off('message', onMessage);
    createRequire(import.meta.url)(msg.colconWasmWorkerScript);
    // ended detached threads reach the blocked main thread (pthread_exits.mjs)
    if (msg.exitRing) sendCleanupsThroughRing(globalThis, msg.exitRing);
  }
};
parentPort.on('message', onMessage);
