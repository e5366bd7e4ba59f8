// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Tests of packages/wasm_js/src/client/copy.mjs (copyBytes) and of
// copier.mjs' memoryMover, run by tests/test_copy.py with `node --test`:
// every size class (the loop, TypedArray.set), between
// shared and unshared memory both ways and at every pair of alignments
// modulo 8, byte for byte against a reference, with the bytes around the
// destination untouched.

import assert from 'node:assert/strict';
import { test } from 'node:test';

import { copyBytes } from '../../packages/wasm_js/src/client/copy.mjs';
import { memoryMover } from '../../packages/wasm_js/src/copier.mjs';

const SIZES = [0, 1, 15, 16, 100, 512, 513, 4095, 4096, 4097, 65536 + 3, 921600 + 5];

function bytes(shared, n) {
  return new Uint8Array(shared ? new SharedArrayBuffer(n) : new ArrayBuffer(n));
}

function fill(u8, seed) {
  for (let i = 0; i < u8.length; i++) u8[i] = (i * 31 + seed * 7 + (i >> 8)) & 255;
}

for (const [from, to] of [[true, false], [false, true], [true, true], [false, false]]) {
  test(`copyBytes ${from ? 'shared' : 'plain'} -> ${to ? 'shared' : 'plain'}`, () => {
    for (const len of SIZES) {
      const src = bytes(from, len + 32);
      const dst = bytes(to, len + 32);
      fill(src, len);
      for (const srcOff of [0, 1, 3, 8]) {
        for (const dstOff of [0, 1, 5, 13, 31]) {
          dst.fill(0xee);
          copyBytes(dst, dstOff, src, srcOff, len);
          assert.deepEqual(dst.subarray(dstOff, dstOff + len), src.subarray(srcOff, srcOff + len),
            `len ${len}, src +${srcOff}, dst +${dstOff}`);
          assert.ok(dst.subarray(0, dstOff).every((b) => b === 0xee), 'bytes before the copy');
          assert.ok(dst.subarray(dstOff + len).every((b) => b === 0xee), 'bytes after the copy');
        }
      }
    }
  });
}

test('copyBytes through views that do not start at their buffer', () => {
  const src = new Uint8Array(new SharedArrayBuffer(70000), 3, 69000);
  const dst = new Uint8Array(new ArrayBuffer(70000), 6, 69000);
  fill(src, 9);
  copyBytes(dst, 10, src, 7, 60000);
  assert.deepEqual(dst.subarray(10, 60010), src.subarray(7, 60007));
});

test('memoryMover moves within a shared memory at any alignment', () => {
  const memory = new WebAssembly.Memory({ initial: 2, maximum: 2, shared: true });
  const move = memoryMover(memory);
  assert.equal(typeof move, 'function');
  const u8 = new Uint8Array(memory.buffer);
  const source = u8.slice(0, 5000);
  fill(source, 4);
  for (const dstAt of [65536, 65537, 65543, 70031]) {
    u8.fill(0);
    u8.set(source, 8);
    move(dstAt, 8, source.length);
    assert.deepEqual(u8.subarray(dstAt, dstAt + source.length), source);
    assert.equal(u8[dstAt - 1], 0);
    assert.equal(u8[dstAt + source.length], 0);
  }
  // outside the memory: an error, not a copy cut short
  assert.throws(() => move(131072 - 10, 0, 100), WebAssembly.RuntimeError);
});

test('memoryMover needs a shared WebAssembly.Memory', () => {
  assert.equal(memoryMover(new WebAssembly.Memory({ initial: 1 })), null);
  assert.equal(memoryMover(new SharedArrayBuffer(8)), null);
});
