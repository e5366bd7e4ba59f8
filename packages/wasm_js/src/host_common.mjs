// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * What a host worker does to run one executable as a bus process: attach to
 * the bus, build the Emscripten `Module` (arguments, environment, log hooks,
 * the shared compiled wasm module, the bus) and load the executable's glue.
 * Used by web_host.js (browser) and node_host.mjs (Node.js).
 *
 * @module host_common
 */

import { BusClient } from './bus_client.mjs';
import { FromHost } from './protocol.mjs';

/**
 * The platform half of a host.
 * @typedef {object} HostPlatform
 * @property {function(string): void} loadGlue run the glue script (URL or path) in global scope
 * @property {function(string): string} locate the URL or path Emscripten should use for a file
 *   next to the glue (pthread worker script, ...)
 * @property {function(object): void} post post a message to the Runtime
 * @property {function(number): void} close end this worker
 * @property {function(string): Promise<WebAssembly.Module>} compile compile a .wasm URL
 */

/**
 * Start the executable described by a START message.
 * @param {object} msg the START message (see protocol.mjs)
 * @param {HostPlatform} platform
 */
export async function startProcess(msg, platform) {
  const post = platform.post;
  let exited = false;
  const exit = (code, crashed, reason) => {
    if (exited) return;
    exited = true;
    post({ type: FromHost.EXIT, code, crashed, reason });
  };
  try {
    const client = BusClient.attach(msg.bus, msg.pid);
    const module = msg.wasmModule || await platform.compile(msg.wasmUrl);
    const env = msg.env || {};
    const Module = {
      arguments: msg.args || [],
      thisProgram: msg.name,
      print: (text) => post({ type: FromHost.LOG, stream: 'stdout', text: String(text) }),
      printErr: (text) => post({ type: FromHost.LOG, stream: 'stderr', text: String(text) }),
      wasmBus: { client, moduleUrl: msg.busModuleUrl },
      env,
      locateFile: (path) => platform.locate(path),
      mainScriptUrlOrBlob: platform.locate(msg.glueFile),
      instantiateWasm: (imports, receive) => {
        WebAssembly.instantiate(module, imports).then(
          (instance) => receive(instance, module),
          (err) => exit(1, true, `cannot instantiate ${msg.wasmUrl}: ${err && err.message}`));
        return {};
      },
      preRun: [() => {
        // Executables that do not link wasm_cpp get their environment here.
        if (typeof globalThis.ENV === 'object' && globalThis.ENV) Object.assign(globalThis.ENV, env);
      }],
      onExit: (code) => {
        exit(code, code !== 0, code !== 0 ? `exited with code ${code}` : '');
        platform.close(code);
      },
      onAbort: (what) => {
        exit(1, true, `aborted: ${what}`);
      },
    };
    globalThis.Module = Module;
    platform.loadGlue(msg.url);
    post({ type: FromHost.STARTED });
  } catch (err) {
    exit(1, true, `cannot start ${msg.url}: ${err && err.message ? err.message : err}`);
    platform.close(1);
  }
}
