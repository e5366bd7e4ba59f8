// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * The Node.js source of read-only views (view_fs.mjs): the real files, with
 * synchronous node:fs calls (the program's host is a worker thread, so they
 * block only that program). Symbolic links are followed; entries whose
 * target is missing are left out of listings.
 *
 * @module view_source_node
 */

import fs from 'node:fs';

/**
 * Describe a stat result as a view entry.
 * @param {string} name
 * @param {fs.Stats} stat
 * @returns {import('./view_fs.mjs').ViewEntry|null} null for what is neither a file nor a directory
 */
function entryOf(name, stat) {
  const kind = stat.isDirectory() ? 'dir' : stat.isFile() ? 'file' : null;
  if (!kind) return null;
  return { name, kind, size: stat.size, mode: stat.mode, mtimeMs: stat.mtimeMs };
}

/**
 * A view source over the host's own files.
 * @returns {import('./view_fs.mjs').ViewSource}
 */
export function fileViewSource() {
  return {
    list(path) {
      const self = entryOf('', fs.statSync(path));
      if (!self || self.kind !== 'dir') throw Object.assign(new Error(`'${path}' is not a directory`), { code: 'ENOTDIR' });
      const entries = [];
      for (const name of fs.readdirSync(path)) {
        let stat;
        try {
          stat = fs.statSync(`${path}/${name}`);
        } catch (e) {
          continue; // a dangling link, or removed meanwhile
        }
        const entry = entryOf(name, stat);
        if (entry) entries.push(entry);
      }
      return { self, entries };
    },
    read(path, position, length) {
      const fd = fs.openSync(path, 'r');
      try {
        const bytes = new Uint8Array(length);
        const n = fs.readSync(fd, bytes, 0, length, position);
        return n === length ? bytes : bytes.subarray(0, n);
      } finally {
        fs.closeSync(fd);
      }
    },
  };
}
