// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Python nodes: a Python script run by Pyodide in its own worker, as a bus
 * process beside the Emscripten executables (the `rclpy` of
 * `python/rclpy/`): a worker thread in Node.js, a module Web Worker in a
 * browser; see docs/python.md of colcon-wasm.
 *
 *   import { spawnPython } from '.../wasm_js/src/python/spawn.mjs';
 *   // Node.js: the script's path and the npm package's folder
 *   const proc = await spawnPython(runtime, { file: '/ws/talker.py', pyodideDir, types,
 *     onLog, onExit });
 *   // browser: its text and the URL Pyodide is served at (colcon-wasm serve: /pyodide/)
 *   const proc = await spawnPython(runtime, { file: '/python/talker.py', source, pyodideUrl,
 *     types, onLog, onExit });
 *
 * The process is a NodeProcess of the runtime (logs, exit, stop(), graph
 * clean-up are the executables'): the worker speaks the program worker protocol
 * (protocol.mjs FromWorker).
 *
 * @module python/spawn
 */

import { BusError, Code } from '../bus.mjs';
import { FromWorker } from '../protocol.mjs';
import { PROC_KIND_NODE } from '../layout.mjs';
import { ProgramWorker, isNode, siblingUrl } from '../platform.mjs';
import { makeStdinPipe } from '../node_process.mjs';
import { NodeProcess } from '../runtime.mjs';
import { dropPyodideSnapshot, pyodideSnapshot } from './pyodide_snapshot.mjs';
import { fillSparePython, takeSparePython } from './python_spares.mjs';

/** The Pyodide release (npm package `pyodide`) this runtime is written and tested for. */
export const PYODIDE_VERSION = '314.0.8';

/** The files of the npm package that a Python node loads (nothing comes from a CDN). */
export const PYODIDE_FILES = ['pyodide.mjs', 'pyodide.asm.mjs', 'pyodide.asm.wasm', 'python_stdlib.zip', 'pyodide-lock.json'];

/**
 * Check a Pyodide folder (the npm package's): its files and its version.
 * @param {string} dir the folder holding pyodide.mjs (node_modules/pyodide)
 * @returns {Promise<string>} the version found
 * @throws {BusError} naming what is missing and how to get it
 */
export async function checkPyodide(dir) {
  const fix = `install it with 'npm install --prefix DIR pyodide@${PYODIDE_VERSION}' and name `
    + "DIR/node_modules/pyodide with COLCON_WASM_PYODIDE (see 'colcon-wasm doctor')";
  if (!dir) throw new BusError(Code.INVALID_ARGUMENT, `a Python node needs Pyodide ${PYODIDE_VERSION}: ${fix}`);
  const fs = await import('node:fs');
  const path = await import('node:path');
  const missing = PYODIDE_FILES.filter((f) => !fs.existsSync(path.join(dir, f)));
  if (missing.length) {
    throw new BusError(Code.INVALID_ARGUMENT, `the Pyodide folder '${dir}' lacks ${missing.join(', ')}: ${fix}`);
  }
  let version = 'unknown';
  try {
    version = JSON.parse(fs.readFileSync(path.join(dir, 'package.json'), 'utf8')).version;
  } catch (e) {
    // no package.json: checked below
  }
  if (version !== PYODIDE_VERSION) {
    throw new BusError(Code.INVALID_ARGUMENT,
      `Incorrect Pyodide version ${version} in '${dir}'. Need Pyodide version ${PYODIDE_VERSION}: ${fix}`);
  }
  return version;
}

/**
 * Run a Python script as a bus process.
 * @param {import('../runtime.mjs').Runtime} runtime
 * @param {object} spec
 * @param {string} spec.file the script (absolute path); it runs as `__main__`
 * @param {string} [spec.source] its text (default: read from `file`)
 * @param {{module: string, function: string}} [spec.entry] a console_scripts entry point of
 *   a Python package: `file` is its installed script, and what runs is what setuptools'
 *   script does, `sys.exit(function())` after `from module import function`
 * @param {string[]} [spec.pythonPath] folders of Python modules, put first on sys.path
 *   (the install space's packages, highest priority first); Node.js: the host's folders,
 *   seen read-only at the same paths
 * @param {Array<{path: string, text: string}>} [spec.pythonFiles] browser: the files of
 *   those folders, written at their paths
 * @param {string[]} [spec.args] sys.argv[1:]
 * @param {Object<string, string>} [spec.env] os.environ
 * @param {string} [spec.name] a name for logs (default: the file's base name)
 * @param {string} [spec.pyodideDir] Node.js: the npm package `pyodide` (folder of pyodide.mjs)
 * @param {string} [spec.pyodideUrl] browser: the URL of that folder, served with the page
 * @param {Array<object|string>} [spec.types] types.json documents, or (Node.js) their paths
 * @param {string|Uint8Array|boolean} [spec.stdin] standard input, as Runtime.spawn's
 *   (`true`: an open one, written with NodeProcess.writeStdin; the page's console)
 * @param {boolean} [spec.snapshot] false: start Pyodide anew rather than from the host's
 *   snapshot (pyodide_snapshot.mjs)
 * @param {function(object): void} [spec.onLog] as Runtime.spawn's
 * @param {function(object): void} [spec.onExit] as Runtime.spawn's
 * @returns {Promise<NodeProcess>}
 */
export async function spawnPython(runtime, spec) {
  if (runtime._closed) throw new BusError(Code.ERROR, 'spawnPython: the runtime is closed');
  if (!spec || !spec.file) throw new BusError(Code.INVALID_ARGUMENT, 'spawnPython: missing file (the Python script)');
  const { file, name, source, types, where } = isNode ? await nodeSpec(spec) : browserSpec(spec);
  const env = {};
  for (const [k, v] of Object.entries(spec.env || {})) env[k] = String(v);
  // the host's snapshot of a started Pyodide (made by the first Python node, shared by all)
  const { snapshot, notes } = spec.snapshot === false ? { snapshot: null, notes: [] }
    : await pyodideSnapshot(runtime, where);
  const pid = await runtime._allocPid(PROC_KIND_NODE);
  // the runtime's warm Python worker (Pyodide loaded already), when it has one
  let worker = snapshot ? takeSparePython(runtime, where) : null;
  const warm = worker !== null;
  try {
    if (!worker) worker = await ProgramWorker.start(siblingUrl('python/python_worker.mjs'), { name: `python ${name}`, type: 'module' });
  } catch (e) {
    await runtime._reap(pid, null);
    throw new BusError(Code.ERROR, `spawnPython '${name}': cannot start a worker: ${e.message}`);
  }
  const stdinPipe = makeStdinPipe(spec.stdin);
  const proc = new NodeProcess(runtime, pid, name, worker, { ...spec, spawnedAt: performance.now(), stdinPipe });
  proc.warmPythonWorker = warm;
  runtime.processes.set(pid, proc);
  worker.on('message', (m) => {
    if (snapshot && m && m.type === FromWorker.STARTED) {
      // a snapshot that loaded: a warm worker is made from it for the next Python node
      if (m.pyodideSnapshot) fillSparePython(runtime, where, snapshot, proc.settled);
      else dropPyodideSnapshot(runtime, where);
    }
    proc._onMessage(m);
  });
  worker.on('error', (e) => proc._finish({ code: 1, crashed: true, reason: `uncaught error in the Python worker: ${e.message}` }));
  worker.on('exit', ({ code }) => {
    proc._finish({ code, crashed: code !== 0, reason: code !== 0 ? `worker exited with code ${code}` : '' });
  });
  worker.postMessage({
    type: 'start', bus: runtime.bus.handle, pid, name, file, source, args: (spec.args || []).map(String), env,
    types, stdin: stdinPipe && stdinPipe.sab, pythonPath: (spec.pythonPath || []).map(String),
    pythonFiles: isNode ? [] : (spec.pythonFiles || []), snapshot: warm ? null : snapshot, notes, ...where,
    module: spec.entry ? spec.entry.module : null,
  });
  return proc;
}

/**
 * The text of a console_scripts entry point's script: what setuptools writes,
 * without its lookup of the distribution (the module is on sys.path).
 */
export function entryPointSource({ module, function: func }) {
  const name = /^[A-Za-z_][A-Za-z0-9_]*(\.[A-Za-z_][A-Za-z0-9_]*)*$/;
  if (!name.test(String(module)) || !name.test(String(func))) {
    throw new BusError(Code.INVALID_ARGUMENT, `the entry point '${module}:${func}' is not 'module:function'`);
  }
  // 'module:Class.method' imports Class
  return `import sys\nfrom ${module} import ${String(func).split('.')[0]}\nsys.exit(${func}())\n`;
}

/** Node.js: read the script and the type descriptions, check the Pyodide folder. */
async function nodeSpec(spec) {
  const fs = await import('node:fs');
  const path = await import('node:path');
  const file = path.resolve(spec.file);
  const name = spec.name || path.basename(file).replace(/\.py$/, '');
  await checkPyodide(spec.pyodideDir);
  let source = spec.entry ? entryPointSource(spec.entry) : spec.source;
  if (source === undefined) {
    try {
      source = fs.readFileSync(file, 'utf8');
    } catch (e) {
      throw new BusError(Code.INVALID_ARGUMENT, `spawnPython '${name}': cannot read ${file}: ${e.message}`);
    }
  }
  const types = (spec.types || []).map((t) => {
    if (typeof t !== 'string') return t;
    try {
      return JSON.parse(fs.readFileSync(t, 'utf8'));
    } catch (e) {
      throw new BusError(Code.INVALID_ARGUMENT, `spawnPython '${name}': cannot read the type descriptions ${t}: ${e.message}`);
    }
  });
  return { file, name, source, types, where: { pyodideDir: path.resolve(spec.pyodideDir) } };
}

/** Browser: the script's text and the types come with the spec; Pyodide from `pyodideUrl`. */
function browserSpec(spec) {
  const file = String(spec.file);
  const name = spec.name || file.slice(file.lastIndexOf('/') + 1).replace(/\.py$/, '');
  const source = spec.entry ? entryPointSource(spec.entry) : spec.source;
  if (typeof source !== 'string') {
    throw new BusError(Code.INVALID_ARGUMENT, `spawnPython '${name}': in a browser, pass the script's text as source`);
  }
  if (!spec.pyodideUrl) {
    throw new BusError(Code.INVALID_ARGUMENT, `spawnPython '${name}': a Python node needs Pyodide ${PYODIDE_VERSION}; `
      + "serve it with the page (colcon-wasm serve --pyodide DIR, or COLCON_WASM_PYODIDE; see 'colcon-wasm doctor')");
  }
  const types = (spec.types || []).filter((t) => typeof t === 'object' && t !== null);
  return { file, name, source, types, where: { pyodideUrl: new URL(spec.pyodideUrl, self.location.href).href } };
}
