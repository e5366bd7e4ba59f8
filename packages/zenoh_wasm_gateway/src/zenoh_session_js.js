// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The imports of zenoh_session.c (an Emscripten JS library). Each one hands
// over to `Module.zenohHost`, the object wasm_js/src/bridges/zenoh/session.mjs
// gives when it instantiates the module: the socket (link.mjs) and the
// handlers of samples, queries and replies. Bytes are copied out of the
// wasm memory before the handler sees them.

mergeInto(LibraryManager.library, {
  zg_js_connect__deps: ['$Asyncify'],
  zg_js_connect: function (address, timeoutMs) {
    return Asyncify.handleSleep(function (wakeUp) {
      Module.zenohHost.connect(UTF8ToString(address), timeoutMs).then(wakeUp, function () { wakeUp(-1); });
    });
  },
  zg_js_wait_readable__deps: ['$Asyncify'],
  zg_js_wait_readable: function (socket, timeoutMs) {
    return Asyncify.handleSleep(function (wakeUp) {
      Module.zenohHost.waitReadable(socket, timeoutMs).then(function (ok) { wakeUp(ok ? 1 : 0); });
    });
  },
  zg_js_read: function (socket, ptr, len) {
    return Module.zenohHost.read(socket, HEAPU8.subarray(ptr, ptr + len));
  },
  zg_js_send: function (socket, ptr, len) {
    return Module.zenohHost.send(socket, HEAPU8.slice(ptr, ptr + len));
  },
  zg_js_close: function (socket) {
    Module.zenohHost.close(socket);
  },
  zg_js_sample__deps: [],
  zg_js_sample: function (id, kind, key, keyLen, payload, len, attachment, attachmentLen) {
    Module.zenohHost.sample(id, kind === 1 ? 'delete' : 'put', UTF8ToString(key, keyLen),
      HEAPU8.slice(payload, payload + len), HEAPU8.slice(attachment, attachment + attachmentLen));
  },
  zg_js_query__deps: [],
  zg_js_query: function (id, query, key, keyLen, payload, len, attachment, attachmentLen) {
    Module.zenohHost.query(id, query, UTF8ToString(key, keyLen),
      HEAPU8.slice(payload, payload + len), HEAPU8.slice(attachment, attachment + attachmentLen));
  },
  zg_js_reply__deps: [],
  zg_js_reply: function (id, ok, key, keyLen, payload, len, attachment, attachmentLen) {
    Module.zenohHost.reply(id, ok === 1, UTF8ToString(key, keyLen),
      HEAPU8.slice(payload, payload + len), HEAPU8.slice(attachment, attachment + attachmentLen));
  },
  zg_js_reply_done: function (id) {
    Module.zenohHost.replyDone(id);
  },
  zg_js_matching: function (id, matching) {
    Module.zenohHost.matching(id, matching === 1);
  },
});
