// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * NodeProcess: the main thread's handle of one running executable (a bus
 * process) of the Runtime: its logs, exit, stop and standard input.
 *
 * @module node_process
 */

import { BusError, Code, waitAsyncAlive } from './bus.mjs';
import { FromWorker } from './protocol.mjs';
import { DEFAULT_STDIN_CAPACITY, StdinPipe } from './stdin_pipe.mjs';

const SEVERITY_RE = /^\[(DEBUG|INFO|WARN|ERROR|FATAL)\]/;
// rcutils colours its console output when isatty() says yes, which it does
// under Emscripten: "\x1b[33m[WARN] ...\x1b[0m".
const ANSI_SGR_RE = /\x1b\[[0-9;]*m/g;

/**
 * Remove ANSI colour codes (SGR sequences) from a log line.
 * @param {string} text
 */
export function stripAnsi(text) {
  return text.indexOf('\x1b') < 0 ? text : text.replace(ANSI_SGR_RE, '');
}

/**
 * Parse the severity of a log line: the ROS tag when there is one
 * (`[INFO] [1700000000.123456789] [talker]: ...`), else INFO for stdout and
 * ERROR for stderr.
 * @param {string} stream
 * @param {string} text
 */
export function severityOf(stream, text) {
  const m = SEVERITY_RE.exec(text);
  if (m) return m[1];
  return stream === 'stderr' ? 'ERROR' : 'INFO';
}

/** The gid words of an entity as hex (graph snapshots). */
export function gidHex(words) {
  return Array.from(new Uint8Array(Int32Array.from(words).buffer), (b) => b.toString(16).padStart(2, '0')).join('');
}

/**
 * The stdin pipe a spawn() asks for: none, an open one (`true`), or one
 * holding a whole text (or bytes) and closed.
 * @param {string|Uint8Array|boolean|null|undefined} stdin
 * @returns {StdinPipe|null}
 */
export function makeStdinPipe(stdin) {
  if (stdin === undefined || stdin === null || stdin === false) return null;
  if (stdin === true) return StdinPipe.create();
  const bytes = stdin instanceof Uint8Array ? stdin : new TextEncoder().encode(String(stdin));
  const pipe = StdinPipe.create(Math.max(DEFAULT_STDIN_CAPACITY, bytes.length));
  pipe.write(bytes);
  pipe.close();
  return pipe;
}

/**
 * One running executable (a bus process).
 */
export class NodeProcess {
  constructor(runtime, pid, name, worker, options) {
    /** Bus process id. */
    this.id = pid;
    /** Name given to spawn() (or the executable's base name). */
    this.name = name;
    /** performance.now() when spawn() created the worker. */
    this.spawnedAt = options.spawnedAt;
    /** performance.now() when the glue was loaded (main() about to run). */
    this.startedAt = null;
    /**
     * How many of its pthread pool workers were booted ahead by a warm worker
     * (known once started; 0 for a program without threads or a cold worker).
     */
    this.prestartedPthreadWorkers = 0;
    /**
     * True when the worker loaded the glue from the script the Runtime
     * prefetched (browsers, shared module), false when it loaded it by URL.
     */
    this.glueFromMemory = false;
    /**
     * A Python node, once started: true when its Pyodide was restored from
     * the host's snapshot (python/pyodide_snapshot.mjs), false when started anew.
     */
    this.pyodideSnapshot = false;
    /**
     * A Python node: true when it took the runtime's warm Python worker, whose
     * Pyodide was loaded before the spawn (python/python_spares.mjs).
     */
    this.warmPythonWorker = false;
    /**
     * Known once the program has exited by itself: true when its main
     * thread copied messages between its heap and the bus with
     * memory.copy (the bus is a WebAssembly.Memory, see copier.mjs), false
     * when it used TypedArray.set() or never published or took.
     */
    this.memoryCopy = false;
    this._runtime = runtime;
    this._worker = worker;
    this._options = options;
    this._done = false;
    this._stdin = options.stdinPipe || null;
    this._stdinWrites = Promise.resolve();
    /** Resolves with {code, crashed, reason} when the process has ended and left the graph. */
    this.exited = new Promise((resolve) => { this._resolve = resolve; });
    /**
     * Resolves (with nothing) once main() has started and settled: it first
     * waits on the bus, or has returned or yielded to the event loop; or when
     * the process has ended. performance.now() then: {@link NodeProcess#settledAt}.
     */
    this.settled = new Promise((resolve) => { this._resolveSettled = resolve; });
    /** performance.now() when main() settled (null before, and when it ended first). */
    this.settledAt = null;
  }

  _onMessage(m) {
    if (!m || typeof m !== 'object') return;
    if (m.type === FromWorker.LOG) {
      const onLog = this._options.onLog;
      if (onLog) {
        try {
          const text = stripAnsi(m.text);
          onLog({ stream: m.stream, severity: severityOf(m.stream, text), text, name: this.name, pid: this.id });
        } catch (e) {
          console.error(`onLog of '${this.name}' threw:`, e);
        }
      }
    } else if (m.type === FromWorker.STARTED) {
      this.startedAt = performance.now();
      this.prestartedPthreadWorkers = m.prestartedPthreadWorkers || 0;
      this.glueFromMemory = !!m.glueFromMemory;
      this.pyodideSnapshot = !!m.pyodideSnapshot;
    } else if (m.type === FromWorker.SETTLED) {
      if (this.settledAt === null && !this._done) this.settledAt = performance.now();
      this._resolveSettled();
    } else if (m.type === FromWorker.EXIT) {
      this.memoryCopy = !!m.memoryCopy;
      this._finish({ code: m.code, crashed: !!m.crashed, reason: m.reason || '' });
    }
  }

  async _finish(result) {
    if (this._done) return;
    this._done = true;
    this._resolveSettled();
    try {
      await this._worker.terminate();
    } catch (e) {
      // Already gone.
    }
    try {
      await this._runtime._reap(this.id, this);
    } catch (e) {
      // The exit must still be reported; the bus says what went wrong.
      console.error(`wasm_js: cleaning up after '${this.name}' (process ${this.id}) failed: ${e && e.stack ? e.stack : e}`);
    }
    if (this._options.onExit) {
      try {
        this._options.onExit(result);
      } catch (e) {
        console.error(`onExit of '${this.name}' threw:`, e);
      }
    }
    this._resolve(result);
  }

  /**
   * Write to the process' standard input (spawned with `stdin: true`), as a
   * user types into a terminal. Writes keep their order; a write larger than
   * the pipe waits until the process has read enough of it.
   * @param {string|Uint8Array} data text (UTF-8) or bytes
   * @returns {Promise<void>} resolves once every byte is in the pipe
   * @throws {BusError} when the process has no open standard input
   */
  writeStdin(data) {
    const bytes = typeof data === 'string' ? new TextEncoder().encode(data) : data;
    if (!(bytes instanceof Uint8Array)) {
      return Promise.reject(new BusError(Code.INVALID_ARGUMENT,
        `writeStdin '${this.name}': give a string or a Uint8Array, not ${typeof data}`));
    }
    const write = this._stdinWrites.then(() => this._writeAll(bytes));
    this._stdinWrites = write.catch(() => {});
    return write;
  }

  async _writeAll(bytes) {
    const pipe = this._checkStdin('writeStdin');
    let rest = bytes;
    for (;;) {
      if (this._done) {
        throw new BusError(Code.ERROR, `writeStdin '${this.name}': the process has ended`);
      }
      rest = rest.subarray(pipe.write(rest));
      this._runtime.bus.ring(this.id);
      if (rest.length === 0) return;
      // full: wait for the process to read (bounded, to notice its end)
      await waitAsyncAlive(pipe.i32, StdinPipe.READ_INDEX, pipe.readCount(), 50);
    }
  }

  /**
   * Close the process' standard input: it reads end of file once it has read
   * what was written before.
   * @returns {Promise<void>} resolves after the pending writes
   */
  closeStdin() {
    const close = this._stdinWrites.then(() => {
      const pipe = this._checkStdin('closeStdin');
      pipe.close();
      if (!this._done) this._runtime.bus.ring(this.id);
    });
    this._stdinWrites = close.catch(() => {});
    return close;
  }

  _checkStdin(what) {
    if (!this._stdin) {
      throw new BusError(Code.INVALID_ARGUMENT,
        `${what} '${this.name}': its standard input is not open (spawn it with stdin: true)`);
    }
    if (this._stdin.closed()) {
      throw new BusError(Code.INVALID_ARGUMENT, `${what} '${this.name}': its standard input is closed`);
    }
    return this._stdin;
  }

  /**
   * Terminate the process now; its nodes and endpoints leave the graph.
   * @returns {Promise<{code: number|null, crashed: boolean, reason: string}>}
   */
  stop() {
    this._finish({ code: null, crashed: false, reason: 'stopped' });
    return this.exited;
  }
}
