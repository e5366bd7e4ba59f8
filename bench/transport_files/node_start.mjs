// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Node start as bench/transport and bench/rclcpp both measure it: from the
 * moment spawn() is called to the source timestamp of the first message the
 * executable publishes on /bench/hello, as the Runtime's tools worker sees it.
 *
 * @module node_start
 */

/**
 * Spawn `url` once on `rt` and time its first message.
 * @param {object} rt a Runtime of its own (the caller closes it)
 * @param {object} spec
 * @param {string} spec.url the executable's glue (URL or file path)
 * @param {string[]} spec.args its arguments (a role that publishes once on /bench/hello)
 * @param {string} spec.type the message type it publishes
 * @param {boolean} [spec.shareModule=true] instantiate the runtime's compiled
 *   module (compiled before the clock starts), or compile in the worker
 * @returns {Promise<number>} milliseconds
 */
export async function measureNodeStart(rt, { url, args, type, shareModule = true }) {
  const tools = await rt.tools();
  let resolveFirst;
  const first = new Promise((r) => { resolveFirst = r; });
  const sub = await tools.subscribe({ topic: '/bench/hello', type },
    (batch) => resolveFirst(batch[0].info.sourceTime));
  const wasmUrl = new URL(url.replace(/\.js$/, '.wasm'),
    typeof location === 'undefined' ? 'file:///' : location.href).href;
  if (shareModule) await rt.compiledModule(wasmUrl);
  await rt.warm();
  const t0 = performance.timeOrigin + performance.now();
  const proc = await rt.spawn({ url, args, name: 'hello', shareModule });
  const sourceTime = await first;
  await proc.exited;
  await sub.close();
  return sourceTime - t0;
}
