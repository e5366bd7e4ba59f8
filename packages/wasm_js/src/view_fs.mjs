// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Read-only views of host directories inside an Emscripten program, at the
 * same absolute paths as on the host (an install space at
 * `/home/u/ws/install_wasm` is `/home/u/ws/install_wasm` for the program).
 *
 * One Emscripten file system type (`VIEWFS`, modelled on Emscripten's MEMFS
 * and WORKERFS) over a pluggable synchronous {@link ViewSource}: real files
 * through node:fs under Node.js (view_source_node.mjs), `colcon-wasm serve`
 * over synchronous XMLHttpRequest in a browser worker (view_source_http.mjs).
 * Everything is lazy: mounting asks the source nothing; a directory is
 * listed once, when a path through it is first looked up or it is read, and
 * a file is read when the program reads it. Writes fail with EROFS. Runs
 * where Emscripten's FS lives, the program's program worker: its pthreads
 * proxy their file system calls there.
 *
 * @module view_fs
 */

/** Emscripten's errno values (WASI numbering, system/include/wasi/api.h). */
export const Errno = Object.freeze({
  EACCES: 2, EBADF: 8, EEXIST: 20, EINVAL: 28, EIO: 29, EISDIR: 31, ELOOP: 32,
  ENOENT: 44, ENOTDIR: 54, ENOTEMPTY: 55, EPERM: 63, EROFS: 69,
});

const ERRNO_NAMES = new Map(Object.entries(Errno).map(([name, value]) => [value, name]));

const S_IFDIR = 0o040000;
const S_IFREG = 0o100000;
const PERMISSION_BITS = 0o7777;
const O_ACCMODE = 0o3;
const O_RDONLY = 0;
const SEEK_CUR = 1;
const SEEK_END = 2;

/**
 * What a source says about one file or directory.
 * @typedef {object} ViewEntry
 * @property {string} name base name (ignored for a listing's `self`)
 * @property {'dir'|'file'} kind symbolic links are followed: the kind of their target
 * @property {number} size bytes
 * @property {number} mode permission bits (type bits are ignored)
 * @property {number} mtimeMs modification time, ms since the epoch
 */

/**
 * A synchronous backing store of views. Paths are absolute and normalized
 * (no trailing slash). Methods throw an Error whose `code` names the errno
 * ('ENOENT', 'ENOTDIR', 'EACCES', ...); any other error reads as EIO.
 * @typedef {object} ViewSource
 * @property {function(string): {self: ViewEntry, entries: ViewEntry[]}} list a directory:
 *   itself and its entries (without `.` and `..`)
 * @property {function(string, number, number): Uint8Array} read up to `length` bytes of a
 *   file from `position` (fewer at its end)
 * @property {function(string): void} [prefetch] told the whole path before a lookup walks it
 *   (the file system lists one directory at a time): a source whose requests are costly may
 *   fetch the listings along it at once; its errors are ignored (the lookup reports them)
 */

/**
 * The errno name of an error of a source or of Emscripten's FS (for messages).
 * @param {*} error
 * @returns {string}
 */
export function errnoName(error) {
  if (error && typeof error.errno === 'number') return ERRNO_NAMES.get(error.errno) || `errno ${error.errno}`;
  if (error && typeof error.code === 'string') return error.code;
  return String(error && error.message ? error.message : error);
}

/**
 * Create the VIEWFS file system type for one program's Emscripten FS.
 * @param {object} FS Emscripten's FS object (the glue's global `FS`)
 * @param {function(string): void} [warn] told once per path about source failures that are
 *   not a plain "no such file" (an HTTP error, an unreadable file), which the program sees as EIO
 * @returns {object} a file system type for `FS.mount(type, {source}, path)`
 */
export function createViewFs(FS, warn = () => {}) {
  const fail = (errno) => {
    throw new FS.ErrnoError(errno);
  };
  const readOnly = () => fail(Errno.EROFS);
  const warned = new Set();

  /** Run a source call, turning its errors into Emscripten errnos. */
  function fromSource(what, path, call) {
    try {
      return call();
    } catch (e) {
      const errno = e && typeof e.code === 'string' ? Errno[e.code] : undefined;
      if (errno === Errno.ENOENT || errno === Errno.ENOTDIR) fail(errno);
      const code = errno || Errno.EIO;
      if (!warned.has(path)) {
        warned.add(path);
        warn(`wasm_js: cannot ${what} '${path}' of a read-only view (the program gets ${ERRNO_NAMES.get(code)}): `
          + `${e && e.message ? e.message : e}`);
      }
      fail(code);
    }
    return undefined;
  }

  const modeOf = (entry) => (entry.kind === 'dir' ? S_IFDIR : S_IFREG) | (entry.mode & PERMISSION_BITS);

  /** The entries of a directory node, listed on first use. */
  function children(node) {
    if (!node.viewChildren) {
      const path = FS.getPath(node);
      const listing = fromSource('list', path, () => node.mount.opts.source.list(path));
      if (listing.self && listing.self.kind !== 'dir') fail(Errno.ENOTDIR);
      // what the parent's listing said stays (one stat per node, as the program saw it first)
      if (!node.viewEntry && listing.self) {
        node.viewEntry = listing.self;
        node.mode = modeOf(listing.self);
      }
      node.viewChildren = new Map(listing.entries.map((e) => [e.name, e]));
    }
    return node.viewChildren;
  }

  function createNode(parent, name, entry) {
    const dir = entry.kind === 'dir';
    const node = FS.createNode(parent, name, modeOf(entry), 0);
    node.node_ops = dir ? dirNodeOps : fileNodeOps;
    node.stream_ops = dir ? dirStreamOps : fileStreamOps;
    node.viewEntry = entry;
    node.viewChildren = null;
    return node;
  }

  function getattr(node) {
    // The root's entry comes with its own listing (a source lists only inside its views).
    if (!node.viewEntry) children(node);
    const entry = node.viewEntry;
    const time = new Date(entry.mtimeMs);
    return {
      dev: 1, ino: node.id, mode: node.mode, nlink: 1, uid: 0, gid: 0, rdev: 0,
      size: entry.size,
      atime: time, mtime: time, ctime: time,
      blksize: 4096, blocks: Math.ceil(entry.size / 512),
    };
  }

  const commonNodeOps = {
    getattr,
    setattr: readOnly,
    readlink: () => fail(Errno.EINVAL),
  };
  const dirNodeOps = {
    ...commonNodeOps,
    lookup(parent, name) {
      const entry = children(parent).get(name);
      if (!entry) fail(Errno.ENOENT);
      return createNode(parent, name, entry);
    },
    readdir: (node) => ['.', '..', ...children(node).keys()],
    mknod: readOnly,
    rename: readOnly,
    unlink: readOnly,
    rmdir: readOnly,
    symlink: readOnly,
  };
  const fileNodeOps = {
    ...commonNodeOps,
    lookup: () => fail(Errno.ENOTDIR),
  };

  function llseek(stream, offset, whence) {
    let position = offset;
    if (whence === SEEK_CUR) position += stream.position;
    else if (whence === SEEK_END && FS.isFile(stream.node.mode)) position += stream.node.viewEntry.size;
    if (position < 0) fail(Errno.EINVAL);
    return position;
  }
  const dirStreamOps = { llseek };
  const fileStreamOps = {
    llseek,
    open(stream) {
      if ((stream.flags & O_ACCMODE) !== O_RDONLY) fail(Errno.EROFS);
    },
    read(stream, buffer, offset, length, position) {
      if (length === 0) return 0;
      const path = FS.getPath(stream.node);
      const bytes = fromSource('read', path, () => stream.node.mount.opts.source.read(path, position, length));
      const n = Math.min(bytes.length, length);
      new Uint8Array(buffer.buffer, buffer.byteOffset + offset, n).set(n === bytes.length ? bytes : bytes.subarray(0, n));
      return n;
    },
    write: readOnly,
  };

  return {
    /** Emscripten calls this from FS.mount(): the root node, nothing asked of the source yet. */
    mount(mount) {
      if (!mount.opts || !mount.opts.source) throw new Error('VIEWFS: FS.mount needs {source}');
      const root = FS.createNode(null, '/', S_IFDIR | 0o555, 0);
      root.node_ops = dirNodeOps;
      root.stream_ops = dirStreamOps;
      root.viewEntry = null;
      root.viewChildren = null;
      return root;
    },
  };
}

/**
 * Tell the views' sources each path a lookup is about to walk through them
 * ({@link ViewSource} `prefetch`): Emscripten's FS resolves every path with
 * FS.lookupPath, one directory at a time, so that is where a whole path is
 * seen. Other paths cost one prefix check.
 * @param {object} FS
 * @param {Array<{path: string, source: ViewSource}>} views
 */
function tellSourcesOfLookups(FS, views) {
  const lookupPath = FS.lookupPath;
  FS.lookupPath = function lookupPathOfViews(path, opts) {
    if (typeof path === 'string') {
      const absolute = path.startsWith('/') ? path : `${FS.cwd()}/${path}`;
      for (const view of views) {
        if (absolute.startsWith(view.path) && (absolute.length === view.path.length || absolute[view.path.length] === '/')) {
          const normalized = absolute.split('/').filter((p) => p && p !== '.').join('/');
          if (!normalized.split('/').includes('..')) {
            try {
              view.source.prefetch(`/${normalized}`);
            } catch (e) {
              // the lookup itself reports what is wrong
            }
          }
          break;
        }
      }
    }
    return lookupPath.call(this, path, opts);
  };
}

/**
 * Mount read-only views into a program's file system (from Module.preRun,
 * before main()). Creates the directories above each path in MEMFS; a view
 * inside another one is left out (the outer view shows the same files).
 * @param {object} FS Emscripten's FS
 * @param {Array<{path: string, source: ViewSource}>} views absolute, normalized paths
 * @param {function(string): void} [warn] see {@link createViewFs}
 * @returns {string[]} the paths mounted
 * @throws {Error} naming the path when a view cannot be mounted there
 */
export function mountViews(FS, views, warn) {
  const type = createViewFs(FS, warn);
  const inside = (path, outer) => outer === path || path.startsWith(outer.endsWith('/') ? outer : `${outer}/`);
  const mounted = [];
  // outer paths first, so that a view inside another is the one left out
  const byDepth = [...views].sort((a, b) => a.path.length - b.path.length);
  for (const { path, source } of byDepth) {
    if (mounted.some((outer) => inside(path, outer.path))) continue;
    try {
      FS.mkdirTree(path);
      FS.mount(type, { source }, path);
    } catch (e) {
      throw new Error(`cannot mount a read-only view at '${path}': ${errnoName(e)}`);
    }
    mounted.push({ path, source });
  }
  // after mounting: FS.mount's own lookups must not make sources fetch anything
  const prefetching = mounted.filter((v) => typeof v.source.prefetch === 'function');
  if (prefetching.length) tellSourcesOfLookups(FS, prefetching);
  return mounted.map((v) => v.path);
}
