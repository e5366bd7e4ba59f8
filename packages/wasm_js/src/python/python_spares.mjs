// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Warm Python workers: once a runtime runs a Python node, it keeps one Python
 * worker ready, with Pyodide already loaded from the host's snapshot
 * (pyodide_snapshot.mjs) and rclpy imported, as the runtime keeps a warm
 * program worker for the executables (runtime.mjs `warmWorkers`). The next
 * Python node takes it, and starts in the time its script takes to create
 * its node: the load of Pyodide (a quarter of a second or more) was done
 * while nothing else started.
 *
 * A spare is made only from a snapshot (COLCON_WASM_PYODIDE_SNAPSHOT=0 or
 * the spawn option `snapshot: false` start every node cold, as before), only
 * after the Python node that asked for it has settled (it does not compete
 * with that node's start for the cores), one per runtime and Pyodide
 * location; it costs a worker and Pyodide's memory (about 40 MB) while it
 * waits. Runtime.close() ends it.
 *
 * @module python/python_spares
 */

import { ProgramWorker, siblingUrl } from '../platform.mjs';

/** Wait at most this long for the node that asked for a spare to settle. */
const FILL_AFTER_MS = 2000;

/** runtime -> Map(where key -> {worker: ProgramWorker|null, made: Promise<void>}) */
const perRuntime = new WeakMap();

function sparesOf(runtime) {
  let spares = perRuntime.get(runtime);
  if (!spares) {
    spares = new Map();
    perRuntime.set(runtime, spares);
    runtime._atClose(async () => {
      const all = [...spares.values()];
      spares.clear();
      await Promise.all(all.map((spare) => spare.made));
      for (const spare of all) if (spare.worker) spare.worker.terminate();
    });
  }
  return spares;
}

const keyOf = (where) => where.pyodideDir || where.pyodideUrl;

/**
 * Take the warm Python worker of `runtime` for Pyodide at `where`, if one is
 * started (it may still be loading Pyodide: the node's start then waits for
 * that, which is still sooner than a new worker).
 * @param {object} runtime
 * @param {{pyodideDir?: string, pyodideUrl?: string}} where
 * @returns {ProgramWorker|null} a worker that was sent the preload (the `start`
 *   message comes next), or null
 */
export function takeSparePython(runtime, where) {
  const spares = perRuntime.get(runtime);
  const spare = spares && spares.get(keyOf(where));
  if (!spare || !spare.worker) return null;
  spares.delete(keyOf(where));
  return spare.worker;
}

/**
 * Have a warm Python worker made for the next Python node of `runtime`, once
 * `after` has resolved (the node that asks has settled) or FILL_AFTER_MS passed.
 * @param {object} runtime
 * @param {{pyodideDir?: string, pyodideUrl?: string}} where
 * @param {SharedArrayBuffer} snapshot the host's Pyodide snapshot
 * @param {Promise<void>} after
 */
export function fillSparePython(runtime, where, snapshot, after) {
  if (runtime._closed) return;
  const spares = sparesOf(runtime);
  const key = keyOf(where);
  if (spares.has(key)) return;
  const spare = { worker: null, made: null };
  let timer = null;
  const later = new Promise((resolve) => {
    timer = setTimeout(resolve, FILL_AFTER_MS);
    if (timer && typeof timer.unref === 'function') timer.unref();
  });
  spare.made = Promise.race([after, later]).then(async () => {
    clearTimeout(timer);
    if (runtime._closed || spares.get(key) !== spare) return;
    let worker;
    try {
      worker = await ProgramWorker.start(siblingUrl('python/python_worker.mjs'),
        { name: 'python (warm)', type: 'module' });
    } catch (e) {
      spares.delete(key); // no spare: the next node starts its own worker, as this one did
      return;
    }
    if (spares.get(key) !== spare) {
      worker.terminate(); // the runtime closed meanwhile
      return;
    }
    worker.on('exit', () => {
      if (spares.get(key) === spare) spares.delete(key);
    });
    worker.postMessage({ type: 'preload', name: 'python (warm worker)', snapshot, ...where });
    spare.worker = worker;
  });
  spares.set(key, spare);
}
