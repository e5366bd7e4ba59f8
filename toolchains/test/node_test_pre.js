// colcon-wasm: --pre-js of the test executables of a --wasm-tests build
// (colcon_wasm/link/test_link.py). They run in Node.js only, like a native
// test: linked with -sNODERAWFS=1, on the host file system.
//
// Node.js >= 18 has a global fetch(), and Emscripten 3.1.6's glue then tries
// fetch() on the .wasm file path ("Failed to parse URL"): hide it, so that
// the glue reads the file with fs (templates/glue/00-node-fetch.j2 does the
// same for installed executables).
var fetch = (typeof process == 'object' && typeof process.versions == 'object' &&
             typeof process.versions.node == 'string') ? undefined : globalThis.fetch;
// The test's environment is the process' (ament_add_gtest's ENV, APPEND_ENV,
// the variables colcon test sets), as getenv() sees it natively.
Module['preRun'] = [].concat(Module['preRun'] || [], [function colconWasmTestEnvironment() {
  if (typeof ENV == 'undefined' || typeof process != 'object' || !process.env) return;
  for (var key in process.env) {
    ENV[key] = String(process.env[key]);
  }
}]);
