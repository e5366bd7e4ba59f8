// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.
//
// A pre-started Emscripten pthread worker for browsers (a classic Web Worker,
// see pthread_pool.mjs): booted and with the bus client imported before the
// program starts; told Emscripten's worker script, it imports it, and that
// script's onmessage takes over. Its threads' ends go to the main thread
// through shared memory (pthread_exits.mjs).
'use strict';

importScripts('import_script.js');

// Taken before the import failed: Emscripten's script owns the messages
// now, and an error message would confuse it.
var taken = false;

self.onmessage = function(e) {
  var d = e.data;
  if (d && typeof d.colconWasmPreload === 'string') {
    import(d.colconWasmPreload).then(function() {
      Atomics.store(d.state, 0, 1);
      Atomics.notify(d.state, 0);
    }, function(err) {
      Atomics.store(d.state, 0, 2);
      Atomics.notify(d.state, 0);
      if (!taken) self.postMessage({colconWasmError: String(err && err.message || err)});
    });
    return;
  }
  if (d && typeof d.colconWasmWorkerScript === 'string') {
    taken = true;
    self.onmessage = null;
    var scripts = d.scripts || {};
    if (Object.keys(scripts).length) {
      // Emscripten's worker script loads the glue with importScripts(): run
      // both from the Runtime's prefetched text (import_script.js).
      var load = self.importScripts;
      self.importScripts = function() {
        for (var i = 0; i < arguments.length; i++) {
          var url = String(arguments[i]);
          colconWasmImportScript(url, scripts[new URL(url, self.location.href).href], load);
        }
      };
    }
    importScripts(d.colconWasmWorkerScript);
    if (d.exitRing) sendCleanupsThroughRing(self, d.exitRing);
  }
};

// pthread_exits.mjs' pushExit and sendCleanupsThroughRing (a classic script
// cannot import a module): change both.
function pushExit(ring, thread) {
  var slots = ring.length - 2;
  for (;;) {
    var written = Atomics.load(ring, 0);
    if (written - Atomics.load(ring, 1) >= slots) return false;
    if (Atomics.compareExchange(ring, 0, written, written + 1) === written) {
      Atomics.store(ring, 2 + (written % slots), thread);
      return true;
    }
  }
}

function sendCleanupsThroughRing(scope, ring) {
  var post = scope.postMessage;
  scope.postMessage = function(msg) {
    if (msg && msg.cmd === 'cleanupThread' && msg.thread && pushExit(ring, msg.thread)) return undefined;
    return post.apply(this, arguments);
  };
}
