// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.
//
// Loaded with importScripts() by the browser's classic workers (program_worker_web.js,
// pthread_stub_web.js): run a script the Runtime prefetched as text, or load
// it by URL.
'use strict';

// Whether this worker may eval(): a Content-Security-Policy without
// 'unsafe-eval' refuses it before anything ran.
var colconWasmEvalAllowed = (function() {
  try {
    (0, eval)('0');
    return true;
  } catch (e) {
    return false;
  }
})();

/**
 * Run a classic script in global scope, from `text` when there is one (an
 * eval instead of a synchronous network load: ~10 ms less for a glue in
 * Chromium), else by `load(url)` (importScripts).
 * @param {string} url the script's URL
 * @param {string|undefined} text its source, prefetched (ends with a
 *   sourceURL comment, so stack traces name the file)
 * @param {function(string): void} load importScripts, or the worker's saved one
 * @returns {boolean} true when the text ran
 */
function colconWasmImportScript(url, text, load) {
  if (typeof text === 'string' && colconWasmEvalAllowed) {
    // A classic script's top-level `var`s are globals, also in a strict
    // script (Emscripten's worker script starts with "use strict"), but a
    // strict eval keeps them to itself: the leading empty statement makes
    // the directive an ordinary expression, so they become globals here too.
    (0, eval)(';' + text);
    return true;
  }
  load.call(self, url);
  return false;
}
