// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The Zenoh gateway of `colcon-wasm run|launch --zenoh ENDPOINT`
 * (`plan.zenoh`: {endpoint, domain, module}), started on the launch's
 * Runtime before its processes, in Node.js (in a worker of its own,
 * gateway.mjs): the module is the zenoh-pico build of the install's
 * zenoh_wasm_gateway package.
 *
 * @module bridges/zenoh/launch
 */

import { readFile } from 'node:fs/promises';
import { pathToFileURL } from 'node:url';

/**
 * The Emscripten factory of a zenoh_session.mjs file, with its .wasm read
 * from the folder beside it (the glue is built for the web: Node.js hands
 * it the bytes).
 * @param {string} path
 */
export async function nodeModuleFactory(path) {
  const { default: factory } = await import(pathToFileURL(path).href);
  const wasmBinary = await readFile(path.replace(/\.mjs$/, '.wasm'));
  return (options) => factory({ ...options, wasmBinary });
}

/**
 * Start the gateway a plan asks for.
 * @returns {Promise<function(): Promise<void>>} its closer
 */
export async function startZenoh(spec, runtime, registry, { out, err }) {
  const { ZenohGateway } = await import('./gateway.mjs');
  const log = (level, text) => {
    if (level === 'debug' && !process.env.COLCON_WASM_ZENOH_DEBUG) return;
    const tag = { info: 'INFO', warning: 'WARNING', error: 'ERROR', debug: 'DEBUG' }[level] || 'INFO';
    (level === 'error' || level === 'warning' ? err : out)(`[${tag}] [zenoh]: ${text}`);
  };
  const gateway = await ZenohGateway.start({
    runtime, registry, endpoint: spec.endpoint, domain: spec.domain || 0, module: spec.module, log,
  });
  return async () => {
    const s = gateway.status();
    if (s.counters.lost || s.counters.malformed) {
      log('warning', `${s.counters.lost} messages lost while the router was away, ${s.counters.malformed} samples or calls without rmw_zenoh's attachment`);
    }
    await gateway.close();
  };
}
