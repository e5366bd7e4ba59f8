// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Checks of the options of Runtime.spawn() that describe the executable's
 * file system: `files` (written before main()) and `mounts` (read-only
 * views, view_fs.mjs).
 *
 * @module spawn_options
 */

import { BusError, Code } from './bus.mjs';

/**
 * Check the `files` option of spawn(): absolute paths to text or bytes.
 * @param {Object<string, string|Uint8Array>|undefined} files
 * @param {string} name the executable, for messages
 * @returns {Object<string, string|Uint8Array>}
 */
export function checkedFiles(files, name) {
  const out = {};
  for (const [path, content] of Object.entries(files || {})) {
    if (!path.startsWith('/') || path.split('/').includes('..')) {
      throw new BusError(Code.INVALID_ARGUMENT,
        `spawn '${name}': file path '${path}' must be absolute and must not contain '..'`);
    }
    if (typeof content !== 'string' && !(content instanceof Uint8Array)) {
      throw new BusError(Code.INVALID_ARGUMENT,
        `spawn '${name}': content of file '${path}' must be a string or a Uint8Array`);
    }
    out[path] = content;
  }
  return out;
}

/**
 * Check the `mounts` option of spawn(): read-only views at absolute,
 * normalized paths (not `/`), none holding one of the spawn's `files`. A
 * relative `url` is resolved against the page.
 * @param {Array<{path: string, url?: string}>|undefined} mounts
 * @param {Object<string, *>} files the checked `files` option
 * @param {string} name the executable, for messages
 * @returns {Array<{path: string, url?: string}>}
 */
export function checkedMounts(mounts, files, name) {
  if (mounts === undefined || mounts === null) return [];
  if (!Array.isArray(mounts)) {
    throw new BusError(Code.INVALID_ARGUMENT, `spawn '${name}': mounts must be an array of {path, url?}`);
  }
  return mounts.map((m) => {
    const path = m && m.path;
    if (typeof path !== 'string' || !path.startsWith('/') || path === '/' || path.endsWith('/')
        || path.split('/').slice(1).some((s) => s === '' || s === '.' || s === '..')) {
      throw new BusError(Code.INVALID_ARGUMENT,
        `spawn '${name}': mount path ${JSON.stringify(path)} must be an absolute, normalized path other than '/'`);
    }
    const file = Object.keys(files).find((f) => f.startsWith(`${path}/`));
    if (file) {
      throw new BusError(Code.INVALID_ARGUMENT,
        `spawn '${name}': file '${file}' lies in the read-only view at '${path}': write it elsewhere`);
    }
    if (m.url === undefined || m.url === null) return { path };
    const base = globalThis.location ? globalThis.location.href : undefined;
    const mount = { path, url: new URL(String(m.url), base).href };
    // what a static export left out ({prefixes: {path: package}, hint}): a lookup there says so
    if (m.leftOut && typeof m.leftOut === 'object') {
      mount.leftOut = { prefixes: { ...m.leftOut.prefixes }, hint: String(m.leftOut.hint) };
    }
    return mount;
  });
}
