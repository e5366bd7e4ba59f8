// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The service worker of a site `colcon-wasm export` wrote
// (colcon_wasm/server/export.py). The nodes share memory (SharedArrayBuffer),
// which a browser allows only on a cross-origin isolated page; a static host
// (GitHub Pages, a plain http.server) sends no COOP/COEP headers, so this
// worker adds them to every response of the site. The page registers it and
// reloads once under it (app.mjs).

const ISOLATION = {
  'Cross-Origin-Opener-Policy': 'same-origin',
  'Cross-Origin-Embedder-Policy': 'require-corp',
  'Cross-Origin-Resource-Policy': 'same-origin',
};

self.addEventListener('install', () => self.skipWaiting());
self.addEventListener('activate', (event) => event.waitUntil(self.clients.claim()));

self.addEventListener('fetch', (event) => {
  const request = event.request;
  // a request the browser may only answer from its cache, of another origin: leave it
  if (request.cache === 'only-if-cached' && request.mode !== 'same-origin') return;
  event.respondWith(fetch(request).then((response) => {
    if (response.status === 0) return response; // opaque: nothing to add
    const headers = new Headers(response.headers);
    for (const [name, value] of Object.entries(ISOLATION)) headers.set(name, value);
    return new Response(response.body, { status: response.status, statusText: response.statusText, headers });
  }));
});
