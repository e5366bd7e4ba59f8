// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * Fuzz target: the JS CDR decoder (packages/wasm_js/src/cdr.mjs), the
 * TypeRegistry of cdr_test_msgs (every CDR feature: alignment, strings and
 * wstrings, bounded and unbounded sequences, fixed arrays, nesting, 64-bit
 * integers). An input is one byte naming the type (its index among the
 * registry's messages, modulo their count), then the CDR bytes. Decoding
 * either gives a value or throws CdrError; a value must encode again and
 * decode to the same value (no other exception, no mismatch). The seed
 * corpus is the golden vectors' bytes (tests/data/cdr/*.json, written by the
 * real Fast CDR library, tests/cdr_fastcdr.py).
 */

import assert from 'node:assert/strict';
import { readFileSync, readdirSync } from 'node:fs';
import { join } from 'node:path';

import { CdrError, toPlain, TypeRegistry } from '../../../packages/wasm_js/src/cdr.mjs';

export const options = { json: false };

function registryOf(types) {
  if (!types) throw new Error('the cdr target needs --types (the types.json of cdr_test_msgs)');
  return new TypeRegistry([JSON.parse(readFileSync(types, 'utf-8'))]);
}

const fromHex = (h) => Uint8Array.from(h.match(/../g) || [], (b) => parseInt(b, 16));

/** The seed corpus: each golden vector as [type index, CDR bytes...]. */
export function capture({ types, repo }) {
  const registry = registryOf(types);
  const names = [...registry.messages.keys()].sort();
  const dir = join(repo, 'tests', 'data', 'cdr');
  const seeds = [];
  for (const f of readdirSync(dir).filter((n) => n.endsWith('.json')).sort()) {
    for (const v of JSON.parse(readFileSync(join(dir, f), 'utf-8')).vectors) {
      const bytes = fromHex(v.hex);
      seeds.push({ name: v.name, bytes: Uint8Array.of(names.indexOf(v.type), ...bytes) });
    }
  }
  return seeds;
}

export async function setup({ types, repo }) {
  const registry = registryOf(types);
  const names = [...registry.messages.keys()].sort();
  const golden = capture({ types, repo });
  const plain = (v) => toPlain(v, { bigint: 'string' });
  return {
    coverageFiles: ['/packages/wasm_js/src/cdr.mjs'],
    one(input) {
      if (!input.length) return 'empty';
      const type = names[input[0] % names.length];
      let value;
      try {
        value = registry.decode(type, input.subarray(1));
      } catch (e) {
        if (e instanceof CdrError) return `CdrError ${e.message.replace(type, 'T')}`;
        throw e;
      }
      // what decodes must encode, and decode to the same value; but for a string
      // with a NUL inside, which Fast CDR reads too and the encoder refuses (rcl's
      // strings end at the first NUL)
      let bytes;
      try {
        bytes = registry.encode(type, value);
      } catch (e) {
        if (e instanceof CdrError && e.message.endsWith('a string cannot contain a NUL character')) return 'ok, a NUL inside a string';
        // bytes that are not UTF-8 decode as U+FFFD (3 bytes each): a bounded string can outgrow its bound
        if (e instanceof CdrError && / more than its bound of /.test(e.message) && JSON.stringify(plain(value)).includes('\ufffd')) {
          return 'ok, a bounded string that is not UTF-8';
        }
        throw e;
      }
      const again = registry.decode(type, bytes);
      assert.deepEqual(JSON.stringify(plain(again)), JSON.stringify(plain(value)), `${type}: decode(encode(v)) differs`);
      return `ok ${type}`;
    },
    check() {
      for (const seed of golden.slice(0, 3)) {
        const type = names[seed.bytes[0]];
        const v = registry.decode(type, seed.bytes.subarray(1));
        assert.deepEqual(registry.encode(type, v), seed.bytes.subarray(1), `${seed.name} no longer round-trips`);
      }
    },
  };
}
