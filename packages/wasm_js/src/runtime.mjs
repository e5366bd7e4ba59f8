// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * The Runtime: owns the bus of a page (or Node.js process), runs each node executable in its
 * own worker, reports logs and exits, cleans up after dead nodes and tells the page about
 * graph changes. Runs on the main thread and never blocks it.
 *
 * @module runtime
 */

import { Bus, BusError, Code } from './bus.mjs';
import { graphOf } from './bus/graph.mjs';
import { PROC_KIND_NODE, PROC_KIND_RUNTIME, PROC_KIND_TOOLS } from './layout.mjs';
import { compileWasm, fetchScript, ProgramWorker, isNode, resolveUrl, siblingUrl } from './platform.mjs';
import { FromWorker, ToWorker, UNCAUGHT_EXCEPTION } from './protocol.mjs';
import { checkedFiles, checkedMounts } from './spawn_options.mjs';
import { Tools } from './tools_process/main_thread.mjs';
import { makeStdinPipe, NodeProcess, severityOf, stripAnsi } from './node_process.mjs';

export { NodeProcess, severityOf, stripAnsi };

/** Thrown by Runtime.create() when shared memory is unavailable (page not cross-origin isolated). */
export class IsolationError extends Error {
  constructor(message) {
    super(message);
    this.name = 'IsolationError';
  }
}

const ISOLATION_HELP =
  'This page is not cross-origin isolated, so SharedArrayBuffer is not available and ROS nodes ' +
  'cannot run here. Serve the page with the HTTP headers ' +
  '"Cross-Origin-Opener-Policy: same-origin" and "Cross-Origin-Embedder-Policy: require-corp" ' +
  '(`colcon-wasm serve` does), and load it over http://localhost or https.';

/**
 * At most this long after a spawn took a warm worker, the Runtime boots the
 * next one even if the new program has not settled yet (main() computing
 * without waiting on the bus).
 */
const REFILL_AFTER_MS = 200;

/**
 * The middleware runtime of one page or Node.js process.
 */
/** Start a program worker (program_worker_node.mjs or program_worker_web.js). */
function startProgramWorker() {
  return ProgramWorker.start(
    isNode ? siblingUrl('program_worker_node.mjs') : siblingUrl('program_worker_web.js'), { name: 'wasm_js program worker', type: 'classic' });
}

/**
 * Warm pthread workers where no manifest says what the install space was built
 * with (a source checkout, a page served without it): colcon-wasm's default
 * `--wasm-pthread-pool-size` (colcon_wasm/options.py).
 */
const FALLBACK_PTHREAD_POOL_SIZE = 4;

/**
 * The pthread pool size this runtime's install space was built with: the
 * `flags.pthread_pool_size` of wasm_js's own colcon-wasm manifest
 * (`share/wasm_js/colcon_wasm/manifest.json` beside `src/`; 0 for a build
 * without pthreads).
 * @returns {Promise<number|null>} null when no manifest can be read
 */
async function builtPthreadPoolSize() {
  const url = new URL('../colcon_wasm/manifest.json', import.meta.url);
  try {
    let text;
    if (isNode && url.protocol === 'file:') {
      const { readFile } = await import('node:fs/promises');
      text = await readFile(url, 'utf8');
    } else {
      const response = await fetch(url);
      if (!response.ok) return null;
      text = await response.text();
    }
    const size = JSON.parse(text).flags.pthread_pool_size;
    return Number.isInteger(size) && size >= 0 ? size : null;
  } catch (e) {
    return null; // no manifest: the fallback
  }
}

export class Runtime {
  /**
   * What this runtime offers beyond the first release, for callers that may
   * load an older one (an install space's): `mounts`, spawn()'s read-only views;
   * `toolsServe`, tools().serve() and subscribe({ignoreLocal}) (the rosbridge bridges).
   * @returns {{mounts: boolean, toolsServe: boolean}}
   */
  static get features() {
    return { mounts: true, toolsServe: true };
  }

  /**
   * Create the bus and the runtime.
   * @param {object} [options]
   * @param {number} [options.maxMessageBytes=64 MiB] largest message
   * @param {number} [options.maxBytes=1 GiB] largest bus size (it grows on demand)
   * @param {number} [options.initialBytes=16 MiB]
   * @param {number} [options.maxProcesses] @param {number} [options.maxNodes]
   * @param {number} [options.maxEndpoints] @param {number} [options.maxLinks]
   * @param {number} [options.warmWorkers=1] idle program workers kept ready (runtime modules
   *   loaded), so that spawn() does not wait for a worker to boot
   * @param {number} [options.warmPthreadWorkers] pthread workers each warm worker boots
   *   ahead for a pthread program's pool; default: the `-sPTHREAD_POOL_SIZE` the
   *   install space was built with (its manifest), else 4; 0: none (a program then
   *   boots its own)
   * @param {boolean} [options.wasmMemory=true] false: the bus is a SharedArrayBuffer
   *   even where it could be a WebAssembly.Memory copied to with memory.copy
   *   (for comparisons; see copier.mjs)
   * @returns {Promise<Runtime>}
   * @throws {IsolationError} when the page is not cross-origin isolated
   */
  static async create(options = {}) {
    if (typeof SharedArrayBuffer === 'undefined' || globalThis.crossOriginIsolated === false) {
      throw new IsolationError(ISOLATION_HELP);
    }
    if (typeof Atomics.waitAsync !== 'function') {
      throw new BusError(Code.UNSUPPORTED,
        'this JavaScript engine lacks Atomics.waitAsync, which the runtime needs to watch the bus without blocking the page (use Chromium >= 87 or Node.js >= 16)');
    }
    if (options.warmPthreadWorkers === undefined) {
      const built = await builtPthreadPoolSize();
      options = { ...options, warmPthreadWorkers: built === null ? FALLBACK_PTHREAD_POOL_SIZE : built };
    }
    const bus = Bus.create(options);
    if (!bus.tryLock(1)) throw new BusError(Code.ERROR, 'a new bus is already locked');
    const pid = bus.allocProcess(PROC_KIND_RUNTIME);
    bus.unlock(1);
    return new Runtime(bus, pid, options);
  }

  constructor(bus, pid, options = {}) {
    /** The bus (what workers attach to is `bus.handle`). */
    this.bus = bus;
    /** This runtime's own process id (owner of its registry mutations). */
    this.pid = pid;
    /** @type {Map<number, NodeProcess>} */
    this.processes = new Map();
    this._modules = new Map();
    this._scripts = new Map();
    this._graphListeners = new Set();
    this._watching = false;
    this._closed = false;
    this._tools = null;
    this._toolsPid = 0;
    /** Bus processes of bridges in workers of their own (helperProcess): pid -> name. */
    this._helpers = new Map();
    /** Warm workers: started workers with the runtime modules loaded, waiting for a spawn. */
    this._warm = options.warmWorkers === undefined ? 1 : options.warmWorkers;
    this._warmPthreadWorkers = options.warmPthreadWorkers === undefined
      ? FALLBACK_PTHREAD_POOL_SIZE : options.warmPthreadWorkers;
    this._spares = [];
    this._closeHooks = [];
    this._fillSpares();
  }

  /**
   * Have `fn` run when the runtime closes, before its processes stop (the
   * warm workers of other modules, e.g. python/python_spares.mjs).
   * @param {function(): (Promise<void>|void)} fn
   */
  _atClose(fn) {
    this._closeHooks.push(fn);
  }

  /**
   * Start an idle program worker: it imports the program worker module and boots pthread
   * workers ahead (PRELOAD). A spawn may take it before it is ready: the worker
   * handles START after PRELOAD, with the pthread workers booted by then.
   * @returns {{host: Promise<ProgramWorker>, ready: Promise<void>}}
   */
  _newWorker() {
    const host = startProgramWorker();
    const ready = host.then((worker) => new Promise((resolve, reject) => {
      worker.on('message', (m) => {
        if (m && m.type === FromWorker.READY) resolve();
        else if (m && m.type === FromWorker.EXIT) reject(new Error(m.reason));
      });
      worker.on('error', (e) => reject(new Error(e.message)));
      worker.postMessage({
        type: ToWorker.PRELOAD, workerModuleUrl: siblingUrl('program_worker.mjs'),
        pthreadWorkers: this._warmPthreadWorkers, busModuleUrl: siblingUrl('bus_client.mjs'),
      });
    }));
    host.catch(() => {});
    ready.catch(() => {});
    return { host, ready };
  }

  _fillSpares() {
    while (!this._closed && this._spares.length < this._warm) this._spares.push(this._newWorker());
  }

  /**
   * Resolves when the warm program workers are ready (e.g. before timing a
   * spawn); boots them now if a spawn has taken one and its program has not
   * settled yet.
   */
  async warm() {
    this._fillSpares();
    await Promise.all(this._spares.map((s) => s.ready.catch(() => {})));
  }

  /**
   * A program worker for a spawn: a warm one (even while it still warms up),
   * else a new one, which warms up first when the Runtime keeps warm workers
   * (spawns in a burst: its pthread workers boot alongside). The caller has
   * the next warm worker booted once the program has settled
   * ({@link Runtime#_fillSparesOnceSettled}).
   */
  async _host() {
    let spare = this._spares.shift();
    if (!spare) {
      if (this._warm === 0) return startProgramWorker();
      spare = this._newWorker();
    }
    try {
      return await spare.host;
    } catch (e) {
      return startProgramWorker(); // a broken spare: start one now
    }
  }

  async _allocPid(kind) {
    await this.bus.lockAsync(this.pid);
    let pid;
    try {
      pid = this.bus.allocProcess(kind);
    } finally {
      this.bus.unlock(this.pid);
    }
    if (!pid) {
      throw new BusError(Code.BAD_ALLOC, `cannot start another node: the bus process table is full (${this.bus.procCap}); create the Runtime with a larger maxProcesses`);
    }
    return pid;
  }

  /** Compile (once) the .wasm of an executable. */
  compiledModule(wasmUrl) {
    let p = this._modules.get(wasmUrl);
    if (!p) {
      p = compileWasm(wasmUrl);
      p.catch(() => this._modules.delete(wasmUrl));
      this._modules.set(wasmUrl, p);
    }
    return p;
  }

  /**
   * Fetch (once) an executable's scripts as text, in browsers: its glue and,
   * for a pthread build (a glue that names its `.worker.js`), Emscripten's
   * worker script. The program worker and each of the program's pthread workers
   * then run them from memory rather than by a synchronous network load each
   * (~10 ms less per script in Chromium). Under Node.js, and for a script
   * that cannot be fetched, nothing: the workers load it by URL as before.
   * @param {string} url the glue's absolute URL
   * @returns {Promise<Object<string, string>>} absolute URL -> script text
   */
  scriptTexts(url) {
    if (isNode) return Promise.resolve({});
    let p = this._scripts.get(url);
    if (!p) {
      const workerUrl = url.replace(/\.js$/, '.worker.js');
      const workerFile = workerUrl.slice(workerUrl.lastIndexOf('/') + 1);
      p = fetchScript(url).then(async (glue) => {
        const scripts = { [url]: glue };
        if (glue.includes(workerFile)) {
          const worker = await fetchScript(workerUrl).catch(() => null);
          if (worker) scripts[workerUrl] = worker;
        }
        return scripts;
      }, () => {
        this._scripts.delete(url); // try again next time; the worker loads it by URL
        return {};
      });
      this._scripts.set(url, p);
    }
    return p;
  }

  /**
   * Start an executable as a new bus process.
   * @param {object} spec
   * @param {string|URL} spec.url the executable's .js glue (URL, or file path in Node.js)
   * @param {string[]} [spec.args] command-line arguments (argv[1..])
   * @param {Object<string, string>} [spec.env] environment variables
   * @param {string} [spec.name] a name for logs (default: the file's base name)
   * @param {function({stream: string, severity: string, text: string, name: string, pid: number}): void} [spec.onLog]
   * @param {function({code: number|null, crashed: boolean, reason: string}): void} [spec.onExit]
   * @param {WebAssembly.Module} [spec.wasmModule] an already compiled module
   * @param {boolean} [spec.shareModule=true] compile the .wasm once and share it between spawns
   * @param {string|Uint8Array|boolean} [spec.stdin] standard input: a text (or bytes) the
   *   executable reads, then end of file; `true` for an open pipe fed with
   *   {@link NodeProcess#writeStdin} and ended with {@link NodeProcess#closeStdin};
   *   without it standard input is empty
   * @param {Object<string, string|Uint8Array>} [spec.files] files written into the executable's
   *   file system before main() runs (absolute path → content), e.g. a `--params-file`
   * @param {boolean} [spec.filesOptional=false] an executable linked without a file system
   *   (which reads no files) starts without `files` instead of failing (a launch file's
   *   parameters given to a program that is no ROS node)
   * @param {{point: string, flag: SharedArrayBuffer, skip?: number}} [spec.faultPoint] tests
   *   only: stop the program's main thread at this fault point of its bus operations
   *   (bus/faults.mjs), to kill it there
   * @param {Array<{path: string, url?: string, leftOut?: object}>} [spec.mounts] read-only
   *   views of host directories (install spaces), at the same absolute paths in the
   *   executable, mounted before main() runs and read lazily: from the host's files under
   *   Node.js, from `url` (served as view_source_http.mjs describes; needed in browsers)
   *   otherwise; `leftOut`: `{prefixes: {path: package}, hint}`, what a static export left
   *   out of the served view (a lookup there writes the hint to the program's stderr once)
   * @returns {Promise<NodeProcess>}
   */
  async spawn(spec) {
    if (this._closed) throw new BusError(Code.ERROR, 'spawn: the runtime is closed');
    if (!spec || !spec.url) throw new BusError(Code.INVALID_ARGUMENT, 'spawn: missing url of the executable (.js)');
    const spawnedAt = performance.now();
    const url = await resolveUrl(spec.url);
    const path = new URL(url).pathname;
    const glueFile = path.slice(path.lastIndexOf('/') + 1);
    if (!glueFile.endsWith('.js')) {
      throw new BusError(Code.INVALID_ARGUMENT, `spawn: '${spec.url}' is not an Emscripten executable (.js)`);
    }
    const wasmUrl = new URL(glueFile.replace(/\.js$/, '.wasm'), url).href;
    const name = spec.name || glueFile.replace(/\.js$/, '');
    const args = (spec.args || []).map(String);
    const env = {};
    for (const [k, v] of Object.entries(spec.env || {})) env[k] = String(v);
    const stdinPipe = makeStdinPipe(spec.stdin);
    const files = checkedFiles(spec.files, name);
    const mounts = checkedMounts(spec.mounts, files, name);
    let wasmModule = spec.wasmModule || null;
    let scripts = {};
    if (spec.shareModule !== false) {
      const texts = this.scriptTexts(url);
      if (!wasmModule) {
        try {
          wasmModule = await this.compiledModule(wasmUrl);
        } catch (e) {
          throw new BusError(Code.ERROR, `spawn '${name}': cannot compile ${wasmUrl}: ${e.message}`);
        }
      }
      scripts = await texts;
    }
    const pid = await this._allocPid(PROC_KIND_NODE);
    let worker;
    try {
      worker = await this._host();
    } catch (e) {
      this._fillSpares();
      await this._reap(pid, null);
      throw new BusError(Code.ERROR, `spawn '${name}': cannot start a worker: ${e.message}`);
    }
    const proc = new NodeProcess(this, pid, name, worker, { ...spec, spawnedAt, stdinPipe });
    this._fillSparesOnceSettled(proc);
    this.processes.set(pid, proc);
    worker.on('message', (m) => proc._onMessage(m));
    worker.on('error', (e) => {
      const where = e.filename ? ` (${e.filename}:${e.lineno})` : '';
      // an uncaught C++ exception arrives described by its program worker (program_worker.mjs)
      const reason = e.message && e.message.startsWith(UNCAUGHT_EXCEPTION) ? e.message
        : `uncaught error: ${e.message}${where}`;
      proc._finish({ code: 1, crashed: true, reason });
    });
    worker.on('exit', ({ code }) => {
      proc._finish({ code, crashed: code !== 0, reason: code !== 0 ? `worker exited with code ${code}` : '' });
    });
    worker.postMessage({
      type: ToWorker.START, bus: this.bus.handle, pid, url, wasmUrl, glueFile, args, env, name, wasmModule, stdin: stdinPipe && stdinPipe.sab, files, filesOptional: !!spec.filesOptional, mounts, scripts,
      faultPoint: spec.faultPoint || null,
      busModuleUrl: siblingUrl('bus_client.mjs'), workerModuleUrl: siblingUrl('program_worker.mjs'),
    });
    return proc;
  }

  /**
   * Boot the next warm worker once `proc` has settled (or after
   * REFILL_AFTER_MS): booting a worker and its pthread workers meanwhile would
   * compete with the starting program for the cores (~10 ms later first
   * publish on two cores).
   * @param {NodeProcess} proc
   */
  _fillSparesOnceSettled(proc) {
    if (this._spares.length >= this._warm) return;
    let timer = null;
    const later = new Promise((resolve) => {
      timer = setTimeout(resolve, REFILL_AFTER_MS);
      if (timer && typeof timer.unref === 'function') timer.unref();
    });
    Promise.race([proc.settled, later]).then(() => {
      clearTimeout(timer);
      this._fillSpares();
    });
  }

  /** Remove a dead process from the bus without blocking (main thread). */
  async _reap(pid, proc) {
    const bus = this.bus;
    bus.markDead(pid);
    bus.ringAll();
    // A terminated browser worker (or one of its pthreads) stops a little
    // later: if it holds the lock, let it finish the mutation it began.
    await bus.releaseGrace(pid, 250);
    await bus.lockAsync(this.pid);
    try {
      bus.cleanupProcess(pid);
      bus.releaseProcess(pid);
      bus.bumpGraph();
    } finally {
      bus.unlock(this.pid);
    }
    bus.ringAll();
    if (proc && this.processes.get(pid) === proc) this.processes.delete(pid);
  }

  /**
   * A snapshot of the graph: nodes, topics and services (with types and
   * endpoints with QoS and gids), per domain.
   */
  graph() {
    const procName = (pid) => (this.processes.get(pid) || {}).name || (this._toolsPid === pid ? 'tools' : '')
      || this._helpers.get(pid) || '';
    return graphOf(this.bus.snapshot(), procName);
  }

  /**
   * Call `callback(graph)` after graph changes (coalesced). Never blocks.
   * @param {function(object): void} callback
   * @returns {function(): void} unsubscribe
   */
  onGraphChange(callback) {
    this._graphListeners.add(callback);
    this._watchGraph();
    return () => this._graphListeners.delete(callback);
  }

  _watchGraph() {
    if (this._watching) return;
    this._watching = true;
    let seen = this.bus.graphVersion();
    const loop = () => {
      if (this._closed || this._graphListeners.size === 0) {
        this._watching = false;
        return;
      }
      const v = this.bus.graphVersion();
      if (v !== seen) {
        seen = v;
        const g = this.graph();
        for (const cb of [...this._graphListeners]) {
          try {
            cb(g);
          } catch (e) {
            console.error('onGraphChange callback threw:', e);
          }
        }
      }
      const r = this.bus.waitGraphAsync(v);
      if (r.async) r.value.then(loop);
      else Promise.resolve().then(loop);
    };
    loop();
  }

  /**
   * A process id for a JS-only bus process that a bridge runs in a worker of
   * its own (the Zenoh gateway, bridges/zenoh/): the worker attaches to
   * `bus.handle` with it. graph() names the process `name`.
   * @param {string} name
   * @returns {Promise<{pid: number, release: function(): Promise<void>}>} release: remove
   *   the process from the bus (its nodes and endpoints) once its worker stopped
   */
  async helperProcess(name) {
    const pid = await this._allocPid(PROC_KIND_TOOLS);
    this._helpers.set(pid, name);
    let released = null;
    const release = () => {
      if (!released) {
        released = this._reap(pid, null).finally(() => this._helpers.delete(pid));
      }
      return released;
    };
    return { pid, release };
  }

  /**
   * A JS-only bus process in a worker, for tools (echo, publish, service calls).
   * @returns {Promise<Tools>}
   */
  async tools() {
    if (!this._tools) {
      this._tools = (async () => {
        const pid = await this._allocPid(PROC_KIND_TOOLS);
        this._toolsPid = pid;
        return Tools.start(this, pid);
      })();
    }
    return this._tools;
  }

  /** Stop every process and the tools worker. */
  async close() {
    if (this._closed) return;
    const spares = this._spares;
    this._spares = [];
    this._warm = 0;
    await Promise.all(spares.map((s) => s.host.then((w) => w.terminate(), () => {})));
    await Promise.all(this._closeHooks.splice(0).map((fn) => Promise.resolve().then(fn).catch(() => {})));
    await Promise.all([...this.processes.values()].map((p) => p.stop()));
    if (this._tools) {
      const tools = await this._tools;
      await tools.close();
    }
    this._closed = true;
    this.bus.bumpGraph();
  }
}

export { PROC_KIND_TOOLS };
