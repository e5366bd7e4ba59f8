// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * The worker of a Python node (a Node.js worker thread, or a browser module
 * Web Worker): loads Pyodide from its npm package folder (or the URL serve
 * gives it), attaches a BusClient to the Runtime's bus, gives
 * Python the module `_colcon_wasm_bus` (below: nodes, endpoints, publish,
 * take and a blocking wait, with CDR through cdr.mjs's TypeRegistry), copies
 * the `rclpy` package next to this module into Pyodide's file system and runs
 * the script as `__main__`. It speaks the program worker protocol (protocol.mjs
 * FromWorker), so the Runtime treats it as any other bus process.
 *
 * A wait blocks this thread in Atomics.wait on the process' doorbell
 * (BusClient.wait), as the C++ nodes' waits do: no polling.
 *
 * @module python/python_worker
 */

import { BusClient } from '../bus_client.mjs';
import { TypeRegistry } from '../cdr.mjs';
import { blockingStdinRead, runtimeWarning } from '../program_worker.mjs';
import { FromWorker } from '../protocol.mjs';
import { StdinPipe } from '../stdin_pipe.mjs';
import { busModule } from './bus_module.mjs';
import { loadDistributionPackages } from './distribution.mjs';
import { RCLPY_FILES, SNAPSHOT_RCLPY_MODULES } from './rclpy_files.mjs';

/** Where the rclpy package lives inside Pyodide's file system. */
const PYTHON_ROOT = '/colcon_wasm/python';
const isNode = typeof process === 'object' && !!(process.versions && process.versions.node);
/** Node.js: worker_threads' parentPort; browser: the worker's own scope. */
const port = isNode ? (await import('node:worker_threads')).parentPort : self;

/**
 * std_msgs/msg/String when the install space has no std_msgs types.json
 * (e.g. a workspace without Humble): its definition is `string data`.
 */
const STD_MSGS_STRING = {
  schema: 1, package: 'std_msgs', messages: {
    'std_msgs/msg/String': { fields: [{ name: 'data', type: 'string' }], constants: [], definition: 'string data\n' },
  },
};

/**
 * builtin_interfaces' Time and Duration when the install space has none,
 * for rclpy.time.Time.to_msg() and rclpy.duration.Duration.to_msg().
 */
const BUILTIN_INTERFACES = {
  schema: 1, package: 'builtin_interfaces', messages: {
    'builtin_interfaces/msg/Time': {
      fields: [{ name: 'sec', type: 'int32' }, { name: 'nanosec', type: 'uint32' }],
      constants: [], definition: 'int32 sec\nuint32 nanosec\n',
    },
    'builtin_interfaces/msg/Duration': {
      fields: [{ name: 'sec', type: 'int32' }, { name: 'nanosec', type: 'uint32' }],
      constants: [], definition: 'int32 sec\nuint32 nanosec\n',
    },
  },
};

/** rosgraph_msgs/msg/Clock when the install space has none, for use_sim_time (rclpy/time_source.py). */
const ROSGRAPH_CLOCK = {
  schema: 1, package: 'rosgraph_msgs', messages: {
    'rosgraph_msgs/msg/Clock': {
      fields: [{ name: 'clock', type: 'builtin_interfaces/msg/Time' }],
      constants: [], definition: 'builtin_interfaces/Time clock\n',
    },
  },
};

const post = (m) => port.postMessage(m);
const log = (stream, text) => {
  if (heldLogs) heldLogs.push([stream, String(text)]);
  else post({ type: FromWorker.LOG, stream, text: String(text) });
};

/** The text of a file of the rclpy package beside this module. */
async function rclpyFile(rel) {
  const url = new URL(rel, import.meta.url);
  if (isNode) {
    const fs = await import('node:fs');
    return fs.readFileSync(url, 'utf8');
  }
  const response = await fetch(url);
  if (!response.ok) throw new Error(`cannot load ${url}: HTTP ${response.status}`);
  return response.text();
}

/** Write the rclpy package beside this module into Pyodide's file system (PYTHON_ROOT). */
async function writeRclpy(pyodide) {
  const sources = await Promise.all(RCLPY_FILES.map(rclpyFile));
  RCLPY_FILES.forEach((rel, i) => {
    const target = `${PYTHON_ROOT}/${rel}`;
    pyodide.FS.mkdirTree(target.slice(0, target.lastIndexOf('/')));
    pyodide.FS.writeFile(target, sources[i]);
  });
}

/** The Pyodide folder (Node.js: a path ending in the separator) or its URL (browser). */
function pyodideIndex(msg) {
  return isNode ? `${msg.pyodideDir.replace(/\/$/, '')}/` : new URL(msg.pyodideUrl, self.location.href).href;
}

/** Import Pyodide's loader from its folder (Node.js) or URL (browser). */
async function importPyodide(msg) {
  const indexURL = pyodideIndex(msg);
  if (isNode) {
    const { pathToFileURL } = await import('node:url');
    const { loadPyodide } = await import(pathToFileURL(`${indexURL}pyodide.mjs`).href);
    return { loadPyodide, indexURL };
  }
  const { loadPyodide } = await import(new URL('pyodide.mjs', indexURL).href);
  return { loadPyodide, indexURL };
}

/** The Python side of the start: argv, environment, run the script, report how it ended. */
const RUNNER = `
import os
import sys
import traceback


def _colcon_wasm_run(file, source, args, env, absent):
    sys.argv = [file] + list(args)
    os.environ.update(env)
    sys.path.insert(0, os.path.dirname(file))
    glb = {'__name__': '__main__', '__file__': file, '__builtins__': __builtins__}
    code, reason, attached = 0, '', False
    try:
        # rclpy (imported already when Pyodide came from the host's snapshot) takes the bus
        # and puts the finder of the install space's message modules on sys.meta_path:
        # 'from std_msgs.msg import String' before 'import rclpy' works, as natively
        import _colcon_wasm_bus
        import rclpy
        rclpy._attach_to_worker(_colcon_wasm_bus)
        # Pyodide's packages whose wheels the Pyodide folder lacks (python/distribution.mjs)
        rclpy._native_only.note_distribution_packages(dict(absent or {}))
        attached = True
        exec(compile(source, file, 'exec'), glb)
    except SystemExit as e:
        code, reason = _exit_status(e)
    except BaseException as e:
        code, reason = _report(e)
    try:
        # as Python before it exits: the threads that are no daemons (spin threads) end first
        if attached:
            import rclpy._threads
            rclpy._threads.join_spin_threads()
    except SystemExit as e:
        code, reason = _exit_status(e)
    except BaseException as e:
        code, reason = _report(e)
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
    return code, reason


def _exit_status(e):
    if e.code is None:
        return 0, ''
    if isinstance(e.code, int):
        return e.code, 'sys.exit({})'.format(e.code) if e.code else ''
    print(e.code, file=sys.stderr)
    return 1, str(e.code)


def _report(e):
    tb = e.__traceback__.tb_next if e.__traceback__ is not None else None
    traceback.print_exception(type(e), e, tb)
    last = traceback.format_exception_only(type(e), e)[-1].strip()
    return 1, 'Python exception: ' + last
`;

async function start(msg) {
  const client = BusClient.attach(msg.bus, msg.pid);
  let settled = false;
  const settle = () => {
    if (!settled) {
      settled = true;
      post({ type: FromWorker.SETTLED });
    }
  };
  client.beforeFirstSleep(settle);
  const registry = new TypeRegistry();
  for (const doc of msg.types || []) {
    try {
      registry.add(doc);
    } catch (e) {
      log('stderr', `[WARNING] [${msg.name}]: ${e.message}`);
    }
  }
  if (!registry.has('std_msgs/msg/String')) registry.add(STD_MSGS_STRING);
  if (!registry.has('builtin_interfaces/msg/Time')) registry.add(BUILTIN_INTERFACES);
  if (!registry.has('rosgraph_msgs/msg/Clock')) registry.add(ROSGRAPH_CLOCK);
  for (const note of msg.notes || []) log('stderr', runtimeWarning(msg.name, note));
  const { pyodide, fromSnapshot } = await (preloaded || startPyodide(msg));
  pyodide.setStdout({ batched: (line) => log('stdout', line) });
  pyodide.setStderr({ batched: (line) => log('stderr', line) });
  const stdinPipe = msg.stdin ? new StdinPipe(msg.stdin) : null;
  if (stdinPipe) {
    // an open standard input (the page's console): reads block like a terminal's
    const read = blockingStdinRead(stdinPipe, client);
    pyodide.setStdin({ read: (buffer) => read(null, buffer, 0, buffer.length) });
  }
  await writeRclpy(pyodide);
  // the install space's Python packages: at their real paths, first on sys.path
  for (const folder of msg.pythonPath || []) {
    if (isNode) pyodide.mountNodeFS(folder, folder);
    else pyodide.FS.mkdirTree(folder);
  }
  for (const { path, text } of msg.pythonFiles || []) {
    pyodide.FS.mkdirTree(path.slice(0, path.lastIndexOf('/')));
    pyodide.FS.writeFile(path, text);
  }
  // the script at its real path, so that tracebacks show its lines
  pyodide.FS.mkdirTree(msg.file.slice(0, msg.file.lastIndexOf('/')) || '/');
  pyodide.FS.writeFile(msg.file, msg.source);
  pyodide.registerJsModule('_colcon_wasm_bus',
    busModule(client, registry, client.createContext(), settle, stdinPipe, log));
  pyodide.runPython(`import sys\nsys.path[0:0] = ${JSON.stringify([PYTHON_ROOT, ...(msg.pythonPath || [])])}`);
  pyodide.runPython(RUNNER, { filename: '<colcon-wasm python worker>' });
  const run = pyodide.globals.get('_colcon_wasm_run');
  post({ type: FromWorker.STARTED, prestartedPthreadWorkers: 0, glueFromMemory: false, pyodideSnapshot: fromSnapshot });
  let absent = {};
  try {
    absent = await loadDistributionPackages(pyodide, {
      source: msg.source, module: msg.module, indexURL: pyodideIndex(msg), isNode, log,
    });
  } catch (e) {
    log('stderr', runtimeWarning(msg.name, `loading the packages it imports from Pyodide's distribution failed: ${e && e.message ? e.message : e}`));
  }
  const result = run(msg.file, msg.source, pyodide.toPy(msg.args), pyodide.toPy(msg.env), pyodide.toPy(absent));
  const [code, reason] = result.toJs();
  result.destroy();
  settle();
  post({ type: FromWorker.EXIT, code, crashed: code !== 0, reason, memoryCopy: false });
}

/**
 * Load Pyodide: from the host's snapshot when it gives one (pyodide_snapshot.mjs), else
 * anew; a snapshot that does not load costs a warning and a fresh start.
 */
async function startPyodide(msg) {
  const { loadPyodide, indexURL } = await importPyodide(msg);
  const env = { HOME: '/home/pyodide', ...msg.env };
  if (msg.snapshot) {
    try {
      // a browser's TextDecoder (Pyodide reads the snapshot's header with one) refuses shared memory
      const bytes = isNode ? new Uint8Array(msg.snapshot) : new Uint8Array(msg.snapshot).slice();
      return { pyodide: await loadPyodide({ indexURL, env, _loadSnapshot: bytes }), fromSnapshot: true };
    } catch (e) {
      log('stderr', runtimeWarning(msg.name, 'the Pyodide snapshot does not load '
        + `(${e && e.message ? e.message : e}): starting Pyodide anew; the next node makes a new snapshot`));
    }
  }
  return { pyodide: await loadPyodide({ indexURL, env }), fromSnapshot: false };
}

/**
 * A snapshot worker (pyodide_snapshot.mjs): load Pyodide for a snapshot, run the
 * prelude, send the snapshot back in a SharedArrayBuffer.
 */
async function snapshot(msg) {
  try {
    const { loadPyodide, indexURL } = await importPyodide(msg);
    const pyodide = await loadPyodide({ indexURL, env: { HOME: '/home/pyodide' }, _makeSnapshot: true });
    pyodide.runPython(msg.prelude, { filename: '<colcon-wasm snapshot prelude>' });
    // rclpy's modules, compiled and imported once for every node of the host (a node
    // writes the files again, for its tracebacks and for the modules imported later)
    await writeRclpy(pyodide);
    pyodide.runPython(`import sys\nsys.path.insert(0, ${JSON.stringify(PYTHON_ROOT)})\n`
      + `import ${SNAPSHOT_RCLPY_MODULES.join(', ')}\nsys.path.remove(${JSON.stringify(PYTHON_ROOT)})`,
    { filename: '<colcon-wasm snapshot prelude>' });
    const bytes = pyodide.makeMemorySnapshot();
    const shared = new SharedArrayBuffer(bytes.length);
    new Uint8Array(shared).set(bytes);
    post({ type: 'snapshot', snapshot: shared });
  } catch (e) {
    post({ type: 'snapshot-failed', reason: e && e.message ? e.message : String(e) });
  }
}

/**
 * A warm worker (python_spares.mjs): Pyodide loading from the host's snapshot
 * before there is a node; its warnings wait for the node's log.
 */
let preloaded = null;
let heldLogs = null;

function preload(msg) {
  heldLogs = [];
  preloaded = startPyodide(msg);
  preloaded.catch(() => {});
}

let started = false;
const onStart = (msg) => {
  if (!started && !preloaded && msg && msg.type === 'snapshot') {
    started = true;
    snapshot(msg);
    return;
  }
  if (!started && !preloaded && msg && msg.type === 'preload') {
    preload(msg);
    return;
  }
  if (started || !msg || msg.type !== 'start') return;
  started = true;
  if (heldLogs) {
    for (const [stream, text] of heldLogs) post({ type: FromWorker.LOG, stream, text });
    heldLogs = null;
  }
  start(msg).catch((e) => {
    log('stderr', `[ERROR] [${msg.name}]: the Python worker failed: ${e && e.stack ? e.stack : e}`);
    post({ type: FromWorker.EXIT, code: 1, crashed: true, reason: `the Python worker failed: ${e && e.message ? e.message : e}` });
  });
};
if (isNode) port.on('message', onStart);
else port.onmessage = (e) => onStart(e.data);
