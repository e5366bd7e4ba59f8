// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Node.js program worker (worker_threads). The Runtime may first post PRELOAD
 * (boot pthread workers ahead, then answer READY: a warm worker), then posts
 * one START; see program_worker.mjs. The glue runs in global scope, as in a browser worker,
 * with the CommonJS globals it expects (require, __filename, __dirname).
 *
 * @module program_worker_node
 */

import fs from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { Worker, parentPort } from 'node:worker_threads';

import { prestartPthreadWorkers, startProcess } from './program_worker.mjs';
import { fileViewSource } from './view_source_node.mjs';

/** A pre-started pthread worker (see pthread_pool.mjs). */
function pthreadStub() {
  const worker = new Worker(new URL('./pthread_stub_node.mjs', import.meta.url), { name: 'wasm_js pthread' });
  return {
    worker,
    listen(fn) {
      const onMessage = (m) => fn(m);
      const onError = (e) => fn({ colconWasmError: e && e.message ? e.message : String(e) });
      const onExit = (code) => fn({ colconWasmError: `exited with code ${code}` });
      worker.on('message', onMessage);
      worker.on('error', onError);
      worker.on('exit', onExit);
      return () => {
        worker.off('message', onMessage);
        worker.off('error', onError);
        worker.off('exit', onExit);
      };
    },
    // An idle stub does not keep the worker alive; Emscripten's workers do.
    idle: () => worker.unref(),
    busy: () => worker.ref(),
  };
}

const onMessage = (msg) => {
  if (msg && msg.type === 'preload') {
    // The program worker module is a static import: already loaded.
    prestartPthreadWorkers(msg.pthreadWorkers, msg.busModuleUrl, pthreadStub).finally(() => {
      parentPort.postMessage({ type: 'ready' });
    });
    return;
  }
  if (!msg || msg.type !== 'start') return;
  parentPort.off('message', onMessage);
  const glue = fileURLToPath(msg.url);
  startProcess(msg, {
    loadGlue() {
      globalThis.require = createRequire(glue);
      globalThis.__filename = glue;
      globalThis.__dirname = path.dirname(glue);
      (0, eval)(fs.readFileSync(glue, 'utf8'));
    },
    locate: (file) => path.join(path.dirname(glue), file),
    post: (m) => parentPort.postMessage(m),
    close: (code) => {
      // Emscripten calls process.exit() itself after onExit; this covers other paths.
      setImmediate(() => process.exit(code || 0));
    },
    compile: async (url) => WebAssembly.compile(await fs.promises.readFile(fileURLToPath(url))),
    fileViewSource,
  });
};
parentPort.on('message', onMessage);
