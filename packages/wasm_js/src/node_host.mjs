// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Node.js host worker (worker_threads). The Runtime posts one START message;
 * see host_common.mjs. The glue runs in global scope, as in a browser worker,
 * with the CommonJS globals it expects (require, __filename, __dirname).
 *
 * @module node_host
 */

import fs from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { parentPort } from 'node:worker_threads';

import { startProcess } from './host_common.mjs';

parentPort.once('message', (msg) => {
  if (!msg || msg.type !== 'start') return;
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
  });
});
