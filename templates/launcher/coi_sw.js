// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The service worker of a site `colcon-wasm export` wrote
// (colcon_wasm/server/export.py). It has two jobs:
//
// - Isolation. The nodes share memory (SharedArrayBuffer), which a browser
//   allows only on a cross-origin isolated page; a static host (GitHub Pages,
//   a plain http.server) sends no COOP/COEP headers, so this worker adds them
//   to every response of the site. The page registers it and reloads once
//   under it (app.mjs).
// - Bytes. The site's manifest (files.json, export_files.py) gives each
//   file's hash and its precompressed forms. A file with a `.gz` is fetched
//   as that and inflated here (a host such as http.server compresses
//   nothing), and every listed file is kept in this worker's cache under its
//   hash: a second visit fetches only the page and the manifest, on any host,
//   a new export replaces what changed, and the same bytes at two paths
//   are fetched once.

const ISOLATION = {
  'Cross-Origin-Opener-Policy': 'same-origin',
  'Cross-Origin-Embedder-Policy': 'require-corp',
  'Cross-Origin-Resource-Policy': 'same-origin',
};
const scope = new URL(self.registration.scope);
const CACHE = `colcon-wasm-site:${scope.pathname}`; // one per site of an origin
const TYPES = {
  wasm: 'application/wasm', js: 'text/javascript', mjs: 'text/javascript', json: 'application/json',
  html: 'text/html; charset=utf-8', css: 'text/css', svg: 'image/svg+xml', png: 'image/png',
  jpg: 'image/jpeg', jpeg: 'image/jpeg',
};
let manifest = null;

/** Read the site's manifest anew (after an export, a navigation sees the new one). */
function loadManifest() {
  manifest = fetch(new URL('files.json', scope), { cache: 'no-store' })
    .then((r) => (r.ok ? r.json() : { files: {} }))
    .then((m) => { pruneCache(m.files || {}); return m.files || {}; })
    .catch(() => ({}));
  return manifest;
}

/** Drop what the cache holds of files that changed or went (the cache stays the site's size). */
async function pruneCache(files) {
  const hashes = new Set(Object.values(files).map((entry) => entry.hash));
  const cache = await caches.open(CACHE);
  for (const request of await cache.keys()) {
    const hash = new URL(request.url).pathname.split('/').slice(-2)[0];
    if (!hashes.has(hash)) await cache.delete(request);
  }
}

/** The path of a URL in the site (as files.json names it), or null outside it. */
function sitePath(url) {
  if (url.origin !== scope.origin || !url.pathname.startsWith(scope.pathname)) return null;
  try {
    return decodeURIComponent(url.pathname.slice(scope.pathname.length));
  } catch {
    return null;
  }
}

function isolated(response, type) {
  if (response.status === 0) return response; // opaque: nothing to add
  const headers = new Headers(response.headers);
  for (const [name, value] of Object.entries(ISOLATION)) headers.set(name, value);
  if (type) {
    headers.set('Content-Type', type);
    headers.delete('Content-Encoding');
    headers.delete('Content-Length');
  }
  return new Response(response.body, { status: response.status, statusText: response.statusText, headers });
}

/**
 * A listed file: from the cache under its hash, else fetched (its .gz when
 * it has one) and kept. `fileUrl` is the file's own URL (a directory's
 * `index.html`, which a static host sends for `dir/`).
 */
async function listedFile(request, fileUrl, path, entry) {
  const cache = await caches.open(CACHE);
  const type = TYPES[path.split('.').pop().toLowerCase()] || 'application/octet-stream';
  // keyed by content: the same bytes at two paths (ws/ and the fs/ view) are fetched once
  const key = new URL(`.colcon-wasm-cache/${entry.hash}/${encodeURIComponent(type)}`, scope);
  const cached = await cache.match(key.href);
  if (cached) return cached;
  let body = null;
  if (entry.gz) {
    const packed = await fetch(`${fileUrl}.gz`, { credentials: 'same-origin' }).catch(() => null);
    if (packed && packed.ok) {
      // a host that sends the .gz with Content-Encoding: gzip had it inflated by fetch already
      body = /gzip/.test(packed.headers.get('Content-Encoding') || '')
        ? packed.body : packed.body.pipeThrough(new DecompressionStream('gzip'));
    }
  }
  if (!body) {
    const plain = await fetch(request);
    if (!plain.ok) return isolated(plain);
    body = plain.body;
  }
  const bytes = await new Response(body).arrayBuffer();
  const response = isolated(new Response(bytes, { status: 200 }), type);
  await cache.put(key.href, response.clone()).catch(() => {}); // a full quota: served, not kept
  return response;
}

async function answer(event) {
  const request = event.request;
  const url = new URL(request.url);
  const path = sitePath(url);
  if (request.mode === 'navigate') loadManifest();
  if (request.method !== 'GET' || path === null || url.search || request.mode === 'navigate'
      || request.headers.has('Range')) {
    return isolated(await fetch(request));
  }
  const files = await (manifest || loadManifest());
  const directory = path === '' || path.endsWith('/');
  const listed = directory ? `${path}index.html` : path;
  const entry = files[listed];
  if (!entry) return isolated(await fetch(request));
  return listedFile(request, `${url.origin}${url.pathname}${directory ? 'index.html' : ''}`, listed, entry);
}

self.addEventListener('install', () => self.skipWaiting());
self.addEventListener('activate', (event) => event.waitUntil(self.clients.claim()));

self.addEventListener('fetch', (event) => {
  const request = event.request;
  // a request the browser may only answer from its cache, of another origin: leave it
  if (request.cache === 'only-if-cached' && request.mode !== 'same-origin') return;
  event.respondWith(answer(event));
});
