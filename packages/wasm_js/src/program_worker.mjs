// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * What a program worker does to run one executable as a bus process: attach to
 * the bus, build the Emscripten `Module` (arguments, environment, log hooks,
 * the shared compiled wasm module, the bus) and load the executable's glue.
 * Used by program_worker_web.js (browser) and program_worker_node.mjs (Node.js).
 *
 * @module program_worker
 */

import { armFaultPoint } from './bus/faults.mjs';
import { BusClient } from './bus_client.mjs';
import { isNode } from './platform.mjs';
import { FromWorker, UNCAUGHT_EXCEPTION } from './protocol.mjs';
import { createExitRing, recycleEndedThreads } from './pthread_exits.mjs';
import { PthreadPool } from './pthread_pool.mjs';
import { StdinPipe } from './stdin_pipe.mjs';
import { mountViews } from './view_fs.mjs';
import { httpViewSource } from './view_source_http.mjs';

/**
 * The platform half of a program worker.
 * @typedef {object} WorkerPlatform
 * @property {function(string, string=): boolean} loadGlue run the glue script (URL or path) in
 *   global scope, from its prefetched text when one is given and the platform can; returns true
 *   when it ran from the text
 * @property {function(string): string} locate the URL or path Emscripten should use for a file
 *   next to the glue (pthread worker script, ...)
 * @property {function(object): void} post post a message to the Runtime
 * @property {function(number): void} close end this worker
 * @property {function(string): Promise<WebAssembly.Module>} compile compile a .wasm URL
 * @property {function(): import('./view_fs.mjs').ViewSource} [fileViewSource] the host's own
 *   files, for views without a URL (Node.js)
 */

/** This worker's pre-started pthread workers (a warm worker's), or null. */
let pthreadPool = null;

/**
 * Boot pthread workers ahead of START (a warm worker), so that a pthread
 * program's pool is ready at once; see pthread_pool.mjs.
 * @param {number} count how many (the program's `-sPTHREAD_POOL_SIZE`; 0: none)
 * @param {string} busModuleUrl the bus client module they import ahead
 * @param {function(): import('./pthread_pool.mjs').PthreadStub} createStub
 * @returns {Promise<void>} resolves when they are ready (or failed: then
 *   Emscripten starts its own workers)
 */
export async function prestartPthreadWorkers(count, busModuleUrl, createStub) {
  if (!(count > 0) || !busModuleUrl) return;
  pthreadPool = pthreadPool || new PthreadPool(createStub);
  await pthreadPool.prestart(count, busModuleUrl);
}

/**
 * Turn `ROS_NAMESPACE` into a namespace remap, unless the arguments remap
 * `__ns` already. Humble's rcl does not read the variable (a ROS 1 habit
 * users keep); colcon-wasm honours it the way `ros2 run` users expect.
 * @param {string[]} args
 * @param {Object<string, string>} env
 * @returns {string[]}
 */
export function withNamespaceFromEnvironment(args, env) {
  const ns = env.ROS_NAMESPACE;
  if (!ns || args.some((a) => a.startsWith('__ns:='))) return args;
  return [...args, '--ros-args', '-r', `__ns:=${ns.startsWith('/') ? ns : '/' + ns}`];
}

/**
 * A warning of the runtime about a process, as rcutils formats a log line
 * (`[WARN] [sec.nsec] [wasm_js]: NAME: text`), for its stderr.
 * @param {string} name the process' name
 * @param {string} text
 * @returns {string}
 */
export function runtimeWarning(name, text) {
  return `[WARN] [${(Date.now() / 1000).toFixed(9)}] [wasm_js]: ${name}: ${text}`;
}

/**
 * Run `load` (the glue) with pre-started pthread workers in place of new
 * ones. Emscripten's glue makes its pthread pool while it loads, with
 * `new Worker(url)` (Emscripten 3.1.6: the pool's worker script, no
 * options); under Node.js it first sets the global `Worker` itself, which
 * the accessor records. Any other construction gets a real Worker.
 * @param {function(): void} load
 * @param {Object<string, string>} [scripts] prefetched script texts the stubs run from memory
 * @returns {Int32Array|null} where the stubs write their ended threads (pthread_exits.mjs),
 *   null when no stub was taken
 */
function withPthreadStubs(load, scripts) {
  if (!pthreadPool || pthreadPool.size === 0) {
    load();
    return null;
  }
  const pool = pthreadPool;
  const exitRing = createExitRing();
  let Real = globalThis.Worker;
  function WorkerOrStub(url, options) {
    const stub = options === undefined ? pool.take(String(url), scripts, exitRing) : null;
    return stub || new Real(url, options);
  }
  Object.defineProperty(globalThis, 'Worker', {
    configurable: true, enumerable: false, get: () => WorkerOrStub, set: (v) => { Real = v; },
  });
  try {
    load();
  } finally {
    Object.defineProperty(globalThis, 'Worker', { configurable: true, enumerable: false, writable: true, value: Real });
  }
  return pool.taken ? exitRing : null;
}

/**
 * Let main() start before the pre-started pthread workers have loaded the
 * program, and keep them from loading while it starts. Emscripten 3.1.6
 * posts each pool worker 'load' once the module is instantiated and holds
 * main() until every one has answered: on two cores, four glue loads and
 * instantiations then compete with main() for the CPU (~10 ms later first
 * publish in Chromium). Here a worker that had booted before it was handed
 * to Emscripten (`readyWorkers`) counts as loaded at once, and gets its
 * 'load' only when Emscripten first posts it something else (a thread's
 * 'run', which follows the 'load') or when the program has settled (see
 * {@link settleOnce}), whichever comes first. A worker runs its messages in
 * order and handles 'load' at once (library_wasm_bus.js holds what follows
 * until the worker has attached to the bus), so 'run' can follow 'load' at
 * once; that needs no help from this thread's event loop, which is blocked
 * while main() waits on the bus. Any other worker keeps Emscripten's wait.
 * Call it after the glue has run and before the module is instantiated.
 * @param {WeakSet<object>} readyWorkers
 * @returns {function(): void} load every worker still waiting for its 'load'
 */
function deferPthreadWorkerLoads(readyWorkers) {
  const PThread = globalThis.PThread;
  const deferred = [];
  const loadAll = () => {
    for (const load of deferred.splice(0)) load();
  };
  if (!PThread || typeof PThread.loadWasmModuleToWorker !== 'function') return loadAll;
  const loadToWorker = PThread.loadWasmModuleToWorker;
  PThread.loadWasmModuleToWorker = function loadLater(worker, onFinishedLoading) {
    if (!readyWorkers.has(worker)) return loadToWorker.call(this, worker, onFinishedLoading);
    let pending = true;
    const load = () => {
      if (!pending) return;
      pending = false;
      delete worker.postMessage;
      loadToWorker.call(PThread, worker, undefined);
    };
    // Emscripten's first message of its own to the worker sends the 'load' ahead of it.
    worker.postMessage = function postAfterLoad(...args) {
      load();
      return worker.postMessage(...args);
    };
    deferred.push(load);
    // Emscripten's spawnThread posts 'run' at once to a loaded worker.
    worker.loaded = true;
    if (onFinishedLoading) onFinishedLoading(worker);
    return undefined;
  };
  return loadAll;
}

/**
 * Call `settle` once, when the program has settled after its start: when
 * main() first sleeps on the bus (a node waiting for work), or when it
 * returns or yields to the event loop, whichever comes first. Until then,
 * background work (pthread workers loading the program, the Runtime's next
 * warm worker booting) would compete with main() for the cores.
 * @param {BusClient} client the main thread's bus client
 * @param {function(): void} settle
 */
function settleOnce(client, settle) {
  let done = false;
  const once = () => {
    if (done) return;
    done = true;
    settle();
  };
  client.beforeFirstSleep(once);
  // Runs once main() returns or yields (the event loop is blocked before).
  setTimeout(once, 0);
}

/**
 * Run `fn` (Emscripten's receiveInstance, which runs main() when nothing else
 * holds it) from a promise reaction, rethrowing what it throws in a task of
 * its own. Thrown in the reaction, a crash in main() (a wasm trap: "RuntimeError:
 * unreachable") would only reject a promise nobody holds: a browser reports
 * that to no one, and the process would hang instead of being reported
 * crashed. Rethrown in a task, it is an uncaught error, which the Runtime
 * hears as the worker's error event (Node.js: its 'error').
 * @param {function(): void} fn
 */
function receiveOutsidePromise(fn) {
  try {
    fn();
  } catch (e) {
    setTimeout(() => {
      throw e;
    }, 0);
  }
}

/**
 * Describe an uncaught C++ exception: Emscripten throws the thrown object's
 * address (a number). `colcon_wasm_exception_text`, which colcon-wasm's link
 * launcher links into every C++ executable (colcon_wasm/link/launcher.py),
 * gives its type and what(), as a native std::terminate prints them. Other
 * values (JS errors, traps) give null.
 * @param {*} value what reached Emscripten's quit()
 * @returns {{type: string, what: string|null}|null}
 */
export function describeUncaughtException(value) {
  const g = globalThis;
  if (typeof value !== 'number' || typeof g.ExceptionInfo !== 'function') return null;
  const text = typeof g._colcon_wasm_exception_text === 'function' ? g._colcon_wasm_exception_text : null;
  if (!text || typeof g.UTF8ToString !== 'function') {
    return { type: '(type unknown: the executable was not linked by colcon-wasm\'s link launcher)', what: null };
  }
  try {
    const type = new g.ExceptionInfo(value).get_type();
    const pointer = text(value, type);
    const [name, ...what] = g.UTF8ToString(pointer).split('\n');
    if (typeof g._free === 'function') g._free(pointer);
    return { type: name, what: what.length ? what.join('\n') : null };
  } catch (e) {
    return null;
  }
}

/**
 * Standard input without a pipe: end of file at once (a worker has no
 * terminal to read from). Emscripten calls the reader once per byte.
 * @returns {null}
 */
function noStdin() {
  return null;
}

/**
 * Read from the process' stdin pipe, blocking while it is empty, like a
 * terminal. The wait sleeps on the process' doorbell, which the Runtime rings
 * after writing, and which a pthread rings when it proxies a call to this
 * thread (its printf): those calls run while we wait, so a node that reads
 * its standard input on the main thread keeps logging from its executor
 * threads.
 * @param {StdinPipe} pipe
 * @param {BusClient} client
 * @returns {function(object, Uint8Array, number, number): number} an Emscripten device read
 */
export function blockingStdinRead(pipe, client) {
  const service = () => {
    const bus = globalThis.WasmBus;
    if (bus && bus.client && typeof bus.client.service === 'function') bus.client.service();
  };
  return (stream, buffer, offset, length) => {
    for (;;) {
      let n = pipe.take(buffer, offset, length);
      if (n >= 0) return n;
      client.register();
      try {
        const bell = client.bell();
        service();
        n = pipe.take(buffer, offset, length);
        if (n >= 0) return n;
        client.sleep(bell, Infinity);
      } finally {
        client.unregister();
      }
    }
  };
}

/**
 * Make /dev/stdin read from the pipe (before main() runs).
 * @param {StdinPipe} pipe
 * @param {BusClient} client
 */
function connectStdin(pipe, client) {
  const FS = globalThis.FS;
  // Linked without a file system (-sFILESYSTEM=0): the executable has no
  // read() to call, so there is nothing to connect.
  if (!FS || typeof FS.init !== 'function' || typeof FS.getDevice !== 'function') return;
  // Emscripten's own init (the same call) then sees it done; with Module.stdin
  // set it makes /dev/stdin a device, whose read we replace: the stock one
  // calls Module.stdin per byte and cannot block until a line arrives.
  if (!FS.init.initialized) FS.init();
  const device = FS.getDevice(FS.lookupPath('/dev/stdin').node.rdev);
  device.stream_ops.read = blockingStdinRead(pipe, client);
}

/**
 * Write the START message's files into the executable's file system (MEMFS).
 * @param {Object<string, string|Uint8Array>|undefined} files
 * @param {string} url the executable, for messages
 * @param {boolean} optional without a file system the executable reads no files: skip them
 */
function writeFiles(files, url, optional) {
  const entries = Object.entries(files || {});
  if (!entries.length) return;
  const FS = globalThis.FS;
  if (!FS || typeof FS.writeFile !== 'function') {
    if (optional) return;
    throw new Error(`${url} was linked without a file system (-sFILESYSTEM=0): cannot give it files`);
  }
  for (const [path, content] of entries) {
    const dir = path.slice(0, path.lastIndexOf('/'));
    if (dir) FS.mkdirTree(dir);
    FS.writeFile(path, content);
  }
}

/**
 * Mount the START message's read-only views (see view_fs.mjs): served ones
 * over HTTP, others from the host's own files. Mounting reads nothing.
 * @param {Array<{path: string, url?: string, leftOut?: object}>|undefined} mounts `leftOut`:
 *   what a static export left out of a served view (see view_source_http.mjs)
 * @param {WorkerPlatform} platform
 * @param {string} url the executable, for messages
 * @param {function(string): void} warn
 */
function mountReadOnlyViews(mounts, platform, url, warn) {
  if (!mounts || !mounts.length) return;
  const FS = globalThis.FS;
  // Linked without a file system (-sFILESYSTEM=0, or no file calls at all): it reads no files.
  if (!FS || typeof FS.mount !== 'function' || typeof FS.createNode !== 'function') return;
  const views = mounts.map(({ path, url: served, leftOut }) => {
    if (served) return { path, source: httpViewSource(served, path, { leftOut, warn }) };
    if (platform.fileViewSource) return { path, source: platform.fileViewSource() };
    throw new Error(`${url}: the view of '${path}' needs a url here: a browser worker reads views over HTTP `
      + '(colcon-wasm serve serves install spaces under /fs/)');
  });
  mountViews(FS, views, warn);
}

/**
 * Start the executable described by a START message.
 * @param {object} msg the START message (see protocol.mjs)
 * @param {WorkerPlatform} platform
 */
export async function startProcess(msg, platform) {
  const post = platform.post;
  let exited = false;
  let loadPthreadWorkers = () => {};
  const exit = (code, crashed, reason) => {
    if (exited) return;
    exited = true;
    // library_wasm_bus.js' state (the glue's top level is this worker's global scope).
    const wasmBus = globalThis.WasmBus;
    const memoryCopy = !!(wasmBus && wasmBus.copyMode === 1);
    post({ type: FromWorker.EXIT, code, crashed, reason, memoryCopy });
  };
  const settle = () => {
    if (exited) return;
    loadPthreadWorkers();
    post({ type: FromWorker.SETTLED });
  };
  try {
    const client = BusClient.attach(msg.bus, msg.pid);
    if (msg.faultPoint) armFaultPoint(client.bus, msg.faultPoint); // tests only
    const module = msg.wasmModule || await platform.compile(msg.wasmUrl);
    const env = msg.env || {};
    const Module = {
      arguments: withNamespaceFromEnvironment(msg.args || [], env),
      thisProgram: msg.name,
      print: (text) => post({ type: FromWorker.LOG, stream: 'stdout', text: String(text) }),
      printErr: (text) => post({ type: FromWorker.LOG, stream: 'stderr', text: String(text) }),
      wasmBus: { client, moduleUrl: msg.busModuleUrl },
      env,
      locateFile: (path) => platform.locate(path),
      mainScriptUrlOrBlob: platform.locate(msg.glueFile),
      instantiateWasm: (imports, receive) => {
        WebAssembly.instantiate(module, imports).then(
          (instance) => {
            settleOnce(client, settle);
            receiveOutsidePromise(() => receive(instance, module));
          },
          (err) => exit(1, true, `cannot instantiate ${msg.wasmUrl}: ${err && err.message}`));
        return {};
      },
      stdin: noStdin,
      preRun: [() => {
        // Executables that do not link wasm_cpp get their environment here.
        if (typeof globalThis.ENV === 'object' && globalThis.ENV) Object.assign(globalThis.ENV, env);
        if (msg.stdin) connectStdin(new StdinPipe(msg.stdin), client);
        writeFiles(msg.files, msg.url, msg.filesOptional);
        mountReadOnlyViews(msg.mounts, platform, msg.url,
          (text) => post({ type: FromWorker.LOG, stream: 'stderr', text }));
      }],
      onExit: (code) => {
        exit(code, code !== 0, code !== 0 ? `exited with code ${code}` : '');
        platform.close(code);
      },
      // Emscripten's own quit calls process.exit() under Node.js, which can drop
      // the last messages (log lines) posted to the runtime: let close() end
      // the worker once they are out.
      quit: (status, toThrow) => {
        const uncaught = describeUncaughtException(toThrow);
        if (uncaught) {
          // what a native process prints when std::terminate ends it
          post({ type: FromWorker.LOG, stream: 'stderr', text: `terminate called after throwing an instance of '${uncaught.type}'` });
          if (uncaught.what !== null) post({ type: FromWorker.LOG, stream: 'stderr', text: `  what():  ${uncaught.what}` });
          const reason = `${UNCAUGHT_EXCEPTION}'${uncaught.type}'${uncaught.what !== null ? `: ${uncaught.what}` : ''}`;
          exit(1, true, reason);
          throw new Error(reason);
        }
        throw toThrow;
      },
      onAbort: (what) => {
        exit(1, true, `aborted: ${what}`);
      },
    };
    globalThis.Module = Module;
    const scripts = msg.scripts || {};
    let glueFromMemory = false;
    const exitRing = withPthreadStubs(() => { glueFromMemory = platform.loadGlue(msg.url, scripts[msg.url]) === true; }, scripts);
    // ended detached threads give their workers back while main() blocks on the bus
    if (exitRing) {
      recycleEndedThreads(globalThis.PThread, exitRing, (running) => post({
        type: FromWorker.LOG, stream: 'stderr',
        text: runtimeWarning(msg.name, `${running + 1} threads at once, more than its pthread `
          + `pool of ${pthreadPool.taken} workers: starting another one${isNode ? ''
            : ', which a browser starts only when main() returns to its event loop (the thread waits until then)'}; `
          + 'rebuild with a larger --wasm-pthread-pool-size to have them started ahead'),
      }));
    }
    if (pthreadPool && pthreadPool.taken) loadPthreadWorkers = deferPthreadWorkerLoads(pthreadPool.readyWorkers);
    post({ type: FromWorker.STARTED, prestartedPthreadWorkers: pthreadPool ? pthreadPool.taken : 0, glueFromMemory });
  } catch (err) {
    exit(1, true, `cannot start ${msg.url}: ${err && err.message ? err.message : err}`);
    platform.close(1);
  }
}
