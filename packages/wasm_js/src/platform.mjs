// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * The platform gap in one place: workers in the browser (Web Workers) and in
 * Node.js (worker_threads) behind one small interface.
 *
 * @module platform
 */

/** True under Node.js. */
export const isNode = typeof process === 'object' && !!(process.versions && process.versions.node) &&
  typeof window === 'undefined' && typeof importScripts !== 'function';

let nodeWorkerThreads = null;
let nodeUrl = null;

async function loadNode() {
  if (!nodeWorkerThreads) {
    nodeWorkerThreads = await import('node:worker_threads');
    nodeUrl = await import('node:url');
  }
}

/**
 * A worker with browser-style events on both platforms.
 */
export class ProgramWorker {
  /**
   * Start a worker.
   * @param {URL|string} url the worker script
   * @param {object} [options]
   * @param {string} [options.name] a name for debuggers
   * @param {'classic'|'module'} [options.type] browser script type
   * @returns {Promise<ProgramWorker>}
   */
  static async start(url, options = {}) {
    const w = new ProgramWorker();
    if (isNode) {
      await loadNode();
      const file = String(url).startsWith('file:') ? nodeUrl.fileURLToPath(String(url)) : String(url);
      w._w = new nodeWorkerThreads.Worker(file, { name: options.name });
      w._w.on('message', (data) => w._emit('message', data));
      w._w.on('error', (err) => w._emit('error', { message: err && err.message, error: err }));
      w._w.on('exit', (code) => w._emit('exit', { code }));
    } else {
      w._w = new Worker(String(url), { name: options.name, type: options.type || 'classic' });
      w._w.onmessage = (e) => w._emit('message', e.data);
      w._w.onerror = (e) => {
        e.preventDefault();
        w._emit('error', {
          message: e.message || 'worker script error',
          filename: e.filename, lineno: e.lineno, error: e.error,
        });
      };
      w._w.onmessageerror = () => w._emit('error', { message: 'a message from the worker could not be deserialized' });
    }
    return w;
  }

  constructor() {
    this._listeners = { message: [], error: [], exit: [] };
    this._w = null;
  }

  _emit(type, value) {
    for (const fn of this._listeners[type]) fn(value);
  }

  /**
   * Listen to 'message' (data), 'error' ({message}) or 'exit' ({code}, Node.js only).
   * @param {'message'|'error'|'exit'} type
   * @param {function} fn
   */
  on(type, fn) {
    this._listeners[type].push(fn);
  }

  /** Post a message (structured clone; SharedArrayBuffers and WebAssembly.Modules are shared). */
  postMessage(message, transfer) {
    this._w.postMessage(message, transfer || []);
  }

  /** Stop the worker (and its nested workers) now. */
  async terminate() {
    await this._w.terminate();
  }
}

/**
 * The URL of a file next to this module (works with file: and http(s): URLs).
 * @param {string} name
 */
export function siblingUrl(name) {
  return new URL(name, import.meta.url).href;
}

/**
 * Resolve an executable location given by the caller: a URL string, a URL,
 * or (Node.js) a file path.
 * @param {string|URL} urlOrPath
 * @returns {Promise<string>} absolute URL
 */
export async function resolveUrl(urlOrPath) {
  if (urlOrPath instanceof URL) return urlOrPath.href;
  const s = String(urlOrPath);
  if (/^[a-z][a-z0-9+.-]*:/i.test(s) && !/^[a-z]:[\\/]/i.test(s)) return s;
  if (isNode) {
    await loadNode();
    const path = await import('node:path');
    return nodeUrl.pathToFileURL(path.resolve(s)).href;
  }
  return new URL(s, globalThis.location ? globalThis.location.href : undefined).href;
}

/**
 * Fetch a classic script's text (browsers), so that workers can run it from
 * memory instead of a synchronous network load each. A `sourceURL` comment
 * is appended: stack traces and devtools then name the file.
 * @param {string} url absolute URL
 * @returns {Promise<string>}
 */
export async function fetchScript(url) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`cannot fetch ${url}: HTTP ${response.status}`);
  return `${await response.text()}\n//# sourceURL=${url}\n`;
}

/**
 * Compile a wasm file once (to share between nodes of the same executable).
 * @param {string} url absolute URL of the .wasm file
 * @returns {Promise<WebAssembly.Module>}
 */
export async function compileWasm(url) {
  if (isNode && url.startsWith('file:')) {
    await loadNode();
    const fs = await import('node:fs/promises');
    return WebAssembly.compile(await fs.readFile(nodeUrl.fileURLToPath(url)));
  }
  const response = await fetch(url);
  if (!response.ok) throw new Error(`cannot fetch ${url}: HTTP ${response.status}`);
  if (WebAssembly.compileStreaming) return WebAssembly.compileStreaming(response);
  return WebAssembly.compile(await response.arrayBuffer());
}
