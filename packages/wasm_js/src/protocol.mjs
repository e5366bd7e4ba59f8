// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Messages between the Runtime (page or Node.js main thread) and its workers.
 * Wire format only: no logic.
 *
 * @module protocol
 */

/** Runtime -> program worker. */
export const ToWorker = Object.freeze({
  /**
   * {type, workerModuleUrl, pthreadWorkers, busModuleUrl}: import the program worker module
   * and boot `pthreadWorkers` pthread workers now (a warm, idle worker); answered by READY
   */
  PRELOAD: 'preload',
  /**
   * {type, bus, pid, url, wasmUrl, glueFile, args, env, name, wasmModule, stdin (SharedArrayBuffer
   * of a StdinPipe, or null), files, mounts ([{path, url?}]: read-only views, see view_fs.mjs),
   * scripts (absolute URL -> text: the glue and pthread worker script, prefetched in browsers;
   * may be empty), busModuleUrl, workerModuleUrl, faultPoint (tests only: {point, flag, skip}
   * of bus/faults.mjs, or null)}
   */
  START: 'start',
});

/** Program worker -> Runtime. */
export const FromWorker = Object.freeze({
  /** {type} the program worker module is imported; the worker waits for START */
  READY: 'ready',
  /** {type, stream: 'stdout'|'stderr', text} one line */
  LOG: 'log',
  /**
   * {type, prestartedPthreadWorkers, glueFromMemory, pyodideSnapshot} the glue is loaded
   * (from its prefetched text, or by URL) and main() is about to run; a Python worker: Pyodide
   * is loaded (from the host's snapshot, or anew) and the script is about to run
   */
  STARTED: 'started',
  /**
   * {type} main() has started and settled: it sleeps on the bus for the first time, or has
   * returned or yielded to the event loop (not sent when the program exits first)
   */
  SETTLED: 'settled',
  /**
   * {type, code, crashed, reason, memoryCopy} the program ended; memoryCopy: its main
   * thread copied messages with memory.copy (see NodeProcess.memoryCopy)
   */
  EXIT: 'exit',
});

/** Runtime <-> tools worker (request/response, comlink style). */
export const ToTools = Object.freeze({
  /** {type, bus, pid} */
  INIT: 'init',
  /** {type, id, method, args} */
  CALL: 'call',
});

export const FromTools = Object.freeze({
  /** {type, id, ok: true, value} or {type, id, ok: false, error: {name, message, code, stack}} */
  RETURN: 'return',
  /** {type, subscription, messages: [{data: Uint8Array, info}]} */
  BATCH: 'batch',
  /** {type, service, requests: [{data: Uint8Array, id: {gid, seqLo, seqHi}, info}]} for serve() */
  REQUESTS: 'requests',
});

/**
 * How a program worker starts the crash reason of an uncaught C++ exception (the
 * worker's error carries it when the EXIT message has not arrived first).
 */
export const UNCAUGHT_EXCEPTION = 'uncaught exception of type ';
