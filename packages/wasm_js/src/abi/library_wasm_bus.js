// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.
//
// Emscripten JS library (--js-library) that connects wasm_cpp to the wasm_js
// bus. Every executable linking wasm_cpp::wasm_cpp gets it through the
// target's link options.
//
// Each thread of the executable has its own BusClient (share/wasm_js/src/bus_client.mjs):
// - the main runtime thread uses the one the wasm_js program worker puts in
//   Module.wasmBus = {client, moduleUrl}; when the executable runs alone
//   (`node exe.js`), it imports bus_client.mjs and creates a private bus;
// - each pthread worker gets {cmd: 'wasmBus', bus, pid, moduleUrl} right
//   after Emscripten's 'load' message, imports bus_client.mjs and attaches;
//   a run dependency holds the worker's 'loaded' reply until it has.
// So no glue post-processing is needed for the bus to reach pthreads.
//
// Functions return wasm_cpp::Code values (0 = ok); the message of the last
// failure of the calling thread is read with wasm_bus_last_error().
//
// Over 500 lines on purpose: Emscripten merges one library object per
// --js-library file into every executable (no imports); each C function of
// bus_abi.hpp is a short adapter to BusClient (src/bus_client.mjs).

var LibraryWasmBus = {
  // addRunDependency / removeRunDependency come from the preamble (always present).
  $WasmBus__postset: 'WasmBus.init();',
#if USE_PTHREADS
  $WasmBus__deps: ['$ENV', 'emscripten_main_thread_process_queued_calls'],
#else
  $WasmBus__deps: ['$ENV'],
#endif
  $WasmBus: {
    client: null,
    moduleUrl: null,
    error: '',
    pending: [],
    settled: false,
    // Unused since the wait loop services the main thread's call queue itself
    // (BusClient.service); kept false so waits never return -1.
    returnAfterWake: false,

    // Word offsets of wasm_bus_take_info and of the event status words, as in
    // src/abi/bus_abi.mjs and packages/wasm_cpp (tests/test_bus_abi.py checks
    // that the three agree).
    TAKE_INFO: {
      SOURCE_MS_F64: 0, RECEIVED_MS_F64: 2, PUB_SEQ_LO: 4, PUB_SEQ_HI: 5, RECV_SEQ_LO: 6,
      RECV_SEQ_HI: 7, GID: 8, REQ_SEQ_LO: 12, REQ_SEQ_HI: 13, SAME_PROCESS: 14, LENGTH: 15,
      DATA: 16, CAPACITY: 17, WORDS: 18,
    },
    EVENT_STATUS: {
      CHANGED: 0, TOTAL: 1, CHANGE: 2, ALIVE: 3, NOT_ALIVE: 4, ALIVE_CHANGE: 5,
      NOT_ALIVE_CHANGE: 6, POLICY: 7, WORDS: 8,
    },

    // Views of the wasm heap, renewed when it grows. Each HEAP* access in a
    // pthread build checks wasmMemory.buffer (~60 ns); hot paths use these.
    hu8: null,
    hi32: null,
    hf64: null,
    heap: function() {
      var u8 = HEAPU8;
      if (WasmBus.hu8 !== u8) {
        WasmBus.hu8 = u8;
        WasmBus.hi32 = new Int32Array(u8.buffer);
        WasmBus.hf64 = new Float64Array(u8.buffer);
      }
    },
    // The views, renewed only when [ptr, end) lies beyond them (the heap grew;
    // in a non-pthread build growth detaches the old buffer: length 0).
    heapFor: function(end) {
      if (!WasmBus.hu8 || end > WasmBus.hu8.length) WasmBus.heap();
    },
    // 1: messages are copied between the heap and the bus with memory.copy
    // (BusClient.useHeapMemory: the bus is a WebAssembly.Memory and the engine
    // has multi-memory), 2: through the heap views; 0: not decided yet (the
    // heap of a non-pthread build exists only once the module is instantiated).
    copyMode: 0,
    // True when publish and take pass no view (null) and use memory.copy.
    memoryCopy: function() {
      if (WasmBus.copyMode === 0) {
        WasmBus.copyMode = (typeof wasmMemory == 'object' && wasmMemory &&
                            WasmBus.client.useHeapMemory(wasmMemory)) ? 1 : 2;
      }
      return WasmBus.copyMode === 1;
    },

    // wasmTable.get() of the allocator functions, cached.
    fnIndex: [0, 0],
    fn: [null, null],
    tableFn: function(slot, index) {
      if (WasmBus.fnIndex[slot] !== index) {
        WasmBus.fnIndex[slot] = index;
        WasmBus.fn[slot] = wasmTable.get(index);
      }
      return WasmBus.fn[slot];
    },

    fail: function(e) {
      WasmBus.error = (e && e.message) ? e.message : String(e);
      return (e && typeof e.code == 'number' && e.code > 0) ? e.code : 1;
    },

    noBus: function() {
      WasmBus.error = WasmBus.error ||
        'wasm_cpp: no bus is attached to this executable: run it with the wasm_js runtime ' +
        '(Runtime.spawn, or `node <wasm_js>/src/cli.mjs exe.js`), or make share/wasm_js findable ' +
        '(WASM_JS_DIR or AMENT_PREFIX_PATH) when running it alone';
      return 1;
    },

    // Install the BusClient of the main runtime thread.
    setClient: function(client, moduleUrl) {
      WasmBus.client = client;
      WasmBus.moduleUrl = moduleUrl;
#if USE_PTHREADS
      // Waits on this thread run the calls pthreads proxy to it (printf, ...).
      client.service = function() { _emscripten_main_thread_process_queued_calls(); };
#endif
      WasmBus.ready();
    },

    // Run fn once the bus is known (attached, or known to be missing).
    whenReady: function(fn) {
      if (WasmBus.settled) fn(); else WasmBus.pending.push(fn);
    },

    ready: function() {
      WasmBus.settled = true;
      var p = WasmBus.pending;
      WasmBus.pending = [];
      p.forEach(function(fn) { fn(); });
    },

#if ENVIRONMENT_MAY_BE_NODE
    // Where is bus_client.mjs when the executable runs alone under Node.js?
    locateModule: function() {
      var path = require('path');
      var fs = require('fs');
      var dirs = [];
      if (process.env['WASM_JS_DIR']) dirs.push(process.env['WASM_JS_DIR']);
      ['AMENT_PREFIX_PATH', 'CMAKE_PREFIX_PATH', 'COLCON_PREFIX_PATH'].forEach(function(v) {
        (process.env[v] || '').split(path.delimiter).forEach(function(p) {
          if (p) dirs.push(path.join(p, 'share', 'wasm_js'), path.join(p, 'wasm_js', 'share', 'wasm_js'));
        });
      });
      var here = typeof __dirname != 'undefined' ? __dirname : process.cwd();
      for (var up = 1; up <= 4; up++) {
        var base = path.resolve(here, new Array(up + 1).join('../'));
        dirs.push(path.join(base, 'share', 'wasm_js'), path.join(base, 'wasm_js', 'share', 'wasm_js'));
      }
      for (var i = 0; i < dirs.length; i++) {
        var f = path.join(dirs[i], 'src', 'bus_client.mjs');
        if (fs.existsSync(f)) return require('url').pathToFileURL(f).href;
      }
      return null;
    },
#endif

    init: function() {
#if USE_PTHREADS
      if (ENVIRONMENT_IS_PTHREAD) {
        // Hold 'loaded' until the main thread sent us the bus and we attached.
        addRunDependency('wasm-bus');
        // And hold what comes before then: the program worker may post a thread's
        // 'run' right after 'load' (program_worker.mjs), and attaching is async.
        // They are handled in order, each in a task of its own (as a message
        // would be, so that what a thread throws reaches the Worker's error
        // handler), until none is left.
        var held = [];
        var onmessage = self.onmessage;
        var replay = function() {
          var e = held.shift();
          if (held.length) setTimeout(replay, 0); else held = null;
          onmessage(e);
        };
        var attached = function() {
          removeRunDependency('wasm-bus');
          if (held.length) setTimeout(replay, 0); else held = null;
        };
        self.onmessage = function(e) {
          var d = e && e.data;
          if (d && d['cmd'] === 'wasmBus') {
            if (!d['bus']) {
              // The main thread has no bus: neither do we (contexts fail clearly).
              WasmBus.error = d['error'];
              attached();
              return;
            }
            WasmBus.moduleUrl = d['moduleUrl'];
            import(d['moduleUrl']).then(function(m) {
              WasmBus.client = m.BusClient.attach(d['bus'], d['pid']);
            }).catch(function(err) {
              WasmBus.error = 'wasm_cpp: a thread could not attach to the bus (' + d['moduleUrl'] + '): ' + err;
            }).then(attached);
            return;
          }
          if (held) {
            held.push(e);
            return;
          }
          return onmessage(e);
        };
        return;
      }
      // Give every pthread worker the bus right after Emscripten loads it.
      var load = PThread.loadWasmModuleToWorker;
      PThread.loadWasmModuleToWorker = function(worker) {
        var r = load.apply(this, arguments);
        WasmBus.whenReady(function() {
          var c = WasmBus.client;
          worker.postMessage({
            'cmd': 'wasmBus', 'bus': c ? c.bus.handle : null, 'pid': c ? c.pid : 0,
            'moduleUrl': WasmBus.moduleUrl, 'error': WasmBus.error,
          });
        });
        return r;
      };
#endif
      // The environment the program worker gives (Module.env; colcon-wasm's glue start-up
      // fragment does the same for executables that do not link wasm_cpp).
      if (Module['env'] && typeof ENV == 'object') {
        for (var k in Module['env']) ENV[k] = String(Module['env'][k]);
      }
      var given = Module['wasmBus'];
      if (given && given['client']) {
        WasmBus.setClient(given['client'], given['moduleUrl']);
        return;
      }
#if ENVIRONMENT_MAY_BE_NODE
      if (ENVIRONMENT_IS_NODE) {
        var url = WasmBus.locateModule();
        if (url) {
          addRunDependency('wasm-bus');
          import(url).then(function(m) {
            WasmBus.setClient(m.BusClient.createPrivate(), url);
          }).catch(function(err) {
            WasmBus.error = 'wasm_cpp: cannot create a private bus from ' + url + ': ' + err;
            WasmBus.ready();
          }).then(function() {
            removeRunDependency('wasm-bus');
          });
          return;
        }
      }
#endif
      // No runtime gave a bus and none can be made: contexts fail with this message.
      WasmBus.noBus();
      WasmBus.ready();
    },
  },

  wasm_bus_attached__deps: ['$WasmBus'],
  wasm_bus_attached: function() {
    return WasmBus.client ? 1 : 0;
  },

  wasm_bus_last_error__deps: ['$WasmBus'],
  wasm_bus_last_error: function(buf, cap) {
    var msg = WasmBus.error || '';
    if (buf && cap > 0) stringToUTF8(msg, buf, cap);
    return lengthBytesUTF8(msg);
  },

  wasm_bus_process_id__deps: ['$WasmBus'],
  wasm_bus_process_id: function() {
    return WasmBus.client ? WasmBus.client.pid : 0;
  },

  wasm_bus_max_message__deps: ['$WasmBus'],
  wasm_bus_max_message: function() {
    return WasmBus.client ? WasmBus.client.maxMessageBytes : 0;
  },

  wasm_bus_context_create__deps: ['$WasmBus'],
  wasm_bus_context_create: function() {
    if (!WasmBus.client) return -WasmBus.noBus();
    return WasmBus.client.createContext();
  },

  // out: [index, gid0, gid1, gid2, gid3, name_taken]
  wasm_bus_node_create__deps: ['$WasmBus'],
  wasm_bus_node_create: function(domain, context, name, ns, enclave, out) {
    if (!WasmBus.client) return WasmBus.noBus();
    try {
      var r = WasmBus.client.createNode({
        domain: domain, context: context, name: UTF8ToString(name), namespace: UTF8ToString(ns),
        enclave: UTF8ToString(enclave),
      });
      HEAP32[out >> 2] = r.index;
      HEAP32.set(r.gid, (out >> 2) + 1);
      HEAP32[(out >> 2) + 5] = r.nameTaken ? 1 : 0;
      return 0;
    } catch (e) {
      return WasmBus.fail(e);
    }
  },

  wasm_bus_node_destroy__deps: ['$WasmBus'],
  wasm_bus_node_destroy: function(node) {
    if (!WasmBus.client) return WasmBus.noBus();
    try {
      WasmBus.client.destroyNode(node);
      return 0;
    } catch (e) {
      return WasmBus.fail(e);
    }
  },

  // qos: 12 words (wasm_bus_qos), resolved in place; out: [index, gid0..gid3]
  wasm_bus_endpoint_create__deps: ['$WasmBus'],
  wasm_bus_endpoint_create: function(kind, node, name, type, qos, flags, keepAllDepth, out) {
    if (!WasmBus.client) return WasmBus.noBus();
    try {
      var r = WasmBus.client.createEndpoint({
        kind: kind, node: node, name: UTF8ToString(name), type: UTF8ToString(type),
        qos: HEAP32.slice(qos >> 2, (qos >> 2) + 12), ignoreLocal: (flags & 1) != 0,
        keepAllDepth: keepAllDepth,
      });
      HEAP32.set(r.qos, qos >> 2);
      HEAP32[out >> 2] = r.index;
      HEAP32.set(r.gid, (out >> 2) + 1);
      return 0;
    } catch (e) {
      return WasmBus.fail(e);
    }
  },

  wasm_bus_endpoint_destroy__deps: ['$WasmBus'],
  wasm_bus_endpoint_destroy: function(ep) {
    if (!WasmBus.client) return WasmBus.noBus();
    try {
      WasmBus.client.destroyEndpoint(ep);
      return 0;
    } catch (e) {
      return WasmBus.fail(e);
    }
  },

  // seq: [lo, hi] of the message's sequence number
  wasm_bus_publish__deps: ['$WasmBus'],
  wasm_bus_publish: function(ep, data, len, timeoutMs, seq) {
    try {
      WasmBus.heapFor(Math.max(data + len, seq + 8));
      var s = WasmBus.client.publishFrom(ep, WasmBus.memoryCopy() ? null : WasmBus.hu8, data, len, timeoutMs);
      if (seq) {
        WasmBus.hi32[seq >> 2] = s % 4294967296;
        WasmBus.hi32[(seq >> 2) + 1] = Math.floor(s / 4294967296);
      }
      return 0;
    } catch (e) {
      return WasmBus.fail(e);
    }
  },

  // gid: 4 words of the request id's client gid; returns 0 also when the client is gone.
  wasm_bus_send_response__deps: ['$WasmBus'],
  wasm_bus_send_response: function(ep, gid, seqLo, seqHi, data, len, timeoutMs) {
    try {
      WasmBus.client.sendResponse(ep, HEAP32.subarray(gid >> 2, (gid >> 2) + 4), seqLo, seqHi,
                                  HEAPU8.subarray(data, data + len), timeoutMs);
      return 0;
    } catch (e) {
      return WasmBus.fail(e);
    }
  },

  // Returns 1 when taken, 0 when nothing is there, -code on failure.
  // info (wasm_bus_take_info): f64 source ms, f64 received ms, u32 pub seq lo/hi,
  // u32 reception seq lo/hi, i32 gid[4], u32 request seq lo/hi, i32 same process,
  // i32 length, i32 data pointer, i32 capacity. On entry, data and capacity name
  // the caller's reusable buffer (data 0: none): a message that fits is copied
  // there without calling the allocator.
  wasm_bus_take__deps: ['$WasmBus'],
  wasm_bus_take: function(ep, mode, allocFn, deallocFn, state, info) {
    try {
      var c = WasmBus.client;
      var T = WasmBus.TAKE_INFO;
      var end = info + T.WORDS * 4;
      WasmBus.heapFor(end);
      // The caller's reusable buffer (info.data, info.capacity), if any.
      var buffer = WasmBus.hi32[(info >> 2) + T.DATA];
      var capacity = buffer ? WasmBus.hi32[(info >> 2) + T.CAPACITY] : -1;
      for (;;) {
        var len = c.takeBegin(ep, mode);
        if (len < 0) return 0;
        var ptr = buffer;
        if (len > capacity) {
          // The allocator may move or free the caller's buffer (realloc): from
          // now on this call uses only what the allocator returns.
          buffer = 0;
          capacity = -1;
          ptr = WasmBus.tableFn(0, allocFn)(len > 0 ? len : 1, state);
          if (!ptr) {
            WasmBus.error = 'take on \'' + c.endpointName(ep) + '\' failed: the allocator returned null for ' + len + ' bytes';
            return -10;
          }
        }
        WasmBus.heapFor(Math.max(ptr + len, end)); // the allocator may have grown the heap
        if (c.takeCopy(WasmBus.memoryCopy() ? null : WasmBus.hu8, ptr)) {
          var i = c.info;
          var f64 = WasmBus.hf64;
          var w = WasmBus.hi32;
          var o = info >> 2;
          f64[(o + T.SOURCE_MS_F64) >> 1] = i.sourceTime;
          f64[(o + T.RECEIVED_MS_F64) >> 1] = i.receivedTime;
          w[o + T.PUB_SEQ_LO] = i.pubSeqLo;
          w[o + T.PUB_SEQ_HI] = i.pubSeqHi;
          w[o + T.RECV_SEQ_LO] = i.recvSeqLo;
          w[o + T.RECV_SEQ_HI] = i.recvSeqHi;
          w[o + T.GID] = i.gid[0];
          w[o + T.GID + 1] = i.gid[1];
          w[o + T.GID + 2] = i.gid[2];
          w[o + T.GID + 3] = i.gid[3];
          w[o + T.REQ_SEQ_LO] = i.reqLo;
          w[o + T.REQ_SEQ_HI] = i.reqHi;
          w[o + T.SAME_PROCESS] = i.sameProcess ? 1 : 0;
          w[o + T.LENGTH] = len;
          w[o + T.DATA] = ptr;
          return 1;
        }
        if (ptr !== buffer) WasmBus.tableFn(1, deallocFn)(ptr, state);
      }
    } catch (e) {
      return -WasmBus.fail(e);
    }
  },

  wasm_bus_has_data__deps: ['$WasmBus'],
  wasm_bus_has_data: function(ep, mode) {
    try {
      return WasmBus.client.takeBegin(ep, mode) >= 0 ? 1 : 0;
    } catch (e) {
      WasmBus.fail(e);
      return 0;
    }
  },

  wasm_bus_matched_count__deps: ['$WasmBus'],
  wasm_bus_matched_count: function(ep) {
    try {
      return WasmBus.client.matchedCount(ep);
    } catch (e) {
      return -WasmBus.fail(e);
    }
  },

  wasm_bus_assert_liveliness__deps: ['$WasmBus'],
  wasm_bus_assert_liveliness: function(ep) {
    try {
      WasmBus.client.assertLiveliness(ep);
      return 0;
    } catch (e) {
      return WasmBus.fail(e);
    }
  },

  wasm_bus_wait_for_acked__deps: ['$WasmBus'],
  wasm_bus_wait_for_acked: function(ep, timeoutMs) {
    try {
      return WasmBus.client.waitForAllAcked(ep, timeoutMs) ? 0 : 2;
    } catch (e) {
      return WasmBus.fail(e);
    }
  },

  // items: 4 words per item (kind, handle, aux, result). Returns the number of
  // ready items, 0 on timeout, -1 when woken and the caller must call again
  // (main thread of a pthread program), or -100 - code on failure.
  wasm_bus_wait__deps: ['$WasmBus'],
  wasm_bus_wait: function(items, count, timeoutMs) {
    try {
      // Guard condition items point anywhere in the heap: check the whole view.
      WasmBus.heap();
      var heap = WasmBus.hi32;
      return WasmBus.client.wait(heap, items >> 2, count, timeoutMs, heap, WasmBus.returnAfterWake);
    } catch (e) {
      return -100 - WasmBus.fail(e);
    }
  },

  // Like wasm_bus_wait, but result = number of new arrivals (nothing is taken).
  wasm_bus_listen__deps: ['$WasmBus'],
  wasm_bus_listen: function(items, count, timeoutMs) {
    try {
      WasmBus.heap();
      return WasmBus.client.listen(WasmBus.hi32, items >> 2, count, timeoutMs, WasmBus.returnAfterWake);
    } catch (e) {
      return -100 - WasmBus.fail(e);
    }
  },

  wasm_bus_listen_forget__deps: ['$WasmBus'],
  wasm_bus_listen_forget: function(ep) {
    if (WasmBus.client) WasmBus.client.listenForget(ep);
  },

  // status: [changed, total, change, alive, not_alive, alive_change, not_alive_change, policy]
  wasm_bus_event_status__deps: ['$WasmBus'],
  wasm_bus_event_status: function(ep, type, take, status) {
    try {
      var s = WasmBus.client.eventStatus(ep, type, take != 0);
      WasmBus.heap();
      var h = WasmBus.hi32;
      var w = status >> 2;
      var S = WasmBus.EVENT_STATUS;
      h[w + S.CHANGED] = s.changed ? 1 : 0;
      h[w + S.TOTAL] = s.total;
      h[w + S.CHANGE] = s.change;
      h[w + S.ALIVE] = s.alive;
      h[w + S.NOT_ALIVE] = s.notAlive;
      h[w + S.ALIVE_CHANGE] = s.aliveChange;
      h[w + S.NOT_ALIVE_CHANGE] = s.notAliveChange;
      h[w + S.POLICY] = s.policy;
      return 0;
    } catch (e) {
      return WasmBus.fail(e);
    }
  },

  wasm_bus_ring_self__deps: ['$WasmBus'],
  wasm_bus_ring_self: function() {
    if (WasmBus.client) WasmBus.client.ringSelf();
  },

  wasm_bus_graph_version__deps: ['$WasmBus'],
  wasm_bus_graph_version: function() {
    return WasmBus.client ? WasmBus.client.graphVersion() : 0;
  },

  // Serialize the graph of one domain into a malloc'd buffer (*out, *outLen):
  // u32 node count, per node: str name, str namespace, str enclave, i32 gid[4];
  // u32 endpoint count, per endpoint: i32 kind, str name, str type, str node
  // name, str node namespace, i32 gid[4], i32 qos[12]. str = u32 length + UTF-8.
  wasm_bus_graph__deps: ['$WasmBus', 'malloc'],
  wasm_bus_graph: function(domain, out, outLen) {
    try {
      var g = WasmBus.client.graph({ domain: domain });
      var enc = new TextEncoder();
      var parts = [];
      var size = 0;
      function u32(v) { var a = new Int32Array([v]); parts.push(new Uint8Array(a.buffer)); size += 4; }
      function words(w) { var a = Int32Array.from(w); parts.push(new Uint8Array(a.buffer)); size += a.length * 4; }
      function str(s) { var b = enc.encode(s); u32(b.length); parts.push(b); size += b.length; }
      u32(g.nodes.length);
      g.nodes.forEach(function(n) { str(n.name); str(n.namespace); str(n.enclave); words(n.gid); });
      u32(g.endpoints.length);
      g.endpoints.forEach(function(e) {
        u32(e.kind); str(e.name); str(e.type); str(e.node); str(e.namespace); words(e.gid); words(e.qosWords);
      });
      var ptr = _malloc(size > 0 ? size : 1);
      if (!ptr) {
        WasmBus.error = 'graph query failed: out of memory for ' + size + ' bytes';
        return 10;
      }
      var p = ptr;
      parts.forEach(function(b) { HEAPU8.set(b, p); p += b.length; });
      HEAP32[out >> 2] = ptr;
      HEAP32[outLen >> 2] = size;
      return 0;
    } catch (e) {
      return WasmBus.fail(e);
    }
  },
};

#if USE_PTHREADS
// A pthread that proxies a call to the main thread (e.g. its printf) rings the
// process' doorbell, so a main thread sleeping in a bus wait wakes up, runs
// the call and goes back to sleep (see wasm_bus_wait's -1 result).
(function() {
  var lib = LibraryManager.library;
  var name = '_emscripten_notify_thread_queue';
  if (typeof lib[name] !== 'function') return;
  var orig = name + '_wasm_bus_orig';
  lib[orig] = lib[name];
  if (lib[name + '__deps']) lib[orig + '__deps'] = lib[name + '__deps'];
  if (lib[name + '__sig']) lib[orig + '__sig'] = lib[name + '__sig'];
  lib[name + '__deps'] = [orig, '$WasmBus'];
  LibraryWasmBus[name + '__deps'] = lib[name + '__deps'];
  LibraryWasmBus[name] = function(targetThreadId, mainThreadId) {
    var r = __emscripten_notify_thread_queue_wasm_bus_orig(targetThreadId, mainThreadId);
    if (targetThreadId == mainThreadId && WasmBus.client) WasmBus.client.ringSelf();
    return r;
  };
})();
#endif

mergeInto(LibraryManager.library, LibraryWasmBus);
