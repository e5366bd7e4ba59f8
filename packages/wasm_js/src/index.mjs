// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * wasm_js: the JavaScript runtime of the colcon-wasm middleware. Its public
 * API: the Runtime and its processes, the tools process, the bus API of one
 * process (BusClient) with its errors, kinds and modes, and QoS profiles.
 *
 *   import { Runtime, IsolationError } from '.../wasm_js/src/index.mjs';
 *   const rt = await Runtime.create();
 *   const talker = await rt.spawn({ url: 'lib/demo_nodes/talker.js', onLog: console.log });
 *
 * @module wasm_js
 */

export { IsolationError, NodeProcess, Runtime } from './runtime.mjs';
export { Tools } from './tools_process/main_thread.mjs';
export {
  BusClient, BusError, Code, EventType, KIND_CLIENT, KIND_PUBLISHER, KIND_SERVICE,
  KIND_SUBSCRIPTION, TakeMode, WaitKind,
} from './bus_client.mjs';
export { EndpointKind } from './abi/bus_abi.mjs';
export {
  Durability, History, Liveliness, PolicyKind, Reliability, checkCompatible, decodeQos, encodeQos,
} from './qos.mjs';
