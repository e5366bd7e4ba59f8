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
 * Wire format, one JSON object per line on a Unix stream socket:
 *   shim -> host  {op: 'spawn', process: {...one process of a host plan..., args, env, files}}
 *                 {op: 'signal', name: 'SIGINT'|'SIGTERM'|'SIGKILL'}
 *   host -> shim  {ev: 'started', label}
 *                 {ev: 'log', stream: 'stdout'|'stderr', text}
 *                 {ev: 'exit', code, crashed, reason}
 *   launcher -> host  {op: 'end'}: the launch has finished; stop what is left
 *   rclpy -> host  {op: 'link'}, answered {ev: 'linked'}, then {id, fn, args} calls of the
 *                  bus functions, answered {id, result} or {id, error} (./host_link_worker.mjs)
 * A connection is one process, or one link; closing it stops the process (the shim was
 * killed), or removes the link's bus process.
 */

import net from 'node:net';

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

function serveConnection(socket, { spawn, end, link, err }) {
  let buffered = '';
  let handle = null;
  let linked = null;
  let pending = null; // a signal that came before the process started
  let exited = false;
  const send = (message) => {
    if (!socket.destroyed) socket.write(`${JSON.stringify(message)}\n`);
  };
  const stop = () => {
    if (handle && !exited) handle.stop();
  };
  const onRequest = async (message) => {
    if (linked && message.id !== undefined) {
      linked.post(message);
    } else if (message.op === 'link') {
      linked = await link();
      linked.onAnswer(send);
      send({ ev: 'linked' });
    } else if (message.op === 'end') {
      end();
    } else if (message.op === 'spawn') {
      if (handle || pending === 'spawning') {
        send({ ev: 'exit', code: null, crashed: true, reason: 'one process per connection' });
        return;
      }
      pending = 'spawning';
      const proc = message.process;
      try {
        handle = await spawn(proc, {
          onLog: ({ stream, text }) => send({ ev: 'log', stream, text: String(text) }),
          onExit: ({ code, crashed, reason }) => {
            exited = true;
            send({ ev: 'exit', code: code ?? null, crashed: !!crashed, reason: reason || '' });
            socket.end();
          },
        });
      } catch (e) {
        exited = true;
        send({ ev: 'exit', code: null, crashed: true, reason: e && e.message ? e.message : String(e) });
        socket.end();
        return;
      }
      const signalled = pending !== 'spawning';
      pending = null;
      if (!exited) send({ ev: 'started', label: proc.label });
      if (signalled) stop();
    } else if (message.op === 'signal') {
      // a wasm program has no signal handlers of its own: every signal stops it, as
      // rclcpp's SIGINT handler ends a node natively (its exit then reads as clean)
      if (handle) stop();
      else pending = message.name;
    } else {
      err(`[WARNING] [launch]: unknown request '${message.op}' from a process of the launch`);
    }
  };
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
      onRequest(message).catch((e) => err(`[ERROR] [launch]: ${e && e.stack ? e.stack : e}`));
    }
  });
  // the shim was killed (SIGKILL) or ended: its program goes too; a link's bus process too
  socket.on('close', () => {
    stop();
    if (linked) linked.close();
  });
  socket.on('error', () => {});
}
