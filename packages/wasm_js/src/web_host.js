// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.
//
// Browser host worker (a classic Web Worker, so that it can importScripts()
// an Emscripten glue). The Runtime posts one START message; see host_common.mjs.
'use strict';

self.onmessage = function(e) {
  var msg = e.data;
  if (!msg || msg.type !== 'start') return;
  self.onmessage = null;
  import(msg.hostModuleUrl).then(function(host) {
    return host.startProcess(msg, {
      loadGlue: function(url) { importScripts(url); },
      locate: function(path) { return new URL(path, msg.url).href; },
      post: function(m) { self.postMessage(m); },
      close: function() { setTimeout(function() { self.close(); }, 0); },
      compile: function(url) {
        return WebAssembly.compileStreaming
          ? WebAssembly.compileStreaming(fetch(url))
          : fetch(url).then(function(r) { return r.arrayBuffer(); }).then(WebAssembly.compile);
      },
    });
  }).catch(function(err) {
    self.postMessage({type: 'exit', code: 1, crashed: true,
                      reason: 'cannot load the wasm_js host (' + msg.hostModuleUrl + '): ' + err});
    self.close();
  });
};
