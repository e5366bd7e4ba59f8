// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Copies between a node's wasm heap and the bus with WebAssembly's
 * `memory.copy`, where the engine supports multi-memory (Chromium 120+,
 * Node.js 22+).
 *
 * TypedArray.set() between two SharedArrayBuffers is an element-wise
 * relaxed-atomic copy in V8; `memory.copy` is a plain memmove. Measured in
 * Chromium 156 on the bench machine, 1 MiB from a wasm heap into a bus
 * cycling over 31 MiB: 13 GB/s against 6 GB/s (docs/performance.md). So when
 * the bus is a shared WebAssembly.Memory (Bus.create does that where this
 * module is supported), each thread builds a tiny module that imports both
 * memories and exports the two copies. Elsewhere (Node.js 20) the bus stays
 * a SharedArrayBuffer and the copies stay TypedArray.set().
 *
 * The relaxed-atomic copy goes word by word only when the source and the
 * destination sit at the same offset modulo 8; otherwise it goes byte by
 * byte (3.6 GB/s against 28 GB/s on the bench machine, Node.js 20). A copy
 * to a place whose alignment is not the source's (an MCAP Message record's
 * data sits 31 bytes into it) can be made in two fast steps when the
 * destination is a shared WebAssembly.Memory: TypedArray.set() to an
 * aligned staging area in it, then `memoryMover`'s memory.copy within that
 * one memory (no multi-memory needed: every engine with bulk memory, Node.js
 * 20 included).
 *
 * @module copier
 */

function leb(n) {
  const out = [];
  do {
    let b = n & 0x7f;
    n >>>= 7;
    if (n) b |= 0x80;
    out.push(b);
  } while (n);
  return out;
}

function name(s) {
  return [s.length, ...Array.from(s, (c) => c.charCodeAt(0))];
}

function section(id, body) {
  return [id, ...leb(body.length), ...body];
}

/** The import of a memory "m".`field` with these limits. */
function memoryImport(field, limits) {
  return [...name('m'), ...name(field), 0x02, ...limits];
}

/** A function body (with its size) of (dst, src, len): memory.copy from memory `src` to `dst`. */
function copyBody(dst, src) {
  // local.get 0..2; memory.copy dst src; end
  const body = [0, 0x20, 0, 0x20, 1, 0x20, 2, 0xfc, 0x0a, dst, src, 0x0b];
  return [...leb(body.length), ...body];
}

/**
 * The bytes of a module importing memory 0 "m"."heap" and memory 1
 * "m"."bus" (shared, any size up to 4 GiB; the heap unshared when
 * `heapShared` is false) and exporting toBus(dst, src, len) and
 * fromBus(dst, src, len).
 */
function moduleBytes(heapShared) {
  // limits: 0x03 = shared with a maximum, 0x00 = a minimum only.
  const heapLimits = heapShared ? [0x03, 0, ...leb(65536)] : [0x00, 0];
  const busLimits = [0x03, 0, ...leb(65536)];
  return new Uint8Array([
    0x00, 0x61, 0x73, 0x6d, 0x01, 0x00, 0x00, 0x00,
    ...section(1, [1, 0x60, 3, 0x7f, 0x7f, 0x7f, 0]),
    ...section(2, [2, ...memoryImport('heap', heapLimits), ...memoryImport('bus', busLimits)]),
    ...section(3, [2, 0, 0]),
    ...section(7, [2, ...name('toBus'), 0x00, 0, ...name('fromBus'), 0x00, 1]),
    ...section(10, [2, ...copyBody(1, 0), ...copyBody(0, 1)]),
  ]);
}

/**
 * The bytes of a module importing one shared memory "m"."memory" and
 * exporting move(dst, src, len), a memory.copy within it.
 */
function moverBytes() {
  return new Uint8Array([
    0x00, 0x61, 0x73, 0x6d, 0x01, 0x00, 0x00, 0x00,
    ...section(1, [1, 0x60, 3, 0x7f, 0x7f, 0x7f, 0]),
    ...section(2, [1, ...memoryImport('memory', [0x03, 0, ...leb(65536)])]),
    ...section(3, [1, 0]),
    ...section(7, [1, ...name('move'), 0x00, 0]),
    ...section(10, [1, ...copyBody(0, 0)]),
  ]);
}

const compiled = new Map();

function compile(heapShared) {
  if (!compiled.has(heapShared)) {
    let mod = null;
    try {
      if (typeof WebAssembly === 'object') mod = new WebAssembly.Module(moduleBytes(heapShared));
    } catch (e) {
      mod = null; // no multi-memory here
    }
    compiled.set(heapShared, mod);
  }
  return compiled.get(heapShared);
}

/** True when this engine can copy between two memories (multi-memory). */
export function multiMemorySupported() {
  return compile(true) !== null;
}

/**
 * Copy functions between `heap` and `bus`, or null when this engine or these
 * memories do not allow them.
 * @param {WebAssembly.Memory} heap a wasm heap (shared or not)
 * @param {WebAssembly.Memory} bus the bus memory (shared)
 * @returns {{toBus: function(number, number, number): void,
 *            fromBus: function(number, number, number): void}|null}
 *   toBus(busOffset, heapOffset, len), fromBus(heapOffset, busOffset, len);
 *   both throw a RangeError-like RuntimeError when a range lies outside its memory
 */
export function heapCopier(heap, bus) {
  if (typeof WebAssembly !== 'object' || !(heap instanceof WebAssembly.Memory) ||
      !(bus instanceof WebAssembly.Memory)) return null;
  const shared = typeof SharedArrayBuffer !== 'undefined' && heap.buffer instanceof SharedArrayBuffer;
  const mod = compile(shared);
  if (mod === null) return null;
  try {
    const e = new WebAssembly.Instance(mod, { m: { heap, bus } }).exports;
    return { toBus: e.toBus, fromBus: e.fromBus };
  } catch (err) {
    return null; // e.g. a heap whose limits the import does not accept
  }
}

let mover = null;

/**
 * memory.copy within one shared memory, at any alignment (see the module's
 * text), or null when this engine or this memory does not allow it.
 * @param {WebAssembly.Memory} memory a shared memory
 * @returns {?function(number, number, number): void} move(dstOffset, srcOffset, len);
 *   it throws a RuntimeError when a range lies outside the memory
 */
export function memoryMover(memory) {
  if (typeof WebAssembly !== 'object' || !(memory instanceof WebAssembly.Memory)) return null;
  try {
    if (mover === null) mover = new WebAssembly.Module(moverBytes());
    return new WebAssembly.Instance(mover, { m: { memory } }).exports.move;
  } catch (err) {
    return null; // no bulk memory, or a memory the import does not accept
  }
}
