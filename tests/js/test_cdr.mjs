// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Tests of packages/wasm_js/src/cdr.mjs, run by tests/test_cdr.py with
// `node --test`.  CDR_TYPES names the types.json of cdr_test_msgs (written by
// colcon_wasm.typedesc); the golden vectors are tests/data/cdr/*.json.

import assert from 'node:assert/strict';
import { readFileSync, readdirSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { test } from 'node:test';
import { fileURLToPath } from 'node:url';

import {
  CdrError, TypeRegistry, UnknownTypeError, normalizeTypeName, toHex, toPlain,
} from '../../packages/wasm_js/src/cdr.mjs';

const here = dirname(fileURLToPath(import.meta.url));
const dataDir = join(here, '..', 'data', 'cdr');
const types = JSON.parse(readFileSync(process.env.CDR_TYPES, 'utf-8'));
const registry = new TypeRegistry([types]);
const vectors = readdirSync(dataDir).filter((f) => f.endsWith('.json')).flatMap(
  (f) => JSON.parse(readFileSync(join(dataDir, f), 'utf-8')).vectors);

const fromHex = (h) => Uint8Array.from(h.match(/../g) || [], (b) => parseInt(b, 16));
const plain = (v) => toPlain(v, { bigint: 'string' });

test('there are golden vectors for every cdr_test_msgs message', () => {
  const covered = new Set(vectors.map((v) => v.type));
  for (const name of registry.messages.keys()) {
    assert.ok(covered.has(name), `no golden vector for ${name}`);
  }
});

for (const vector of vectors) {
  test(`encode ${vector.name} gives Fast CDR's bytes`, () => {
    assert.equal(toHex(registry.encode(vector.type, vector.value)), vector.hex);
  });
  test(`decode ${vector.name} gives the value back`, () => {
    assert.deepEqual(plain(registry.decode(vector.type, fromHex(vector.hex))), vector.value);
  });
}

test('hand-derived bytes: header, alignment after the header, string with NUL', () => {
  // uint8 tag=1 | pad to 8 | float64 x=2.0 | uint32 len=3 | 'h' 'i' NUL
  const bytes = registry.encode('cdr_test_msgs/msg/Inner', { tag: 1, x: 2, label: 'hi' });
  assert.equal(toHex(bytes), '00010000' + '01' + '00'.repeat(7) + '0000000000000040'
    + '03000000' + '686900');
});

test('hand-derived bytes: wstring is a count of UTF-16 units, each as uint32', () => {
  const value = registry.create('cdr_test_msgs/msg/Strings');
  value.w = '\u00e9\u{1F600}';  // é, then a surrogate pair
  const hex = toHex(registry.encode('cdr_test_msgs/msg/Strings', value));
  assert.ok(hex.includes('03000000' + 'e9000000' + '3dd80000' + '00de0000'), hex);
});

test('decoded numeric collections are typed arrays, 64-bit values BigInt', () => {
  const v = registry.decode('cdr_test_msgs/msg/Sequences', registry.encode(
    'cdr_test_msgs/msg/Sequences', { u8s: [1, 2], f64s: [0.5], u64s: ['18446744073709551615'] }));
  assert.ok(v.u8s instanceof Uint8Array);
  assert.ok(v.f64s instanceof Float64Array);
  assert.ok(v.u64s instanceof BigUint64Array);
  assert.equal(v.u64s[0], 18446744073709551615n);
  assert.deepEqual(v.strings, []);
});

test('typed arrays and plain arrays encode the same', () => {
  const type = 'cdr_test_msgs/msg/Sequences';
  const a = registry.encode(type, { i16s: [1, -2, 3], f64s: [1.5, 2.5], u8s: [9] });
  const b = registry.encode(type, {
    i16s: Int16Array.of(1, -2, 3), f64s: Float64Array.of(1.5, 2.5), u8s: Uint8Array.of(9),
  });
  assert.equal(toHex(a), toHex(b));
});

test('round trip of a large byte sequence (an image-sized payload)', () => {
  const u8s = new Uint8Array(1 << 20);
  for (let i = 0; i < u8s.length; i++) u8s[i] = (i * 31) & 0xff;
  const type = 'cdr_test_msgs/msg/Sequences';
  const back = registry.decode(type, registry.encode(type, { u8s, lead: 1 }));
  assert.equal(back.u8s.length, u8s.length);
  assert.deepEqual(back.u8s, u8s);
});

test('missing fields take the declared defaults, create() gives them', () => {
  const type = 'cdr_test_msgs/msg/Defaults';
  const declared = vectors.find((v) => v.name === 'defaults_as_declared');
  assert.equal(toHex(registry.encode(type, {})), declared.hex);
  const d = registry.create(type);
  assert.equal(d.count, 7);
  assert.equal(d.big, 18446744073709551615n);
  assert.ok(d.triple instanceof Int16Array);
  assert.deepEqual(d.words, ['a', 'b,c']);
  d.words.push('changed');
  assert.deepEqual(registry.create(type).words, ['a', 'b,c'], 'defaults are not shared');
});

test('64-bit fields accept BigInt, safe numbers and decimal strings', () => {
  const type = 'cdr_test_msgs/srv/AddTwoInts_Request';
  const hex = toHex(registry.encode(type, { a: 2n, b: -3n }));
  assert.equal(toHex(registry.encode(type, { a: 2, b: '-3' })), hex);
});

test('type names: DDS spelling and package/Type are accepted', () => {
  assert.equal(normalizeTypeName('std_msgs::msg::dds_::String_'), 'std_msgs/msg/String');
  assert.equal(normalizeTypeName('std_msgs/String'), 'std_msgs/msg/String');
  assert.ok(registry.has('cdr_test_msgs::msg::dds_::Inner_'));
  const { request, response } = registry.service('cdr_test_msgs/srv/AddTwoInts');
  assert.deepEqual({ request, response }, {
    request: 'cdr_test_msgs/srv/AddTwoInts_Request',
    response: 'cdr_test_msgs/srv/AddTwoInts_Response',
  });
});

const bad = [
  ['cdr_test_msgs/msg/Primitives', { u8: 256 }, "field 'u8': 256 is not a uint8 (an integer from 0 to 255)"],
  ['cdr_test_msgs/msg/Primitives', { i32: 1.5 }, "field 'i32': 1.5 is not a int32"],
  ['cdr_test_msgs/msg/Primitives', { u64: -1 }, "field 'u64': -1 is not a uint64"],
  ['cdr_test_msgs/msg/Primitives', { i64: 2 ** 60 }, "field 'i64'"],
  ['cdr_test_msgs/msg/Primitives', { f32: 'x' }, "field 'f32': \"x\" is not a float32"],
  ['cdr_test_msgs/msg/Primitives', { b: 'yes' }, "field 'b': \"yes\" is not a bool"],
  ['cdr_test_msgs/msg/Primitives', { u9: 1 }, "no field 'u9' (fields: b, f64_after_bool"],
  ['cdr_test_msgs/msg/Strings', { bounded: 'eleven char' }, "field 'bounded': the string has 11 bytes, more than its bound of 10"],
  ['cdr_test_msgs/msg/Strings', { wbounded: '123456' }, "field 'wbounded': the wstring has 6 characters"],
  ['cdr_test_msgs/msg/Strings', { s: 5 }, "field 's': 5 is not a string"],
  ['cdr_test_msgs/msg/Strings', { s: 'a\u0000b' }, 'cannot contain a NUL'],
  ['cdr_test_msgs/msg/Arrays', { f64s: [1] }, "field 'f64s': has 1 elements, the array needs exactly 2"],
  ['cdr_test_msgs/msg/BoundedSequences', { u8s: [1, 2, 3, 4, 5] }, 'more than the sequence bound of 4'],
  ['cdr_test_msgs/msg/BoundedSequences', { strings: ['toolong'] }, "field 'strings[0]': the string has 7 bytes"],
  ['cdr_test_msgs/msg/Nested', { more: [{ tag: 1, x: 'no' }] }, "field 'more[0].x': \"no\" is not a float64"],
  ['cdr_test_msgs/msg/Nested', { inner: 3 }, "field 'inner': 3 is not a cdr_test_msgs/msg/Inner message"],
  ['cdr_test_msgs/msg/Nested', { inner: { nope: 1 } }, "field 'inner' has no field 'nope'"],
  ['cdr_test_msgs/msg/Sequences', { u8s: 'abc' }, "field 'u8s': \"abc\" is not a sequence uint8 values"],
];
for (const [type, value, message] of bad) {
  test(`encode rejects ${JSON.stringify(value)} with a clear error`, () => {
    assert.throws(() => registry.encode(type, value), (e) => {
      assert.ok(e instanceof CdrError, e);
      assert.ok(e.message.startsWith(`encoding ${type}: `), e.message);
      assert.ok(e.message.includes(message), `${e.message}\n  does not include\n${message}`);
      return true;
    });
  });
}

test('decode rejects truncated, malformed and foreign input', () => {
  const type = 'cdr_test_msgs/msg/Inner';
  const good = registry.encode(type, { tag: 1, x: 2, label: 'hello' });
  assert.throws(() => registry.decode(type, good.subarray(0, 3)), /shorter than the 4-byte CDR header/);
  assert.throws(() => registry.decode(type, good.subarray(0, good.length - 1)),
    /field 'label': a count of 6 elements does not fit in the 5 bytes left/);
  const cut = registry.encode('cdr_test_msgs/msg/Primitives', {});
  assert.throws(() => registry.decode('cdr_test_msgs/msg/Primitives', cut.subarray(0, 30)),
    /decoding cdr_test_msgs\/msg\/Primitives: field 'i32': the message ends at byte 30, but 4 more bytes are needed at byte 28/);
  assert.throws(() => registry.decode(type, Uint8Array.of(0, 7, 0, 0, 1)), /unsupported encapsulation 00 07/);
  const huge = Uint8Array.from(good);
  new DataView(huge.buffer).setUint32(20, 0xfffffff0, true);  // the string length
  assert.throws(() => registry.decode(type, huge), /a count of 4294967280 elements does not fit/);
  const noNul = Uint8Array.from(good);
  noNul[noNul.length - 1] = 0x21;
  assert.throws(() => registry.decode(type, noNul), /does not end with NUL/);
});

test('decode reads big-endian CDR too', () => {
  // 00 00 header = CDR_BE; uint8 tag, pad, float64 2.0, string "a"
  const be = Uint8Array.from([0, 0, 0, 0, 7, 0, 0, 0, 0, 0, 0, 0,
    0x40, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 0x61, 0]);
  assert.deepEqual(registry.decode('cdr_test_msgs/msg/Inner', be), { tag: 7, x: 2, label: 'a' });
});

test('unknown types say which package is missing', () => {
  assert.throws(() => registry.encode('std_msgs/msg/String', {}), (e) => {
    assert.ok(e instanceof UnknownTypeError);
    assert.match(e.message, /unknown message type 'std_msgs\/msg\/String': no types.json of package 'std_msgs'/);
    return true;
  });
  assert.throws(() => registry.message('cdr_test_msgs/msg/Nope'),
    /package 'cdr_test_msgs' has type descriptions, but not this message/);
});

test('toPlain makes decoded values JSON-safe', () => {
  assert.deepEqual(toPlain({ a: 5n, b: 2n ** 60n, c: NaN, d: Float32Array.of(0.5), e: [-Infinity] }),
    { a: 5, b: '1152921504606846976', c: 'NaN', d: [0.5], e: ['-Infinity'] });
});
