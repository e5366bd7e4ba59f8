// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The main-thread side of the build host's rclpy (./host_link_worker.mjs):
 * one JS-only bus process per link, in a worker of its own, named
 * `launch_ros` in the graph; closing the link removes it from the bus.
 *
 * @module launch/host_link
 */

import { Worker } from 'node:worker_threads';

/**
 * Start a link's bus process.
 * @param {import('../runtime.mjs').Runtime} runtime
 * @param {string[]} types the types.json files of the install space
 * @returns {Promise<{post: function(object): void, onAnswer: function(function(object): void): void,
 *   close: function(): Promise<void>}>}
 */
export async function startHostLink(runtime, types) {
  const { pid, release } = await runtime.helperProcess('launch_ros');
  const worker = new Worker(new URL('./host_link_worker.mjs', import.meta.url));
  worker.postMessage({ init: { bus: runtime.bus.handle, pid, types } });
  let closed = null;
  return {
    post: (message) => worker.postMessage(message),
    onAnswer: (fn) => worker.on('message', fn),
    close() {
      if (!closed) closed = worker.terminate().then(() => release(), () => release());
      return closed;
    },
  };
}
