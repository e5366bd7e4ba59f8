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

import {
  BusClient, KIND_CLIENT, KIND_PUBLISHER, KIND_SERVICE, KIND_SUBSCRIPTION, TakeMode, WAIT_ITEM_WORDS, WaitKind,
} from '../bus_client.mjs';
import { normalizeTypeName, TypeRegistry } from '../cdr.mjs';
import { HEADER } from '../layout.mjs';
import { blockingStdinRead, runtimeWarning } from '../program_worker.mjs';
import { FromWorker } from '../protocol.mjs';
import { StdinPipe } from '../stdin_pipe.mjs';
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

/** Import Pyodide's loader from its folder (Node.js) or URL (browser). */
async function importPyodide(msg) {
  if (isNode) {
    const path = await import('node:path');
    const { pathToFileURL } = await import('node:url');
    const { loadPyodide } = await import(pathToFileURL(path.join(msg.pyodideDir, 'pyodide.mjs')).href);
    return { loadPyodide, indexURL: msg.pyodideDir + path.sep };
  }
  const base = new URL(msg.pyodideUrl, self.location.href).href;
  const { loadPyodide } = await import(new URL('pyodide.mjs', base).href);
  return { loadPyodide, indexURL: base };
}

const WAIT_KINDS = {
  subscription: WaitKind.SUBSCRIPTION, service: WaitKind.SERVICE, client: WaitKind.CLIENT, event: WaitKind.EVENT,
};

/**
 * The `_colcon_wasm_bus` module: what rclpy calls (plain values in, plain values out).
 * `stdinPipe`: the process' standard input when it has one (the page's console), else null.
 */
function busModule(client, registry, context, settle, stdinPipe) {
  // the memory of a 'graph' wait item (a graph guard condition at byte 0)
  const graphWord = new Int32Array(new SharedArrayBuffer(16));
  let items = new Int32Array(0);
  return {
    create_node(name, namespace, domain) {
      return client.createNode({ name, namespace, domain, context }).index;
    },
    destroy_node(index) {
      client.destroyNode(index);
    },
    create_publisher(node, topic, type, qosJson) {
      registry.codec(type); // an unknown type fails here, naming its package
      return client.createEndpoint({ kind: KIND_PUBLISHER, node, name: topic, type, qos: JSON.parse(qosJson) }).index;
    },
    create_subscription(node, topic, type, qosJson) {
      registry.codec(type);
      return client.createEndpoint({ kind: KIND_SUBSCRIPTION, node, name: topic, type, qos: JSON.parse(qosJson) }).index;
    },
    destroy_endpoint(index) {
      client.destroyEndpoint(index);
    },
    /** Encode (cdr.mjs) and publish; returns the sequence number. */
    publish(ep, type, value) {
      return client.publish(ep, registry.encode(type, value), 10000);
    },
    /** The next message of a subscription, decoded, or undefined (None in Python). */
    take(ep, type) {
      const data = client.take(ep, TakeMode.MESSAGE);
      return data === null ? undefined : registry.decode(type, data);
    },
    create_service(node, name, type, qosJson) {
      registry.service(type);
      return client.createEndpoint({ kind: KIND_SERVICE, node, name, type, qos: JSON.parse(qosJson) }).index;
    },
    create_client(node, name, type, qosJson) {
      registry.service(type);
      return client.createEndpoint({ kind: KIND_CLIENT, node, name, type, qos: JSON.parse(qosJson) }).index;
    },
    /** The next request of a service: {value, id} (id: for send_response), or undefined. */
    take_request(ep, type) {
      const data = client.take(ep, TakeMode.REQUEST);
      if (data === null) return undefined;
      const i = client.info;
      return { value: registry.decode(type, data), id: { gid: Array.from(i.gid), seqLo: i.reqLo, seqHi: i.reqHi } };
    },
    send_response(ep, id, type, value) {
      return client.sendResponse(ep, id.gid, id.seqLo, id.seqHi, registry.encode(type, value), 10000);
    },
    /** Send a request; returns its sequence number (the response carries it). */
    send_request(ep, type, value) {
      return client.publish(ep, registry.encode(type, value), 10000);
    },
    /** The next response of a client: {value, seq}, or undefined. */
    take_response(ep, type) {
      const data = client.take(ep, TakeMode.RESPONSE);
      if (data === null) return undefined;
      const i = client.info;
      return { value: registry.decode(type, data), seq: i.reqHi * 4294967296 + (i.reqLo >>> 0) };
    },
    server_available(ep) {
      return client.serverAvailable(ep);
    },
    /**
     * Block until a client has a server or `timeoutMs` passed (< 0: forever):
     * sleeps on the bus' graph version, which every graph change bumps.
     */
    wait_for_server(ep, timeoutMs) {
      const i32 = client.bus.i32;
      const end = timeoutMs < 0 ? Infinity : performance.now() + timeoutMs;
      for (;;) {
        const version = Atomics.load(i32, HEADER.GRAPH_VERSION);
        if (client.serverAvailable(ep)) return true;
        const left = end - performance.now();
        if (left <= 0) return false;
        settle();
        Atomics.wait(i32, HEADER.GRAPH_VERSION, version, left);
      }
    },
    matched_count(ep) {
      return client.matchedCount(ep);
    },
    /** A QoS event's status, its changes reset: {changed, total, change, alive, ...}. */
    event_status(ep, type) {
      return client.eventStatus(ep, type, true);
    },
    assert_liveliness(ep) {
      client.assertLiveliness(ep);
    },
    /** The bus' graph version (every graph change bumps it). */
    graph_version() {
      return client.graphVersion();
    },
    /**
     * Block until one of the endpoints has something to take or the timeout
     * passes (< 0: forever). `kinds`: 'subscription', 'service', 'client'
     * or 'event', one per handle, or 'graph' (one at most: ready once the graph
     * version differs from its `eventTypes` entry); `eventTypes`: the EventType
     * of each 'event' (0 for the others). Returns the ready flags, one per handle.
     */
    wait(handles, kinds, timeoutMs, eventTypes) {
      const list = Array.from(handles);
      const kindList = Array.from(kinds);
      const types = eventTypes ? Array.from(eventTypes) : [];
      const n = list.length;
      if (items.length < n * WAIT_ITEM_WORDS) items = new Int32Array(n * WAIT_ITEM_WORDS);
      graphWord.fill(0);
      for (let i = 0; i < n; i++) {
        const o = i * WAIT_ITEM_WORDS;
        const graph = kindList[i] === 'graph';
        const kind = graph ? WaitKind.GUARD_CONDITION : WAIT_KINDS[kindList[i]];
        if (kind === undefined) throw new TypeError(`wait: unknown item kind ${JSON.stringify(kindList[i])}`);
        if (graph) {
          // rcl's graph guard condition (client/wait.mjs): word 0 says "graph", word 2 the version seen
          graphWord[0] = 1;
          graphWord[2] = types[i] || 0;
        }
        items[o] = kind;
        items[o + 1] = graph ? 0 : list[i];
        items[o + 2] = graph ? 0 : types[i] || 0;
        items[o + 3] = 0;
      }
      if (n === 0) {
        // nothing to wait for but time: sleep on the doorbell (a stop still ends the worker)
        settle();
        client.register();
        const bell = client.bell();
        client.sleep(bell, timeoutMs < 0 ? Infinity : timeoutMs);
        client.unregister();
        return [];
      }
      client.wait(items, 0, n, timeoutMs, graphWord);
      const ready = [];
      for (let i = 0; i < n; i++) ready.push(items[i * WAIT_ITEM_WORDS + 3] !== 0);
      return ready;
    },
    /**
     * The graph of a domain as one JSON text, for rclpy's graph queries:
     * {nodes: [{name, namespace}], endpoints: [{kind, name, type, node,
     * namespace, gid, qos}]}, kind one of publisher, subscription,
     * service, client, types as `pkg/msg/Name`.
     */
    graph_json(domain) {
      const g = client.graph({ domain });
      return JSON.stringify({
        nodes: g.nodes.map((n) => ({ name: n.name, namespace: n.namespace })),
        endpoints: g.endpoints.map((e) => ({
          kind: e.kindName, name: e.name, type: normalizeTypeName(e.type), node: e.node,
          namespace: e.namespace, gid: Array.from(e.gid), qos: e.qos,
        })),
      });
    },
    /** The type descriptions as one JSON text: {messages, services, actions}. */
    types_json() {
      return JSON.stringify({
        messages: Object.fromEntries(registry.messages),
        services: Object.fromEntries(registry.services),
        actions: Object.fromEntries(registry.actions),
      });
    },
    has_type(type) {
      return registry.has(type);
    },
    /** Whether a read of standard input would return now: bytes or its end are there. */
    stdin_ready() {
      return !!stdinPipe && (stdinPipe.available() > 0 || stdinPipe.closed());
    },
    log,
  };
}

/** The Python side of the start: argv, environment, run the script, report how it ended. */
const RUNNER = `
import os
import sys
import traceback


def _colcon_wasm_run(file, source, args, env):
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
    busModule(client, registry, client.createContext(), settle, stdinPipe));
  pyodide.runPython(`import sys\nsys.path[0:0] = ${JSON.stringify([PYTHON_ROOT, ...(msg.pythonPath || [])])}`);
  pyodide.runPython(RUNNER, { filename: '<colcon-wasm python worker>' });
  const run = pyodide.globals.get('_colcon_wasm_run');
  post({ type: FromWorker.STARTED, prestartedPthreadWorkers: 0, glueFromMemory: false, pyodideSnapshot: fromSnapshot });
  const result = run(msg.file, msg.source, pyodide.toPy(msg.args), pyodide.toPy(msg.env));
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
