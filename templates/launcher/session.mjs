// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The page's one connection to the wasm_js Runtime: processes and their logs,
// the live graph, and the tools process (echo, publish, call) — every view
// goes through here, so the Runtime API is used in this file only.

import { TypeRegistry } from '../wasm_js/cdr.mjs';
import { graphModel, subscriptionQos } from '../wasm_js/page/graph.mjs';
import { mergeRemote } from '../wasm_js/bridges/rosbridge/remote_graph.mjs';
import { siteUrl } from './site_url.mjs';

const SEVERITY = /^\s*\[(DEBUG|INFO|WARN|WARNING|ERROR|FATAL)\]/;
const MAX_LOG = 5000;

let logSeq = 0;

function severityOf(stream, text) {
  const m = SEVERITY.exec(text);
  if (m) return m[1] === 'WARNING' ? 'WARN' : m[1];
  return stream === 'stderr' && /error|abort|exception|fatal/i.test(text) ? 'ERROR' : 'INFO';
}

export class Session {
  constructor(workspace) {
    this.workspace = workspace;
    this.listeners = new Map();
    this.processes = new Map();
    this.nextId = 1;
    this.runtime = null;
    this.tools = null;
    this.registry = new TypeRegistry();
    this.typeError = null;
    this.graph = graphModel(null);
    this.bridge = null;
    this.zenoh = null;
  }

  on(event, callback) {
    if (!this.listeners.has(event)) this.listeners.set(event, new Set());
    this.listeners.get(event).add(callback);
  }

  off(event, callback) {
    const set = this.listeners.get(event);
    if (set) set.delete(callback);
  }

  emit(event, ...args) {
    for (const cb of this.listeners.get(event) || []) {
      try { cb(...args); } catch (e) { console.error(`a ${event} listener failed`, e); }
    }
  }

  /**
   * Start the Runtime; the type descriptions and the tools process follow in
   * the background (`ready`), so that executables can start at once.
   */
  async start() {
    const { Runtime } = await import(siteUrl(this.workspace.runtime));
    this.Runtime = Runtime;
    const registry = this.loadTypes();
    this.runtime = await Runtime.create({});
    this.ready = (async () => {
      this.registry = await registry;
      this.tools = await this.runtime.tools();
      this.runtime.onGraphChange((raw) => this.refreshGraph(raw));
      this.refreshGraph(this.runtime.graph());
      this.emit('ready');
    })();
    // awaited by the page after it started the ?run executables
    this.ready.catch(() => {});
  }

  /** Load every package's types.json; a broken one is reported, the others load. */
  async loadTypes() {
    const registry = new TypeRegistry();
    const problems = [];
    this.typeDocuments = [];
    await Promise.all(this.workspace.types.map(async (url) => {
      try {
        const response = await fetch(url);
        if (!response.ok) throw new Error(`HTTP ${response.status}`);
        const document = await response.json();
        registry.add(document);
        this.typeDocuments.push(document);
      } catch (e) {
        problems.push(`${url}: ${e.message}`);
      }
    }));
    if (problems.length) this.typeError = `cannot load ${problems.join('; ')}`;
    return registry;
  }

  refreshGraph(raw) {
    // the runtime's own graph, the tools' endpoints included (the 3D view's feeds read it)
    this.rawGraph = raw;
    const hidden = this.zenoh ? [this.zenoh.pid] : [];
    this.graph = mergeRemote(mergeRemote(graphModel(raw, { toolsPid: this.tools ? this.tools.pid : undefined, hiddenPids: hidden }), this.bridge), this.zenoh);
    this.emit('graph', this.graph);
  }

  /**
   * Bridge the page's nodes to a rosbridge v2 server (`?rosbridge=ws://...`,
   * the header's connect field): bridges/rosbridge/client.mjs.
   */
  async connectBridge(url) {
    await this.ready;
    if (this.bridge) await this.disconnectBridge();
    const { RosbridgeClient } = await import('../wasm_js/bridges/rosbridge/client.mjs');
    this.bridge = await RosbridgeClient.start({
      runtime: this.runtime, registry: this.registry, url, remoteGraph: true,
      log: (level, text) => (level === 'error' ? console.error : console.log)(`[rosbridge] ${text}`),
      onChange: () => {
        this.emit('bridge', this.bridge);
        this.refreshGraph(this.runtime.graph());
      },
    });
    this.emit('bridge', this.bridge);
    return this.bridge;
  }

  /**
   * Join the page's nodes to the ROS 2 graph of a Zenoh router
   * (`?zenoh=ws/HOST:PORT`, the header's field): bridges/zenoh/gateway.mjs
   * with the install space's zenoh-pico module (workspace.zenoh.module).
   */
  async connectZenoh(endpoint) {
    await this.ready;
    if (!this.workspace.zenoh) {
      throw new Error('the install space has no zenoh_wasm_gateway: build zenoh-pico in the workspace (docs/zenoh.md)');
    }
    if (this.zenoh) await this.disconnectZenoh();
    const { parseEndpoint } = await import('../wasm_js/bridges/zenoh/link.mjs');
    if (parseEndpoint(endpoint).scheme !== 'ws') throw new Error(`a page reaches a router through its WebSocket listener: ws/HOST:PORT, not ${endpoint}`);
    const { ZenohGateway } = await import('../wasm_js/bridges/zenoh/gateway.mjs');
    this.zenoh = await ZenohGateway.start({
      runtime: this.runtime, registry: this.registry, endpoint, module: siteUrl(this.workspace.zenoh.module),
      log: (level, text) => (level === 'error' || level === 'warning' ? console.warn : console.log)(`[zenoh] ${text}`),
      onChange: () => {
        this.emit('zenoh', this.zenoh);
        this.refreshGraph(this.runtime.graph());
      },
    });
    this.emit('zenoh', this.zenoh);
    return this.zenoh;
  }

  async disconnectZenoh() {
    const gateway = this.zenoh;
    this.zenoh = null;
    if (gateway) await gateway.close();
    this.emit('zenoh', null);
    this.refreshGraph(this.runtime.graph());
  }

  async disconnectBridge() {
    const bridge = this.bridge;
    this.bridge = null;
    if (bridge) await bridge.close();
    this.emit('bridge', null);
    this.refreshGraph(this.runtime.graph());
  }

  runningCount() {
    let n = 0;
    for (const p of this.processes.values()) {
      if (p.kind !== 'launch' && (p.state === 'starting' || p.state === 'running')) n++;
    }
    return n;
  }

  /**
   * Start an executable; several instances of one are numbered like ros2 launch does.
   * `extra` is what a launch file gives a process (./launch_run.mjs): `env` over the install's,
   * `files` written into its file system (launch_ros' --params-file files), `launch` (the
   * launch's entry it belongs to), `onLog` ({stream, text}: its output) and `onExit`, called
   * once with its end.
   */
  startProcess(pkg, exe, args, extra = {}) {
    const info = this.workspace.packages.find((p) => p.name === pkg)?.executables.find((e) => e.name === exe);
    if (!info) throw new Error(`there is no executable ${pkg}/${exe} in this install space`);
    if (info.python) return this.startPythonEntryPoint(pkg, info, args, extra);
    const proc = this.newProcess(pkg, exe, args, extra);
    this.addLog(proc, { severity: 'SYSTEM', text: `starting ${pkg}/${exe} ${args.join(' ')}`.trim() });
    const view = this.installView();
    if (view.mounts.length && !(this.Runtime.features && this.Runtime.features.mounts)) {
      this.addLog(proc, {
        severity: 'WARN',
        text: `the wasm_js runtime (${this.workspace.runtime}) predates read-only views: ${exe} does not see `
          + 'its install space; rebuild it with colcon build --wasm --packages-select wasm_js',
      });
    }
    this.emit('processes');
    const started = this.runtime.spawn({
      url: siteUrl(info.url),
      args: proc.args,
      name: proc.label,
      ...view,
      env: { ...view.env, ...(extra.env || {}) },
      ...(extra.files && Object.keys(extra.files).length ? { files: extra.files } : {}),
      onLog: ({ stream, text }) => {
        this.addLog(proc, { stream, severity: severityOf(stream, text), text });
        if (extra.onLog) extra.onLog({ stream, text });
      },
      onExit: (exit) => this.exited(proc, exit),
      stdin: true, // an open standard input, typed into from the log dock
    });
    return this.track(proc, started);
  }

  /**
   * List a launch file's run (./launch_run.mjs) as a process of its own: its
   * log is launch's output, its Stop button stops the launch.
   * @param {{stop: function(): Promise<void>}} handle
   */
  addLaunch(pkg, file, args, handle) {
    const proc = Object.assign(this.newProcess(pkg, file, args), {
      label: `launch ${file.split('/').pop()}`, state: 'running', handle, kind: 'launch', noStdin: true,
    });
    this.emit('processes');
    return proc;
  }

  /** List a new process, numbered like ros2 launch numbers them (`talker-3`). */
  newProcess(pkg, exe, args, extra = {}) {
    const id = this.nextId++;
    const proc = {
      id, pkg, exe, args: [...args], label: `${exe}-${id}`, state: 'starting', log: [], exit: null, handle: null,
      started: performance.now(), launch: extra.launch || null, onExit: extra.onExit || null,
    };
    this.processes.set(id, proc);
    return proc;
  }

  /** Follow a spawn: the process runs once it resolves, or crashed with its error. */
  track(proc, started) {
    proc.starting = started;
    started.then((handle) => {
      proc.handle = handle;
      if (proc.state === 'starting') proc.state = 'running';
      if (proc.stopRequested) handle.stop();
      this.emit('processes');
    }, (error) => {
      this.exited(proc, { code: null, crashed: true, reason: error && error.message ? error.message : String(error), stack: error && error.stack });
    });
    return proc;
  }

  /**
   * Start a Python node (Pyodide in a Web Worker, the pure-Python rclpy of
   * wasm_js/python/): its `name`.py runs as `__main__` with `args` as sys.argv[1:].
   * Listed, logged and stopped like an executable.
   */
  startPython(name, source, args = [], { stdin = false } = {}) {
    const exe = name.replace(/\.py$/, '');
    return this.spawnPythonProcess('python', exe, args, `starting Python ${name} ${args.join(' ')}`, async () => ({
      file: `/python/${name.endsWith('.py') ? name : `${name}.py`}`, source, stdin,
    }));
  }

  /**
   * Start an entry point of a Python package of the install space (its
   * console_scripts, `colcon build --wasm` packed it): Pyodide imports its module
   * from the install space's Python packages, fetched from serve at their real
   * paths, and runs `sys.exit(function())` as the installed script does.
   */
  startPythonEntryPoint(pkg, info, args, extra = {}) {
    const python = this.workspace.python || {};
    return this.spawnPythonProcess(pkg, info.name, args, `starting ${pkg}/${info.name} (Python) ${args.join(' ')}`,
      async () => ({
        file: info.file, pythonPath: python.path || [], pythonFiles: await this.pythonFiles(), stdin: true,
        // a console_scripts entry point, or a script a CMake package installed (run as __main__)
        ...(info.python.script ? { source: await this.pythonScript(info) } : { entry: info.python }),
      }), extra);
  }

  /** The text of a Python script of the install space (served at its executable's URL). */
  async pythonScript(info) {
    const response = await fetch(info.url);
    if (!response.ok) throw new Error(`cannot load the Python script ${info.file}: HTTP ${response.status} for ${info.url}`);
    return response.text();
  }

  /**
   * List, log and start one Python process: `spec()` gives what is its own
   * (file, source or entry, ...); Pyodide, the types, the environment and the
   * log and exit handlers are every Python process' of the page.
   */
  spawnPythonProcess(pkg, exe, args, startText, spec, extra = {}) {
    const python = this.workspace.python || {};
    const proc = this.newProcess(pkg, exe, args, extra);
    this.addLog(proc, { severity: 'SYSTEM', text: startText.trim() });
    this.emit('processes');
    const started = (async () => {
      if (!python.pyodide) throw new Error(python.problem || 'this serve does not serve Pyodide: start it with --pyodide DIR');
      await this.ready;
      const own = await spec();
      const { spawnPython } = await import('../wasm_js/python/spawn.mjs');
      return spawnPython(this.runtime, {
        ...own, args: proc.args, name: proc.label, env: { ...this.installView().env, ...(extra.env || {}) },
        pyodideUrl: siteUrl(python.pyodide),
        types: this.typeDocuments || [],
        onLog: ({ stream, text }) => {
          this.addLog(proc, { stream, severity: severityOf(stream, text), text });
          if (extra.onLog) extra.onLog({ stream, text });
        },
        onExit: (exit) => this.exited(proc, exit),
      });
    })();
    return this.track(proc, started);
  }

  /** The Python packages' files ({path, text}), fetched once per page. */
  pythonFiles() {
    if (!this._pythonFiles) {
      const files = (this.workspace.python && this.workspace.python.files) || [];
      this._pythonFiles = Promise.all(files.map(async ({ path, url }) => {
        const response = await fetch(url);
        if (!response.ok) throw new Error(`cannot load the Python module ${path}: HTTP ${response.status} for ${url}`);
        return { path, text: await response.text() };
      }));
      this._pythonFiles.catch(() => { this._pythonFiles = null; });
    }
    return this._pythonFiles;
  }

  /**
   * Start the Python console: a REPL (wasm_js/python/console.py) with rclpy
   * imported, read from the process' standard input (the log dock's line).
   */
  async startPythonConsole() {
    const response = await fetch(siteUrl('wasm_js/python/console.py'));
    if (!response.ok) throw new Error(`cannot load the Python console: HTTP ${response.status} for ${siteUrl('wasm_js/python/console.py')}`);
    return this.startPython('python_console.py', await response.text(), [], { stdin: true });
  }

  /**
   * What every program sees of the install spaces (colcon_wasm/launch/install_view.py):
   * read-only views served by `colcon-wasm serve` under /fs/, and AMENT_PREFIX_PATH.
   * @returns {{mounts: Array<{path: string, url: string}>, env: Object<string, string>}}
   */
  installView() {
    // an exported site that left packages out: a node looking there is told which option includes them
    const leftOut = this.workspace.left_out || undefined;
    const mounts = (this.workspace.mounts || []).map((m) => ({ path: m.path, url: siteUrl(m.url), leftOut }));
    const env = {};
    for (const [name, value] of Object.entries(this.workspace.environment || {})) if (value) env[name] = value;
    return { mounts, env };
  }

  exited(proc, exit) {
    if (proc.state === 'exited' || proc.state === 'crashed' || proc.state === 'stopped') return;
    proc.exit = exit || {};
    if (proc.onExit) proc.onExit(proc.exit);
    if (proc.stopRequested && !proc.exit.crashed) {
      proc.state = 'stopped';
      this.addLog(proc, { severity: 'SYSTEM', text: `${proc.label} stopped` });
    } else if (proc.exit.crashed || (proc.exit.code !== 0 && proc.exit.code !== undefined && proc.exit.code !== null)) {
      proc.state = 'crashed';
      const code = proc.exit.code === null || proc.exit.code === undefined ? '' : ` (exit code ${proc.exit.code})`;
      this.addLog(proc, {
        severity: 'ERROR', crash: true,
        text: `${proc.exit.reason || 'the process died'}${code}. The other nodes go on.`,
        detail: proc.exit.stack || null,
      });
    } else {
      proc.state = 'exited';
      this.addLog(proc, { severity: 'SYSTEM', text: `${proc.label} finished (exit code ${proc.exit.code ?? 0})` });
    }
    this.emit('processes');
  }

  addLog(proc, entry) {
    const lines = entry.crash ? [entry.text] : String(entry.text).split('\n').filter((l) => l !== '');
    for (const text of lines) {
      const e = { ...entry, text, seq: logSeq++, time: performance.now() };
      proc.log.push(e);
      if (proc.log.length > MAX_LOG) proc.log.splice(0, proc.log.length - MAX_LOG);
      this.emit('log', proc, e);
    }
  }

  /**
   * Type a line into a running process' standard input, as into its
   * terminal; the line is echoed in its log.
   * @returns {Promise<void>}
   */
  sendStdin(id, line) {
    const proc = this.processes.get(id);
    if (!proc || !proc.handle || proc.state !== 'running') {
      return Promise.reject(new Error('the process is not running'));
    }
    this.addLog(proc, { severity: 'SYSTEM', text: `stdin › ${line}` });
    return proc.handle.writeStdin(`${line}\n`).catch((e) => {
      this.addLog(proc, { severity: 'ERROR', text: `standard input: ${e.message}` });
    });
  }

  /** End a running process' standard input (end of file, like Ctrl-D). */
  closeStdin(id) {
    const proc = this.processes.get(id);
    if (!proc || !proc.handle || proc.state !== 'running') return Promise.resolve();
    this.addLog(proc, { severity: 'SYSTEM', text: 'stdin closed (end of file)' });
    return proc.handle.closeStdin().catch((e) => {
      this.addLog(proc, { severity: 'ERROR', text: `standard input: ${e.message}` });
    });
  }

  stopProcess(id) {
    const proc = this.processes.get(id);
    if (!proc) return;
    proc.stopRequested = true;
    this.addLog(proc, { severity: 'SYSTEM', text: `stopping ${proc.label}` });
    if (proc.handle) {
      proc.handle.stop().then(() => this.exited(proc, { code: null, crashed: false, reason: 'stopped' }),
        (e) => this.addLog(proc, { severity: 'ERROR', text: `stopping failed: ${e.message}` }));
    }
  }

  forgetFinished() {
    for (const [id, p] of this.processes) if (p.state !== 'starting' && p.state !== 'running') this.processes.delete(id);
    this.emit('processes');
  }

  // ---------------------------------------------------------------- tools

  /**
   * Subscribe to a topic: onBatch([{bytes, time, seq}]). Returns {close()} at
   * once. The QoS matches the topic's publishers (as ros2 topic echo does),
   * unless one is given.
   */
  subscribe(topic, type, onBatch, qos = null) {
    let seq = 0;
    let closed = false;
    const entry = this.graph.topics.find((t) => t.name === topic);
    qos ||= subscriptionQos(entry ? entry.publisherQos : []);
    const pending = this.tools.subscribe({ topic, type, qos }, (messages) => {
      if (closed) return;
      const now = performance.now();
      onBatch(messages.map((m) => ({ bytes: m.data, info: m.info, time: now, seq: ++seq })));
    });
    pending.catch((e) => console.error(`subscribing to ${topic} failed:`, e));
    return {
      ready: pending,
      close: () => {
        closed = true;
        pending.then((s) => s.close()).catch(() => {});
      },
    };
  }

  /** A publisher of the tools process: {publish(bytes) -> Promise, close()}. */
  publisher(topic, type) {
    const pending = this.tools.advertise({ topic, type, qos: {} });
    return {
      publish: async (bytes) => (await pending).publish(bytes),
      close: () => pending.then((p) => p.close()).catch(() => {}),
    };
  }

  /** Call a service with request bytes; resolves to the response bytes. */
  async call(service, type, bytes, timeoutMs) {
    const response = await this.tools.call({ service, type, qos: {}, timeoutMs }, bytes);
    return response.data;
  }

  /** The {call, subscribe} pair the action and parameter clients use. */
  toolsBus() {
    return {
      call: (service, type, bytes, timeoutMs) => this.call(service, type, bytes, timeoutMs),
      subscribe: (topic, type, onBatch) => this.subscribe(topic, type, onBatch),
    };
  }
}
