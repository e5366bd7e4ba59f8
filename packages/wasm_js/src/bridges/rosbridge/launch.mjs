// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The bridges of `colcon-wasm run|launch` (launch/run_plan.mjs): the
 * rosbridge server (`plan.rosbridge`: {host, port, token, capabilities,
 * limits, schemas}) and the client to a remote rosbridge server
 * (`plan.rosbridge_connect`: {url, token, allow, deny, limits}), started on
 * the launch's Runtime before its processes; and the Foxglove server
 * (`plan.foxglove`, ../foxglove/launch.mjs); and the Zenoh gateway
 * (`plan.zenoh`, ../zenoh/launch.mjs).
 *
 * @module bridges/rosbridge/launch
 */

/**
 * Start the bridges a plan asks for.
 * @param {object} plan the launch plan (colcon_wasm/launch/runner.py)
 * @param {import('../../runtime.mjs').Runtime} runtime
 * @param {import('../../cdr.mjs').TypeRegistry} registry
 * @param {{out: function(string): void, err: function(string): void}} io
 * @returns {Promise<{close: function(): Promise<void>}>}
 * @throws {Error} with a message for the user (a port in use, ...)
 */
export async function startBridges(plan, runtime, registry, { out, err }) {
  const closers = [];
  const log = (level, text) => {
    if (level === 'debug' && !process.env.COLCON_WASM_ROSBRIDGE_DEBUG) return;
    const tag = { info: 'INFO', warning: 'WARNING', error: 'ERROR', debug: 'DEBUG' }[level] || 'INFO';
    (level === 'error' || level === 'warning' ? err : out)(`[${tag}] [rosbridge]: ${text}`);
  };
  if (plan.rosbridge) {
    const { RosbridgeServer } = await import('./server.mjs');
    const spec = plan.rosbridge;
    const server = await RosbridgeServer.start({
      runtime, registry, host: spec.host, port: spec.port, token: spec.token,
      capabilities: spec.capabilities || null, limits: spec.limits || {}, schemas: spec.schemas || null, log,
    });
    log('info', `rosbridge server listening on ${server.url}${spec.token ? ' (token required)' : ''}`);
    closers.push(() => server.close());
  }
  if (plan.rosbridge_connect) {
    const { RosbridgeClient } = await import('./client.mjs');
    const { NodeWebSocket } = await import('./ws_node.mjs');
    const spec = plan.rosbridge_connect;
    const client = await RosbridgeClient.start({
      runtime, registry, url: spec.url, token: spec.token, allow: spec.allow, deny: spec.deny,
      limits: spec.limits || {}, WebSocket: NodeWebSocket, log,
    });
    closers.push(() => client.close());
  }
  if (plan.foxglove) {
    const { startFoxglove } = await import('../foxglove/launch.mjs');
    closers.push(await startFoxglove(plan.foxglove, runtime, registry, { out, err }));
  }
  if (plan.zenoh) {
    const { startZenoh } = await import('../zenoh/launch.mjs');
    closers.push(await startZenoh(plan.zenoh, runtime, registry, { out, err }));
  }
  return {
    close: async () => {
      for (const c of closers.reverse()) await c().catch(() => {});
    },
  };
}
