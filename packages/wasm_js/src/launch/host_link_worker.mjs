// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The bus process of the build host's rclpy (a Python launch file's launch_ros).
 *
 * launch_ros makes a ROS node in the launch process for LoadComposableNodes,
 * LifecycleNode transitions and its ROS events (ros_adapters.py). The launch
 * runs on the build host, in CPython: its rclpy is colcon-wasm's, whose
 * `_colcon_wasm_bus` functions (python/bus_module.mjs) run here, in a worker
 * that is one JS-only bus process (Runtime.helperProcess), called over the
 * launch's socket (process_server.mjs, rclpy/_host_link.py). Calls are
 * answered in order of completion: a wait of the spin thread does not hold up
 * a call of the launch's thread (the waits sleep with Atomics.waitAsync).
 *
 * The same worker runs in the page (a Web Worker) for a launch file that
 * `colcon-wasm serve` evaluates (templates/launcher/launch_files.mjs).
 *
 * Messages: {init: {bus, pid, types}} first (types: the types.json files'
 * paths in Node.js, their parsed documents in the page), then {id, fn, args};
 * answers {id, result} or {id, error: {name, message}}, and {log: {stream,
 * text}} for what the node logs. Values cross as JSON: 64-bit integers as
 * {$int: 'digits'}, typed arrays as lists.
 *
 * @module launch/host_link_worker
 */

import { BusClient } from '../bus_client.mjs';
import { TypeRegistry } from '../cdr.mjs';
import { isNode } from '../platform.mjs';
import { busModule } from '../python/bus_module.mjs';

const port = isNode ? (await import('node:worker_threads')).parentPort : null;
const post = (m) => (port ? port.postMessage(m) : globalThis.postMessage(m));

/** Replace what JSON cannot carry: BigInts, typed arrays. */
export function toWire(value) {
  if (typeof value === 'bigint') {
    return Number.isSafeInteger(Number(value)) ? Number(value) : { $int: value.toString() };
  }
  if (ArrayBuffer.isView(value)) return Array.from(value, toWire);
  if (Array.isArray(value)) return value.map(toWire);
  if (value && typeof value === 'object') {
    return Object.fromEntries(Object.entries(value).map(([k, v]) => [k, toWire(v)]));
  }
  return value;
}

/** Undo toWire's integers: {$int: 'digits'} is a BigInt. */
export function fromWire(value) {
  if (Array.isArray(value)) return value.map(fromWire);
  if (value && typeof value === 'object') {
    if (typeof value.$int === 'string' && Object.keys(value).length === 1) return BigInt(value.$int);
    return Object.fromEntries(Object.entries(value).map(([k, v]) => [k, fromWire(v)]));
  }
  return value;
}

/** The functions of bus_module.mjs that block, and their waitAsync forms. */
const ASYNC_FORMS = { wait: 'wait_async', wait_for_server: 'wait_for_server_async' };

let functions = null;

async function start({ bus, pid, types }) {
  const client = BusClient.attach(bus, pid);
  const registry = new TypeRegistry();
  const log = (stream, text) => post({ log: { stream: stream === 'stderr' ? 'stderr' : 'stdout', text: String(text) } });
  const readFile = isNode ? (await import('node:fs')).readFileSync : null;
  for (const entry of types || []) {
    try {
      registry.add(typeof entry === 'string' ? JSON.parse(readFile(entry, 'utf-8')) : entry);
    } catch (e) {
      const name = typeof entry === 'string' ? entry : 'of the page';
      log('stderr', `[WARNING] [launch_ros]: cannot read the type descriptions ${name}: ${e.message}`);
    }
  }
  functions = busModule(client, registry, client.createContext(), () => {}, null, log);
}

async function answer({ id, fn, args }) {
  try {
    const name = ASYNC_FORMS[fn] || fn;
    if (!functions || typeof functions[name] !== 'function' || name === 'log') {
      throw new TypeError(`the bus has no function '${fn}'`);
    }
    const result = await functions[name](...fromWire(args || []));
    post({ id, result: toWire(result === undefined ? null : result) });
  } catch (e) {
    post({ id, error: { name: e && e.name ? e.name : 'Error', message: e && e.message ? e.message : String(e) } });
  }
}

// calls wait for the start: it reads the type descriptions first
let started = null;
const onMessage = (message) => {
  if (message.init) started = start(message.init);
  else (started || Promise.resolve()).then(() => answer(message));
};
if (port) port.on('message', onMessage);
else if (typeof globalThis.WorkerGlobalScope !== 'undefined') globalThis.onmessage = (e) => onMessage(e.data);
