// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * wasm_js: the JavaScript runtime of the colcon-wasm middleware.
 *
 *   import { Runtime, IsolationError } from '.../wasm_js/src/index.mjs';
 *   const rt = await Runtime.create();
 *   const talker = await rt.spawn({ url: 'lib/demo_nodes/talker.js', onLog: console.log });
 *
 * @module wasm_js
 */

export { IsolationError, NodeProcess, Runtime, severityOf, stripAnsi } from './runtime.mjs';
export { Tools } from './tools.mjs';
export { BusClient, EventType, TakeMode, WaitKind } from './bus_client.mjs';
export {
  Bus, BusError, Code, KIND_CLIENT, KIND_PUBLISHER, KIND_SERVICE, KIND_SUBSCRIPTION,
} from './bus.mjs';
export {
  Durability, History, Liveliness, PolicyKind, Reliability, checkCompatible, decodeQos, encodeQos,
} from './qos.mjs';
