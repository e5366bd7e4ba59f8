// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The Foxglove server of `colcon-wasm run|launch --foxglove` (`plan.foxglove`:
 * {host, port, queueMessages, schemas, shares}), started with the rosbridge bridges
 * (../rosbridge/launch.mjs) on the launch's Runtime before its processes.
 *
 * @module bridges/foxglove/launch
 */

/**
 * Start the Foxglove server a plan entry asks for.
 * @param {{host: string, port: number, queueMessages: number, schemas: string, shares: Object<string, string>}} spec
 * @param {import('../../runtime.mjs').Runtime} runtime
 * @param {import('../../cdr.mjs').TypeRegistry} registry
 * @param {{out: function(string): void, err: function(string): void}} io
 * @returns {Promise<function(): Promise<void>>} stop it
 * @throws {Error} FoxgloveError with a message for the user (a port in use, ...)
 */
export async function startFoxglove(spec, runtime, registry, { out, err }) {
  const { FoxgloveServer } = await import('./server.mjs');
  const log = (level, text) => {
    if (level === 'debug' && !process.env.COLCON_WASM_FOXGLOVE_DEBUG) return;
    const tag = { info: 'INFO', warning: 'WARNING', error: 'ERROR', debug: 'DEBUG' }[level] || 'INFO';
    (level === 'error' || level === 'warning' ? err : out)(`[${tag}] [foxglove]: ${text}`);
  };
  const server = await FoxgloveServer.start({
    runtime, registry, schemas: spec.schemas, shares: spec.shares, host: spec.host, port: spec.port,
    queueMessages: spec.queueMessages || 10, log,
  });
  log('info', `foxglove server listening on ${server.url}`);
  return () => server.close();
}
