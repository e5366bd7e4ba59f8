// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The bus side of a Python launch file (colcon_wasm/launch/python_launch/).
 *
 * Humble's real `launch` runs on the build host and starts every process as
 * a host process. A `Node` of the install space starts a small host program
 * (node_shim.py, found by launch_ros' ExecutableInPackage in the launch's
 * host prefix), which connects here and asks for its wasm executable to run
 * on this host's bus. The shim is the process launch knows: its pid, its
 * output, its signals and its exit code are the node's, so launch's process
 * events, `on_exit`, `respawn` and `Shutdown()` work as they do natively.
 *
 * The messages are ./process_protocol.mjs', one JSON object per line on a Unix
 * stream socket.
 */

import net from 'node:net';

import { processConnection } from './process_protocol.mjs';

const MAX_LINE = 64 * 1024 * 1024; // a spawn carries --params-file contents

/**
 * Serve spawn requests on a Unix socket.
 * @param {string} path the socket's path (made by the launcher, in its private folder)
 * @param {object} hooks
 * @param {function(object, object): Promise<object>} hooks.spawn start a process of the plan's
 *   form with `{onLog, onExit}` and return its handle (`stop()`)
 * @param {function(): void} hooks.end the launcher said the launch has finished
 * @param {function(): Promise<object>} hooks.link start a bus process for the build host's
 *   rclpy (./host_link.mjs)
 * @param {function(string): void} hooks.err report a broken connection
 * @returns {Promise<net.Server>} once it listens
 */
export function serveProcesses(path, hooks) {
  const server = net.createServer((socket) => serveConnection(socket, hooks));
  return new Promise((resolve, reject) => {
    server.once('error', reject);
    server.listen(path, () => {
      server.off('error', reject);
      resolve(server);
    });
  });
}

function serveConnection(socket, hooks) {
  let buffered = '';
  const send = (message) => {
    if (!socket.destroyed) socket.write(`${JSON.stringify(message)}\n`);
  };
  const { onMessage, onClose } = processConnection({ send, end: () => socket.end() }, hooks);
  const { err } = hooks;
  socket.setEncoding('utf-8');
  socket.on('data', (chunk) => {
    buffered += chunk;
    if (buffered.length > MAX_LINE) {
      err('[ERROR] [launch]: a request of a process of the launch is too long; closing it');
      socket.destroy();
      return;
    }
    let at;
    while ((at = buffered.indexOf('\n')) >= 0) {
      const line = buffered.slice(0, at);
      buffered = buffered.slice(at + 1);
      if (!line.trim()) continue;
      let message;
      try {
        message = JSON.parse(line);
      } catch (e) {
        err(`[ERROR] [launch]: a process of the launch sent what is no JSON: ${e.message}`);
        socket.destroy();
        return;
      }
      onMessage(message).catch((e) => err(`[ERROR] [launch]: ${e && e.stack ? e.stack : e}`));
    }
  });
  socket.on('close', onClose);
  socket.on('error', () => {});
}
