// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * One connection of a Python launch file's host programs to the bus, whatever
 * carries it: a Unix socket of `colcon-wasm launch` (./process_server.mjs, in
 * Node.js), or a channel of the page's `/launch` WebSocket of `colcon-wasm
 * serve` (templates/launcher/launch_files.mjs, in the browser).
 *
 * Messages, one JSON object each:
 *   shim -> bus  {op: 'spawn', process: {...one process of a host plan..., args, env, files}}
 *                {op: 'signal', name: 'SIGINT'|'SIGTERM'|'SIGKILL'}
 *   bus -> shim  {ev: 'started', label}
 *                {ev: 'log', stream: 'stdout'|'stderr', text}
 *                {ev: 'exit', code, crashed, reason}
 *   launcher -> bus  {op: 'end'}: the launch has finished; stop what is left
 *   rclpy -> bus  {op: 'link'}, answered {ev: 'linked'}, then {id, fn, args} calls of the
 *                 bus functions, answered {id, result} or {id, error} (./host_link_worker.mjs)
 * A connection is one process, or one link; closing it stops the process (the shim was
 * killed), or removes the link's bus process.
 *
 * @module launch/process_protocol
 */

/**
 * Serve one connection.
 * @param {object} io
 * @param {function(object): void} io.send send one message to the host program
 * @param {function(): void} io.end close the connection once the process has exited
 * @param {object} hooks
 * @param {function(object, object): Promise<object>} hooks.spawn start a process of the plan's
 *   form with `{onLog, onExit}` and return its handle (`stop()`)
 * @param {function(): void} hooks.end the launcher said the launch has finished
 * @param {function(): Promise<object>} hooks.link start a bus process for the build host's
 *   rclpy: `{post(message), onAnswer(fn), close()}` (./host_link.mjs)
 * @param {function(string): void} hooks.err report a request that makes no sense
 * @returns {{onMessage: function(object): Promise<void>, onClose: function(): void}}
 */
export function processConnection({ send, end: endConnection }, { spawn, end, link, err }) {
  let handle = null;
  let linked = null;
  let pending = null; // a signal that came before the process started
  let exited = false;
  const stop = () => {
    if (handle && !exited) handle.stop();
  };
  const finish = (exit) => {
    exited = true;
    send({ ev: 'exit', code: exit.code ?? null, crashed: !!exit.crashed, reason: exit.reason || '' });
    endConnection();
  };
  const onSpawn = async (proc) => {
    if (handle || pending === 'spawning') {
      send({ ev: 'exit', code: null, crashed: true, reason: 'one process per connection' });
      return;
    }
    pending = 'spawning';
    try {
      handle = await spawn(proc, {
        onLog: ({ stream, text }) => send({ ev: 'log', stream, text: String(text) }),
        onExit: finish,
      });
    } catch (e) {
      finish({ code: null, crashed: true, reason: e && e.message ? e.message : String(e) });
      return;
    }
    const signalled = pending !== 'spawning';
    pending = null;
    if (!exited) send({ ev: 'started', label: proc.label });
    if (signalled) stop();
  };
  const onMessage = async (message) => {
    if (linked && message.id !== undefined) {
      linked.post(message);
    } else if (message.op === 'link') {
      linked = await link();
      linked.onAnswer(send);
      send({ ev: 'linked' });
    } else if (message.op === 'end') {
      end();
    } else if (message.op === 'spawn') {
      await onSpawn(message.process);
    } else if (message.op === 'signal') {
      // a wasm program has no signal handlers of its own: every signal stops it, as
      // rclcpp's SIGINT handler ends a node natively (its exit then reads as clean)
      if (handle) stop();
      else pending = message.name;
    } else {
      err(`[WARNING] [launch]: unknown request '${message.op}' from a process of the launch`);
    }
  };
  // the shim was killed (SIGKILL) or ended: its program goes too; a link's bus process too
  const onClose = () => {
    stop();
    if (linked) linked.close();
  };
  return { onMessage, onClose };
}
