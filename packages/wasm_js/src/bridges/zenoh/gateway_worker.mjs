// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The Zenoh gateway's worker (started by gateway.mjs): zenoh-pico, its
 * socket and the gateway's bus process in one thread of their own, so that
 * a message goes from the bus to the router without the page's (or the
 * launch's) main thread and without a postMessage. Messages with the main
 * thread (the structured clones of gateway.mjs):
 * - in: {type: 'start', bus, pid, options: {endpoint, domain, limits, module, types}};
 *   {type: 'close'};
 * - out: {type: 'log', level, text}; {type: 'state', state, zid, remote, status};
 *   {type: 'closed'}.
 *
 * @module bridges/zenoh/gateway_worker
 */

import { isNode } from '../../platform.mjs';
import { GATEWAY_NODE, GatewayCore, knownTypes } from './core.mjs';
import { GatewayBus } from './gateway_bus.mjs';

/** While messages flow, the counters reach the main thread this often. */
const STATUS_INTERVAL_MS = 250;

let port = null;
if (isNode) port = (await import('node:worker_threads')).parentPort;
const post = (m) => (port ? port.postMessage(m) : self.postMessage(m));

let core = null;
let statusTimer = null;
let lastStatus = '';

function postState() {
  if (!core) return;
  const status = core.status();
  lastStatus = JSON.stringify(status.counters);
  post({ type: 'state', state: core.state, zid: status.zid, remote: core.remote, status });
}

/** The Emscripten factory of zenoh_session.mjs (Node.js: its .wasm read from beside it). */
async function moduleFactory(module) {
  if (isNode) {
    const { nodeModuleFactory } = await import('./launch.mjs');
    const { fileURLToPath } = await import('node:url');
    return nodeModuleFactory(module.startsWith('file:') ? fileURLToPath(module) : module);
  }
  return (await import(module)).default;
}

async function start({ bus: handle, pid, options }) {
  const log = (level, text) => post({ type: 'log', level, text });
  const bus = GatewayBus.attach(handle, pid, { name: GATEWAY_NODE, domain: options.domain || 0 });
  bus.onError = (error) => log('error', `the gateway's bus process failed: ${error.stack || error.message}`);
  const WS = isNode ? (await import('../rosbridge/ws_node.mjs')).NodeWebSocket : globalThis.WebSocket;
  core = new GatewayCore(bus, {
    registry: knownTypes(options.types || {}), endpoint: options.endpoint, domain: options.domain || 0,
    limits: options.limits, createModule: await moduleFactory(options.module), WebSocket: WS, log,
    onChange: postState,
  });
  statusTimer = setInterval(() => {
    if (core && JSON.stringify(core.status().counters) !== lastStatus) postState();
  }, STATUS_INTERVAL_MS);
  if (statusTimer.unref) statusTimer.unref();
  core.start();
}

async function onMessage(m) {
  if (!m) return;
  if (m.type === 'start') {
    try {
      await start(m);
    } catch (error) {
      post({ type: 'log', level: 'error', text: `the Zenoh gateway did not start: ${error.stack || error.message}` });
    }
  } else if (m.type === 'close') {
    clearInterval(statusTimer);
    if (core) await core.close();
    post({ type: 'closed' });
  }
}

if (port) port.on('message', onMessage);
else self.onmessage = (e) => onMessage(e.data);
