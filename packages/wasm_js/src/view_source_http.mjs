// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * The browser source of read-only views (view_fs.mjs): a directory tree
 * served over HTTP, read with synchronous XMLHttpRequest (allowed in
 * workers; the program's host is one). The protocol, as `colcon-wasm serve`
 * implements it under `/fs/<n>/` (colcon_wasm/server/views.py):
 *
 *   GET <url>/<relative path>/   a directory: JSON {size, mode, mtime_ms, entries: [{name,
 *                                kind: 'dir'|'file', size, mode, mtime_ms}]}
 *   GET <url>/<relative path>/?walk=<k>   the listings of the directories along the
 *                                path from its k-th on: JSON {listings: {<relative path>:
 *                                listing}} (the server may add others it expects next)
 *   GET <url>/<relative path>    a file's bytes
 *
 * 404 means no such file or directory. Listings are kept: each directory is
 * fetched once, and a lookup of a path through directories not listed yet
 * fetches them all in one walk ({@link ViewSource} `prefetch`, which view_fs.mjs
 * calls before each path lookup): a sync request costs ~3 ms in Chromium.
 * Files are fetched whole on their first read and kept (up to
 * {@link FILE_CACHE_BYTES}), since programs read them in small chunks.
 *
 * @module view_source_http
 */

/** File contents kept per program, least recently used dropped first. */
export const FILE_CACHE_BYTES = 32 << 20;

/** An Error with the errno name view_fs.mjs reads. */
function sourceError(code, message) {
  return Object.assign(new Error(message), { code });
}

/**
 * GET a URL synchronously.
 * @param {string} url
 * @param {'text'|'arraybuffer'} type
 * @returns {string|ArrayBuffer}
 */
function getSync(url, type) {
  const xhr = new XMLHttpRequest();
  xhr.open('GET', url, false);
  xhr.responseType = type;
  try {
    xhr.send();
  } catch (e) {
    throw sourceError('EIO', `GET ${url} failed: ${e && e.message ? e.message : e}`);
  }
  if (xhr.status === 200) return xhr.response;
  const body = type === 'text' ? String(xhr.response || '').trim() : '';
  const code = xhr.status === 404 ? 'ENOENT' : xhr.status === 403 ? 'EACCES' : 'EIO';
  throw sourceError(code, `GET ${url}: HTTP ${xhr.status}${body ? ` (${body})` : ''}`);
}

/** A listing entry of the JSON protocol as a view entry. */
function entryOf(e) {
  return { name: e.name, kind: e.kind === 'dir' ? 'dir' : 'file', size: e.size, mode: e.mode, mtimeMs: e.mtime_ms };
}

/** A listing of the JSON protocol as a source's listing (+ `byName`, for walks). */
function listingOf(listing) {
  const entries = listing.entries.map(entryOf);
  return {
    self: { name: '', kind: 'dir', size: listing.size, mode: listing.mode, mtimeMs: listing.mtime_ms },
    entries,
    byName: new Map(entries.map((e) => [e.name, e])),
  };
}

/**
 * A view source over HTTP for the view at `root`.
 * @param {string} url absolute URL the tree is served under (no trailing slash needed)
 * @param {string} root the view's absolute path in the program (`url` serves it)
 * @returns {import('./view_fs.mjs').ViewSource}
 */
export function httpViewSource(url, root, { leftOut = null, warn = () => {} } = {}) {
  const base = url.replace(/\/+$/, '');
  const cache = new Map();
  const told = new Set();
  /** A path inside a package a static export left out: say once which option includes it. */
  const tellLeftOut = (path) => {
    if (!leftOut) return;
    for (const [prefix, name] of Object.entries(leftOut.prefixes || {})) {
      if ((path === prefix || path.startsWith(`${prefix}/`)) && !told.has(name)) {
        told.add(name);
        warn(`${path}: no such file here: ${String(leftOut.hint).replaceAll('{package}', name)}`);
      }
    }
  };
  let cached = 0;
  /** absolute path -> listing; a walk brings several */
  const listings = new Map();
  const partsOf = (path) => {
    if (path !== root && !path.startsWith(`${root}/`)) {
      throw sourceError('ENOENT', `'${path}' is not inside the view at '${root}'`);
    }
    return path.slice(root.length).split('/').filter(Boolean);
  };
  const urlOf = (path) => {
    const relative = partsOf(path).map(encodeURIComponent).join('/');
    return relative ? `${base}/${relative}` : base;
  };
  const fileBytes = (path) => {
    let bytes = cache.get(path);
    if (bytes) {
      cache.delete(path); // most recently used last
    } else {
      bytes = new Uint8Array(getSync(urlOf(path), 'arraybuffer'));
      cached += bytes.length;
      for (const [old, oldBytes] of cache) {
        if (cached <= FILE_CACHE_BYTES) break;
        cache.delete(old);
        cached -= oldBytes.length;
      }
    }
    cache.set(path, bytes);
    return bytes;
  };
  return {
    list(path) {
      let listing = listings.get(path);
      if (!listing) {
        listing = listingOf(JSON.parse(getSync(`${urlOf(path)}/`, 'text')));
        listings.set(path, listing);
      }
      return listing;
    },
    prefetch(path) {
      tellLeftOut(path);
      const parts = partsOf(path);
      // the directories along the path already listed need no request
      let dir = root;
      let depth = 0;
      for (; depth <= parts.length; depth++) {
        const listing = listings.get(dir);
        if (!listing) break;
        if (depth === parts.length) return;
        const entry = listing.byName.get(parts[depth]);
        if (!entry || entry.kind !== 'dir') return; // the path ends (or fails) in what is known
        dir = `${dir}/${parts[depth]}`;
      }
      let walk;
      try {
        walk = JSON.parse(getSync(`${urlOf(path)}/?walk=${depth}`, 'text'));
      } catch (e) {
        if (e.code === 'ENOENT') return; // the path is no directory: the lookup says what is missing
        throw e;
      }
      if (!walk.listings) {
        // a static copy of the views (colcon-wasm export) has no walks: it answers with the
        // directory's own listing, and the lookup lists the rest one directory at a time
        if (walk.entries && !listings.has(path)) listings.set(path, listingOf(walk));
        return;
      }
      for (const [relative, listing] of Object.entries(walk.listings)) {
        const at = relative ? `${root}/${relative}` : root;
        if (!listings.has(at)) listings.set(at, listingOf(listing));
      }
    },
    read(path, position, length) {
      return fileBytes(path).subarray(position, position + length);
    },
  };
}
