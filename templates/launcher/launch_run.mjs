// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * A launch file started from the page: `colcon-wasm serve` evaluates it on
 * the build host, the page runs its nodes (colcon_wasm/server/launch_socket.py).
 *
 * A file Humble's launch runs: every host program launch starts for a node
 * (node_shim.py) is a channel of the `/launch` WebSocket, served here as the
 * Node.js host of `colcon-wasm launch` serves it (wasm_js'
 * launch/process_protocol.mjs): the node runs on the page's bus, its output
 * and its end go back to launch, launch_ros' own ROS node is a bus process of
 * the page (launch/host_link.mjs). So process events, respawn, lifecycle and
 * composable nodes are launch's own. A file colcon-wasm's reader reads: serve
 * sends the plan, the page starts its processes and loads its composable nodes.
 *
 * The launch is listed as a process of its own: its log is launch's output
 * (lines of the nodes' own output are in the nodes' logs), its Stop is Ctrl-C.
 */

/** Lines of launch's output that are a process' own output (`[talker-1] ...`). */
const PROCESS_LINE = /^\[([^\]\s]+)\] /;
const LAUNCH_SEVERITIES = new Set(['DEBUG', 'INFO', 'WARNING', 'WARN', 'ERROR', 'FATAL']);

/** The URL of serve's /launch socket. */
function socketUrl(path) {
  return `${location.protocol === 'https:' ? 'wss' : 'ws'}://${location.host}${path}`;
}

/** Ask serve for a launch file's declared arguments: [{name, default, description, choices, conditional}]. */
export function launchArguments(workspace, pkg, file) {
  return new Promise((resolve, reject) => {
    const ws = new WebSocket(socketUrl(workspace.launch.socket));
    ws.onopen = () => ws.send(JSON.stringify({ op: 'arguments', package: pkg, file }));
    ws.onmessage = (e) => {
      const message = JSON.parse(e.data);
      if (message.op === 'arguments') resolve(message.arguments);
      else if (message.op === 'error') reject(new Error(message.msg));
      ws.close();
    };
    ws.onerror = () => reject(new Error(`cannot reach ${workspace.launch.socket} of colcon-wasm serve`));
  });
}

export class LaunchRun {
  /**
   * @param {import('./session.mjs').Session} session
   * @param {string} pkg the package of the launch file
   * @param {string} file its name (or its path in the share folder)
   * @param {Object<string, string>} args name:=value launch arguments
   */
  constructor(session, pkg, file, args) {
    this.session = session;
    this.pkg = pkg;
    this.file = file;
    this.args = args;
    this.channels = new Map();
    this.ws = null;
    this.entry = null;
    this.ended = new Promise((resolve) => { this._end = resolve; });
    this.onRviz = null;
  }

  /** Connect and start; resolves with the launch's process entry once serve started it. */
  async start() {
    const { session } = this;
    const words = Object.entries(this.args).map(([k, v]) => `${k}:=${v}`);
    // loaded first: the channels' messages are then handled in the order they come
    ({ processConnection: this.processConnection } = await import('../wasm_js/launch/process_protocol.mjs').catch(() => {
      throw new Error(`the wasm_js runtime (${session.workspace.runtime}) has no launch/process_protocol.mjs: `
        + 'rebuild it with colcon build --wasm --packages-select wasm_js');
    }));
    return new Promise((resolve, reject) => {
      const ws = new WebSocket(socketUrl(session.workspace.launch.socket));
      this.ws = ws;
      ws.onopen = () => ws.send(JSON.stringify({ op: 'start', package: this.pkg, file: this.file, arguments: this.args }));
      ws.onmessage = (e) => {
        const message = JSON.parse(e.data);
        if (message.op === 'started') {
          this.runner = message.runner;
          this.entry = session.addLaunch(this.pkg, this.file, words, { stop: () => this.stop() });
          session.addLog(this.entry, { severity: 'SYSTEM', text: `launching ${this.pkg} ${this.file} ${words.join(' ')}`.trim() });
          resolve(this.entry);
        } else if (message.op === 'error' && !this.entry) {
          reject(new Error(message.msg));
          ws.close();
        } else {
          this.onMessage(message);
        }
      };
      ws.onerror = () => reject(new Error(`cannot reach ${session.workspace.launch.socket} of colcon-wasm serve`));
      ws.onclose = () => {
        if (this.entry && this.entry.state === 'running') {
          this.finish({ code: null, crashed: true, reason: 'the connection to colcon-wasm serve closed' });
        }
      };
    });
  }

  /**
   * Start a launch an exported site planned (colcon-wasm export --launch):
   * the reader's plan, made when the site was written, started here with no
   * server, as a reader's plan from serve is. Resolves with its entry.
   */
  async startPlanned(plan) {
    const words = Object.entries(this.args).map(([k, v]) => `${k}:=${v}`);
    this.runner = 'reader';
    this.entry = this.session.addLaunch(this.pkg, this.file, words, { stop: () => this.stop() });
    this.session.addLog(this.entry, {
      severity: 'SYSTEM', text: `launching ${this.pkg} ${this.file} ${words.join(' ')} (planned by the export)`.trim(),
    });
    await this.startPlan(plan);
    return this.entry;
  }

  send(message) {
    if (this.ws && this.ws.readyState === WebSocket.OPEN) this.ws.send(JSON.stringify(message));
  }

  log(stream, text) {
    if (!this.entry) return;
    const severity = /^\[(ERROR|FATAL)\]/.test(text) ? 'ERROR' : (/^\[WARN/.test(text) ? 'WARN' : 'INFO');
    this.session.addLog(this.entry, { stream, severity, text });
  }

  /** Handle one message of serve, at once (a channel's requests run on, in their order). */
  onMessage(message) {
    const failed = (error) => this.log('stderr', `[ERROR] [launch]: ${error && error.stack ? error.stack : error}`);
    switch (message.op) {
      case 'output': {
        const match = PROCESS_LINE.exec(message.text);
        if (!match || LAUNCH_SEVERITIES.has(match[1])) this.log(message.stream, message.text);
        break;
      }
      case 'open':
        this.openChannel(message.ch);
        break;
      case 'to': {
        const channel = this.channels.get(message.ch);
        if (channel) channel.onMessage(message.msg).catch(failed);
        break;
      }
      case 'closed': {
        const channel = this.channels.get(message.ch);
        this.channels.delete(message.ch);
        if (channel) channel.onClose();
        break;
      }
      case 'rviz':
        if (this.onRviz) this.onRviz(message.uri);
        break;
      case 'plan':
        this.startPlan(message).catch(failed);
        break;
      case 'ended':
        this.finish({ code: message.code, crashed: false });
        break;
      case 'error':
        this.log('stderr', `[ERROR] [launch]: ${message.msg}`);
        break;
      default:
        this.log('stderr', `[WARNING] [launch]: serve sent an unknown message '${message.op}'`);
    }
  }

  /** A host program of the launch connected: serve it as process_server.mjs does. */
  openChannel(ch) {
    const io = {
      send: (msg) => this.send({ op: 'from', ch, msg }),
      end: () => this.send({ op: 'close', ch }),
    };
    this.channels.set(ch, this.processConnection(io, {
      spawn: (proc, hooks) => this.spawn(proc, hooks),
      end: () => {},
      link: () => this.link(),
      err: (text) => this.log('stderr', text),
    }));
  }

  /** Start a node launch asked for; resolves with its handle once it runs. */
  async spawn(proc, hooks) {
    const started = this.session.startProcess(proc.package, proc.executable, proc.args || [], {
      env: proc.env || {}, files: proc.files || {}, launch: this.entry, onLog: hooks.onLog, onExit: hooks.onExit,
    });
    await started.starting.catch(() => {}); // a failed start is its exit, sent by onExit
    return { stop: () => this.session.stopProcess(started.id) };
  }

  /** launch_ros' ROS node: a bus process of the page, with the page's type descriptions. */
  async link() {
    const { startHostLink } = await import('../wasm_js/launch/host_link.mjs');
    await this.session.ready;
    return startHostLink(this.session.runtime, this.session.typeDocuments || [],
      (stream, text) => this.log(stream, `[launch_ros] ${text}`));
  }

  /** colcon-wasm's reader made the plan: start its processes, then load its composable nodes. */
  async startPlan({ processes, loads, load_timeout: timeout }) {
    const running = new Set();
    let loader = null;
    let failed = false; // as colcon-wasm launch: 1 when a process crashed or ended with an error
    for (const proc of processes) {
      this.session.startProcess(proc.package, proc.executable, proc.args || [], {
        env: proc.env || {}, launch: this.entry,
        onExit: (exit) => {
          running.delete(proc.label);
          if (exit.crashed || (exit.code && exit.reason !== 'stopped')) failed = true;
          if (loader) loader.processExited();
          if (running.size === 0) this.finish({ code: failed ? 1 : 0, crashed: false });
        },
      });
      running.add(proc.label);
    }
    if (!loads || loads.length === 0) return;
    const { ComposableLoader } = await import('../wasm_js/launch/composable.mjs');
    await this.session.ready;
    loader = new ComposableLoader({
      runtime: this.session.runtime,
      tools: () => this.session.runtime.tools(),
      registry: this.session.registry,
      timeoutMs: (timeout || 60) * 1000,
      isRunning: (label) => running.has(label),
      out: (text) => this.log('stdout', text),
      err: (text) => this.log('stderr', text),
    });
    for (const group of loads) loader.load(group);
    this.loader = loader;
  }

  /** Stop the launch, as Ctrl-C; resolves once it has ended. */
  stop() {
    if (this.runner === 'reader') {
      if (this.loader) this.loader.shutdown();
      for (const proc of this.session.processes.values()) {
        if (proc.launch === this.entry && (proc.state === 'running' || proc.state === 'starting')) {
          this.session.stopProcess(proc.id);
        }
      }
      this.finish({ code: 0, crashed: false, reason: 'stopped' });
    } else {
      this.send({ op: 'stop' });
    }
    return this.ended;
  }

  /** The launch has ended: what of it still runs is stopped, its entry shows the status. */
  finish(exit) {
    if (!this.entry || this.entry.state !== 'running') return;
    for (const proc of this.session.processes.values()) {
      if (proc.launch === this.entry && (proc.state === 'running' || proc.state === 'starting')) {
        this.session.stopProcess(proc.id);
      }
    }
    for (const channel of this.channels.values()) channel.onClose();
    this.channels.clear();
    this.session.exited(this.entry, exit);
    if (this.ws) this.ws.close();
    this._end();
  }
}
