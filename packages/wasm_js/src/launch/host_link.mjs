// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The main-thread side of the build host's rclpy (./host_link_worker.mjs):
 * one JS-only bus process per link, in a worker of its own, named
 * `launch_ros` in the graph; closing the link removes it from the bus. In
 * Node.js (colcon-wasm launch) and in the page (a launch file serve runs).
 *
 * @module launch/host_link
 */

import { ProgramWorker } from '../platform.mjs';

/**
 * Start a link's bus process.
 * @param {import('../runtime.mjs').Runtime} runtime
 * @param {Array<string|object>} types the types.json files of the install space (Node.js),
 *   or their documents (the page)
 * @param {function(string, string): void} [log] what the node logs (stream, text); default:
 *   this process' standard output and error
 * @returns {Promise<{post: function(object): void, onAnswer: function(function(object): void): void,
 *   close: function(): Promise<void>}>}
 */
export async function startHostLink(runtime, types, log = defaultLog) {
  const { pid, release } = await runtime.helperProcess('launch_ros');
  const worker = await ProgramWorker.start(new URL('./host_link_worker.mjs', import.meta.url),
    { name: 'launch_ros', type: 'module' });
  worker.postMessage({ init: { bus: runtime.bus.handle, pid, types } });
  let closed = null;
  const answers = [];
  worker.on('message', (message) => {
    if (message.log) log(message.log.stream, message.log.text);
    else for (const fn of answers) fn(message);
  });
  worker.on('error', (e) => log('stderr', `[ERROR] [launch_ros]: the bus process of the launch failed: ${e.message}`));
  return {
    post: (message) => worker.postMessage(message),
    onAnswer: (fn) => answers.push(fn),
    close() {
      if (!closed) closed = worker.terminate().then(() => release(), () => release());
      return closed;
    },
  };
}

function defaultLog(stream, text) {
  process[stream === 'stderr' ? 'stderr' : 'stdout'].write(`${text}\n`);
}
