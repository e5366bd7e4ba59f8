// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.
//
// Browser program worker (a classic Web Worker, so that it can importScripts()
// an Emscripten glue). The Runtime may first post PRELOAD (import the program worker
// module, boot pthread workers ahead, answer READY: a warm worker), then posts
// one START; see program_worker.mjs.
'use strict';

importScripts('import_script.js');

var workerModule = null;

function load(url) {
  if (!workerModule) workerModule = import(url);
  return workerModule;
}

// A pre-started pthread worker (see pthread_pool.mjs).
function pthreadStub(url) {
  var worker = new Worker(url, {name: 'wasm_js pthread'});
  return {
    worker: worker,
    listen: function(fn) {
      worker.onmessage = function(e) { fn(e.data); };
      worker.onerror = function(e) {
        e.preventDefault();
        fn({colconWasmError: e.message || 'worker script error'});
      };
      // Emscripten sets its own handlers when it takes the worker.
      return function() {
        worker.onmessage = null;
        worker.onerror = null;
      };
    },
  };
}

function fail(reason) {
  self.postMessage({type: 'exit', code: 1, crashed: true, reason: reason});
  self.close();
}

self.onmessage = function(e) {
  var msg = e.data;
  if (!msg) return;
  if (msg.type === 'preload') {
    load(msg.workerModuleUrl).then(function(common) {
      return common.prestartPthreadWorkers(msg.pthreadWorkers, msg.busModuleUrl, function() {
        return pthreadStub(new URL('pthread_stub_web.js', msg.workerModuleUrl).href);
      });
    }).then(function() {
      self.postMessage({type: 'ready'});
    }, function(err) {
      fail('cannot load the wasm_js program worker (' + msg.workerModuleUrl + '): ' + err);
    });
    return;
  }
  if (msg.type !== 'start') return;
  self.onmessage = null;
  load(msg.workerModuleUrl).then(function(common) {
    return common.startProcess(msg, {
      loadGlue: function(url, text) { return colconWasmImportScript(url, text, importScripts); },
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
    fail('cannot load the wasm_js program worker (' + msg.workerModuleUrl + '): ' + err);
  });
};
