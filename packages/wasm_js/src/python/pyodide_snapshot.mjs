// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * A memory snapshot of a started Pyodide, shared by the Python nodes of one
 * host: the first Python node of a runtime has a worker load Pyodide once,
 * import the standard modules rclpy uses and rclpy itself
 * (SNAPSHOT_RCLPY_MODULES: its modules hold no bus and no JavaScript object
 * until a node attaches them) and take a snapshot of its memory (Pyodide's
 * `makeMemorySnapshot`); every Python node then starts from it
 * (`loadPyodide({_loadSnapshot})`) instead of starting the interpreter
 * anew, a few hundred milliseconds instead of seconds. The snapshot lives
 * in a SharedArrayBuffer, so the nodes share one copy.
 *
 * In Node.js the snapshot is also kept on disk
 * (`$COLCON_WASM_CACHE/pyodide-snapshots/`, default
 * `~/.cache/colcon-wasm`), keyed by Pyodide's version and binary, by the
 * prelude below and by rclpy's sources, so the next launch starts warm too.
 * `COLCON_WASM_PYODIDE_SNAPSHOT=0` (or the spawn option `snapshot: false`)
 * starts every node cold. A snapshot that cannot be made or loaded costs a
 * warning and a cold start, nothing else.
 *
 * @module python/pyodide_snapshot
 */

import { ProgramWorker, isNode, siblingUrl } from '../platform.mjs';
import { RCLPY_FILES, SNAPSHOT_RCLPY_MODULES } from './rclpy_files.mjs';

/**
 * The Python run before the snapshot: the standard modules rclpy and the
 * worker's runner import (no module that holds a JavaScript object: a
 * snapshot cannot keep one).
 */
export const SNAPSHOT_PRELUDE = [
  'import array, asyncio, asyncio.events, concurrent.futures, concurrent.futures.thread',
  'import enum, importlib.abc, importlib.machinery, inspect, json, os, struct, sys',
  'import threading, time, traceback, types, uuid',
  'import pyodide.ffi',
].join('\n');

/** Bumped when what a snapshot holds changes in a way the key does not see. */
const SNAPSHOT_FORMAT = 2;

/** runtime -> Map(where key -> Promise<{snapshot, notes}>) */
const perRuntime = new WeakMap();

/**
 * The snapshot for the Python nodes of `runtime` (made once per runtime and
 * Pyodide location; Node.js: read from the disk cache when it is there).
 * @param {object} runtime the Runtime the nodes run on
 * @param {{pyodideDir?: string, pyodideUrl?: string}} where the Pyodide folder or URL
 * @returns {Promise<{snapshot: SharedArrayBuffer|null, notes: string[]}>} the
 *   snapshot, or null with the reason in `notes` (warnings for the node's log)
 */
export function pyodideSnapshot(runtime, where) {
  if (isNode && process.env.COLCON_WASM_PYODIDE_SNAPSHOT === '0') {
    return Promise.resolve({ snapshot: null, notes: [] });
  }
  let made = perRuntime.get(runtime);
  if (!made) {
    made = new Map();
    perRuntime.set(runtime, made);
  }
  const key = where.pyodideDir || where.pyodideUrl;
  if (!made.has(key)) made.set(key, obtain(where));
  return made.get(key);
}

/**
 * Forget the snapshot of a runtime (a node could not start from it): the
 * next Python node makes a new one, and the disk copy is removed.
 * @param {object} runtime
 * @param {{pyodideDir?: string, pyodideUrl?: string}} where
 */
export async function dropPyodideSnapshot(runtime, where) {
  const made = perRuntime.get(runtime);
  if (made) made.delete(where.pyodideDir || where.pyodideUrl);
  if (isNode && where.pyodideDir) {
    const fs = await import('node:fs');
    try {
      fs.rmSync(await cacheFile(where.pyodideDir), { force: true });
    } catch (e) {
      // not removable: the next host tries it, fails the same way and starts anew
    }
  }
}

async function obtain(where) {
  const notes = [];
  const file = isNode && where.pyodideDir ? await cacheFile(where.pyodideDir) : null;
  if (file) {
    const kept = await readKept(file);
    if (kept) return { snapshot: kept, notes };
  }
  let snapshot;
  try {
    snapshot = await makeSnapshot(where);
  } catch (e) {
    notes.push(`cannot make a snapshot of Pyodide (${e.message}): this Python node starts Pyodide anew, `
      + 'which takes seconds; set COLCON_WASM_PYODIDE_SNAPSHOT=0 to skip the attempt');
    return { snapshot: null, notes };
  }
  if (file) {
    const reason = await keep(file, snapshot);
    if (reason) {
      notes.push(`cannot keep the Pyodide snapshot in ${file} (${reason}): the next launch makes it anew; `
        + 'set COLCON_WASM_CACHE to a writable folder');
    }
  }
  return { snapshot, notes };
}

/** Start a Python worker that loads Pyodide, runs the prelude and sends back its snapshot. */
async function makeSnapshot(where) {
  const worker = await ProgramWorker.start(siblingUrl('python/python_worker.mjs'),
    { name: 'python snapshot', type: 'module' });
  try {
    return await new Promise((resolve, reject) => {
      worker.on('message', (m) => {
        if (m && m.type === 'snapshot') resolve(m.snapshot);
        else if (m && m.type === 'snapshot-failed') reject(new Error(m.reason));
      });
      worker.on('error', (e) => reject(e));
      worker.on('exit', ({ code }) => reject(new Error(`its worker exited with code ${code}`)));
      worker.postMessage({ type: 'snapshot', prelude: SNAPSHOT_PRELUDE, ...where });
    });
  } finally {
    worker.terminate();
  }
}

/** Node.js: where the snapshot of this Pyodide folder is kept. */
async function cacheFile(pyodideDir) {
  const [fs, os, path, crypto] = await Promise.all(
    ['node:fs', 'node:os', 'node:path', 'node:crypto'].map((m) => import(m)));
  const wasm = fs.statSync(path.join(pyodideDir, 'pyodide.asm.wasm'));
  let version = '';
  try {
    version = JSON.parse(fs.readFileSync(path.join(pyodideDir, 'package.json'), 'utf8')).version;
  } catch (e) {
    // checked by spawn.mjs' checkPyodide; the binary's size and time tell versions apart anyway
  }
  const hash = crypto.createHash('sha256')
    .update(JSON.stringify([SNAPSHOT_FORMAT, version, wasm.size, wasm.mtimeMs, SNAPSHOT_PRELUDE,
      SNAPSHOT_RCLPY_MODULES]));
  for (const rel of RCLPY_FILES) hash.update(rel).update(fs.readFileSync(new URL(rel, import.meta.url)));
  const key = hash.digest('hex').slice(0, 16);
  const root = process.env.COLCON_WASM_CACHE || path.join(os.homedir(), '.cache', 'colcon-wasm');
  return path.join(root, 'pyodide-snapshots', `pyodide-${version}-${key}.snapshot`);
}

/** Node.js: the kept snapshot in a SharedArrayBuffer, or null when there is none. */
async function readKept(file) {
  const fs = await import('node:fs');
  let handle;
  try {
    handle = fs.openSync(file, 'r');
  } catch (e) {
    return null;
  }
  try {
    const size = fs.fstatSync(handle).size;
    const sab = new SharedArrayBuffer(size);
    const view = new Uint8Array(sab);
    for (let at = 0; at < size;) {
      const n = fs.readSync(handle, view, at, size - at, at);
      if (n <= 0) return null;
      at += n;
    }
    return sab;
  } catch (e) {
    return null;
  } finally {
    fs.closeSync(handle);
  }
}

/** Node.js: write the snapshot (whole or not at all: a temporary file renamed); the reason it failed, or ''. */
async function keep(file, snapshot) {
  const fs = await import('node:fs');
  const path = await import('node:path');
  const tmp = `${file}.${process.pid}.tmp`;
  try {
    fs.mkdirSync(path.dirname(file), { recursive: true });
    fs.writeFileSync(tmp, new Uint8Array(snapshot));
    fs.renameSync(tmp, file);
    return '';
  } catch (e) {
    try {
      fs.rmSync(tmp, { force: true });
    } catch (ignored) {
      // there is no temporary file when its folder could not be made
    }
    return e.message;
  }
}
