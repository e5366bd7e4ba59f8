// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * Loading composable nodes into containers, as launch_ros' (Humble)
 * LoadComposableNodes does it for `colcon-wasm launch`: wait for the
 * container's `<container>/_container/load_node` service
 * (composition_interfaces/srv/LoadNode), then call it once per node, in
 * order, and report each answer on the logger
 * `launch_ros.actions.load_composable_nodes`:
 *
 *   [INFO] [launch_ros.actions.load_composable_nodes]: Loaded node '/talker' in container '/c'
 *   [ERROR] [launch_ros.actions.load_composable_nodes]: Failed to load node 'x' of type 'p::X' in container '/c': <why>
 *
 * Any container that serves the service works. Unlike launch_ros, the wait
 * is bounded (`timeoutMs`, for the service and for each answer) and ends at
 * once when every process of the launch with the container's name has
 * exited, so that a launch never hangs. Loads into one container are made
 * one at a time, in the order of the launch file.
 *
 * The requests come ready from colcon_wasm/launch/composable.py: LoadNode
 * request objects whose int64 values are decimal strings (cdr.mjs encodes
 * them exactly).
 */

export const LOGGER = 'launch_ros.actions.load_composable_nodes';

/** A wait given up because the launch is shutting down: not a failure, as in launch_ros. */
class Abandoned extends Error {}

function hasServer(graph, service) {
  return (graph.services || []).some((s) => s.name === service && s.servers.length > 0);
}

/** Loads the composable nodes of a launch plan (`plan.loads`). */
export class ComposableLoader {
  /**
   * @param {object} options
   * @param {object} options.runtime the wasm_js Runtime (graph, onGraphChange)
   * @param {function(): Promise<object>} options.tools the Runtime's tools (service calls)
   * @param {object} options.registry a TypeRegistry (cdr.mjs) with the LoadNode types
   * @param {number} options.timeoutMs bound of each wait
   * @param {function(string): boolean} options.isRunning whether a process (by label) runs
   * @param {function(string): void} options.out writes a line to stdout
   * @param {function(string): void} options.err writes a line to stderr
   */
  constructor({ runtime, tools, registry, timeoutMs, isRunning, out, err }) {
    this._runtime = runtime;
    this._tools = tools;
    this._registry = registry;
    this._timeoutMs = timeoutMs;
    this._isRunning = isRunning;
    this._out = out;
    this._err = err;
    this._queues = new Map();
    this._checks = new Set();
    this._stopping = false;
  }

  /**
   * Load one group of nodes (a node_container's or a load_composable_node's),
   * after the loads queued before it into the same container.
   * @param {object} group {target, service, type, containers, where, requests}
   * @returns {Promise<boolean>} true when every node of the group was loaded
   */
  load(group) {
    const previous = this._queues.get(group.service) || Promise.resolve();
    const run = previous.catch(() => {}).then(() => this._loadGroup(group));
    this._queues.set(group.service, run);
    return run;
  }

  /** Re-check the waits: a process of the launch has exited. */
  processExited() {
    for (const check of [...this._checks]) check();
  }

  /** Give up every wait: the launch is shutting down. */
  shutdown() {
    this._stopping = true;
    this.processExited();
  }

  async _loadGroup(group) {
    try {
      await this._waitForService(group);
    } catch (e) {
      if (e instanceof Abandoned) return this._abandon(group);
      for (const request of group.requests) this._fail(group, request, e.message);
      return false;
    }
    let ok = true;
    for (const request of group.requests) {
      if (this._stopping) return this._abandon(group) && ok;
      try {
        const response = await this._call(group, request);
        if (response.success) {
          this._out(`[INFO] [${LOGGER}]: Loaded node '${response.full_node_name}' in container '${group.target}'`);
          continue;
        }
        this._fail(group, request, response.error_message, response.full_node_name);
      } catch (e) {
        if (e instanceof Abandoned) return this._abandon(group) && ok;
        this._fail(group, request, e.message);
      }
      ok = false;
    }
    return ok;
  }

  _abandon(group) {
    this._err(`[WARNING] [${LOGGER}]: Abandoning wait for the '${group.service}' service, due to shutdown.`);
    return true;
  }

  _fail(group, request, why, fullName) {
    // WebAssembly has no dlopen: a container hosts what was linked into it
    const hosts = group.hosts && group.hosts.length
      ? ` (the container was linked with: ${group.hosts.join(', ')})` : '';
    this._err(`[ERROR] [${LOGGER}]: Failed to load node '${fullName || request.node_name}' of type `
      + `'${request.plugin_name}' in container '${group.target}': ${why}${hosts}`);
  }

  _waitForService(group) {
    return new Promise((resolve, reject) => {
      let timer = null;
      let unsubscribe = () => {};
      const finish = (settle, value) => {
        clearTimeout(timer);
        unsubscribe();
        this._checks.delete(check);
        settle(value);
      };
      const check = () => {
        if (this._stopping) {
          finish(reject, new Abandoned());
        } else if (hasServer(this._runtime.graph(), group.service)) {
          finish(resolve);
        } else if (group.containers.length && !group.containers.some((label) => this._isRunning(label))) {
          finish(reject, new Error(`the container process ${group.containers.map((l) => `'${l}'`).join(', ')} `
            + `exited before its service '${group.service}' appeared`));
        }
      };
      const seconds = this._timeoutMs / 1000;
      timer = setTimeout(() => finish(reject, new Error(
        `the service '${group.service}' did not appear within ${seconds} s`
        + `${group.where ? ` (${group.where})` : ''}: is '${group.target}' a running `
        + 'component container? --load-timeout S waits longer')), this._timeoutMs);
      this._checks.add(check);
      unsubscribe = this._runtime.onGraphChange(check);
      check();
    });
  }

  async _call(group, request) {
    const registry = this._registry;
    let types;
    try {
      types = registry.service(group.type);
    } catch (e) {
      throw new Error(`cannot encode the request: ${e.message}`);
    }
    const bytes = registry.encode(types.request, request);
    const tools = await this._tools();
    let reply;
    try {
      reply = await tools.call({ service: group.service, type: group.type, qos: {}, timeoutMs: this._timeoutMs }, bytes);
    } catch (e) {
      if (this._stopping) throw new Abandoned();
      throw new Error(`no answer: ${e.message}; --load-timeout S waits longer`);
    }
    return registry.decode(types.response, reply.data);
  }
}
