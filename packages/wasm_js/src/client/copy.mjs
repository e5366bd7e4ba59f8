// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Copying message bytes between the bus and a heap without garbage.
 *
 * @module client/copy
 */

/**
 * Messages up to this size are copied with a loop: no view object, no
 * garbage. Word by word, a loop beats TypedArray.set() (which needs a
 * subarray) up to ~512 bytes; byte by byte it is 4-10x slower.
 */
const SMALL_COPY = 512;

// Int32Array views of the last two byte arrays copied (the bus and the wasm
// heap), for word copies without a new view per message.
let wordsOf1 = null;
let words1 = null;
let wordsOf2 = null;
let words2 = null;

/** An Int32Array over the same bytes as `u8`, or null when it is not word-aligned. */
function wordsOf(u8) {
  if (u8 === wordsOf1) return words1;
  if (u8 === wordsOf2) return words2;
  const w = (u8.byteOffset & 3) === 0 ? new Int32Array(u8.buffer, u8.byteOffset, u8.length >> 2) : null;
  wordsOf2 = wordsOf1;
  words2 = words1;
  wordsOf1 = u8;
  words1 = w;
  return w;
}

/** Copy len bytes; small copies allocate nothing (views would feed the GC per message). */
export function copyBytes(dst, dstOff, src, srcOff, len) {
  if (len > SMALL_COPY) {
    dst.set(srcOff === 0 && len === src.length ? src : src.subarray(srcOff, srcOff + len), dstOff);
    return;
  }
  let i = 0;
  if (((dstOff | srcOff) & 3) === 0 && len >= 16) {
    const d = wordsOf(dst);
    const s = wordsOf(src);
    if (d !== null && s !== null) {
      const n = len >> 2;
      const db = dstOff >> 2;
      const sb = srcOff >> 2;
      for (let k = 0; k < n; k++) d[db + k] = s[sb + k];
      i = n << 2;
    }
  }
  for (; i < len; i++) dst[dstOff + i] = src[srcOff + i];
}
