// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * A seeded mutation generator for the JS fuzz drivers (tests/fuzz/run.mjs):
 * the same seed gives the same inputs. Byte mutations (bit flips,
 * interesting values, 32/64-bit integers at any offset, inserts, deletes,
 * duplicated ranges, truncation, splicing with another corpus entry) and,
 * for JSON inputs, structure mutations (a value replaced by one of another
 * type or an edge value, keys dropped or added, arrays grown, deep nesting),
 * mixed with the byte mutations of the JSON text.
 *
 * @module tests/fuzz/mutate
 */

/** A small fast PRNG (mulberry32): `next()` is a float in [0, 1). */
export class Random {
  constructor(seed) {
    this.state = (Number(seed) >>> 0) || 1;
  }

  next() {
    this.state = (this.state + 0x6d2b79f5) >>> 0;
    let t = this.state;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  }

  /** An integer in [0, n). */
  int(n) {
    return Math.floor(this.next() * n);
  }

  pick(list) {
    return list[this.int(list.length)];
  }

  chance(p) {
    return this.next() < p;
  }
}

const INTERESTING_8 = [0, 1, 0x7f, 0x80, 0xff, 0x10, 0x20, 0x40, 0x00];
const INTERESTING_32 = [0, 1, 2, 3, 4, 8, 16, 0x7f, 0x80, 0xff, 0x100, 0x7fff, 0x8000, 0xffff, 0x10000,
  0x7fffffff, 0x80000000, 0xfffffffe, 0xffffffff, 1 << 20, 1 << 24];
const MAX_BYTES = 1 << 16;

const enc = new TextEncoder();
const dec = new TextDecoder('utf-8', { fatal: false });

function writeU32(out, at, v) {
  if (at + 4 > out.length) return;
  out[at] = v & 0xff; out[at + 1] = (v >>> 8) & 0xff; out[at + 2] = (v >>> 16) & 0xff; out[at + 3] = (v >>> 24) & 0xff;
}

/**
 * One to four byte mutations of `input` (a new array; `input` is kept).
 * @param {Random} rng
 * @param {Uint8Array} input
 * @param {Uint8Array[]} corpus other entries, for splicing
 * @returns {Uint8Array}
 */
export function mutateBytes(rng, input, corpus = []) {
  let out = Uint8Array.from(input);
  const rounds = 1 + rng.int(4);
  for (let r = 0; r < rounds; r++) {
    const n = out.length;
    const at = n ? rng.int(n) : 0;
    switch (rng.int(11)) {
      case 0: if (n) out[at] ^= 1 << rng.int(8); break;
      case 1: if (n) out[at] = rng.pick(INTERESTING_8); break;
      case 2: if (n) out[at] = rng.int(256); break;
      case 3: if (n >= 4) writeU32(out, rng.int(n - 3), rng.pick(INTERESTING_32)); break;
      case 4: if (n >= 4) writeU32(out, rng.int(n - 3), (out[at] + rng.int(9) - 4) >>> 0); break;
      case 5: { // insert random bytes
        const k = 1 + rng.int(8);
        const ins = Uint8Array.from({ length: k }, () => rng.int(256));
        out = concat(out.subarray(0, at), ins, out.subarray(at));
        break;
      }
      case 6: { // delete a range
        if (!n) break;
        const k = 1 + rng.int(Math.min(n - at, 16));
        out = concat(out.subarray(0, at), out.subarray(at + k));
        break;
      }
      case 7: { // duplicate a range
        if (!n) break;
        const k = 1 + rng.int(Math.min(n - at, 64));
        out = concat(out.subarray(0, at + k), out.subarray(at, at + k), out.subarray(at + k));
        break;
      }
      case 8: out = out.slice(0, n ? rng.int(n) : 0); break; // truncate
      case 9: { // splice with another entry
        const other = corpus.length ? rng.pick(corpus) : out;
        const cut = other.length ? rng.int(other.length) : 0;
        out = concat(out.subarray(0, at), other.subarray(cut));
        break;
      }
      default: { // overwrite with a piece of another entry
        const other = corpus.length ? rng.pick(corpus) : out;
        if (!other.length || !n) break;
        const from = rng.int(other.length);
        const k = Math.min(1 + rng.int(16), other.length - from, n - at);
        out.set(other.subarray(from, from + k), at);
      }
    }
  }
  return out.length > MAX_BYTES ? out.slice(0, MAX_BYTES) : out;
}

function concat(...parts) {
  const out = new Uint8Array(parts.reduce((s, p) => s + p.length, 0));
  let at = 0;
  for (const p of parts) { out.set(p, at); at += p.length; }
  return out;
}

const EDGE_VALUES = [null, true, false, 0, -1, 1.5, 2 ** 31, -(2 ** 31) - 1, 2 ** 32, 2 ** 53, -(2 ** 63), 1e308, -0,
  '', ' ', '0', '-1', 'NaN', 'a'.repeat(300), '\u0000', '\ud800', '/', '//', '/a b', 'std_msgs/msg/String',
  'cdr_test_msgs/msg/Nested', '$(env HOME)', '../..', [], {}, [null], [[[]]], { op: 'publish' }];

function randomValue(rng, depth = 0) {
  if (depth > 3 || rng.chance(0.6)) return structuredClone(rng.pick(EDGE_VALUES));
  if (rng.chance(0.5)) return Array.from({ length: rng.int(4) }, () => randomValue(rng, depth + 1));
  const obj = {};
  for (let i = rng.int(4); i > 0; i--) obj[rng.pick(['op', 'id', 'topic', 'type', 'msg', 'data', 'x', 'service', 'args'])] = randomValue(rng, depth + 1);
  return obj;
}

/** Every container in a JSON value, with the path to it: [[holder, key], ...]. */
function slots(value, out = [], depth = 0) {
  if (depth > 20 || value === null || typeof value !== 'object') return out;
  for (const key of Object.keys(value)) {
    out.push([value, key]);
    slots(value[key], out, depth + 1);
  }
  return out;
}

/**
 * One to three structure mutations of a JSON value (a copy), as text.
 * @returns {string|null} null when `text` is not JSON
 */
export function mutateJson(rng, text, corpusValues = []) {
  let value;
  try {
    value = JSON.parse(text);
  } catch {
    return null;
  }
  const rounds = 1 + rng.int(3);
  for (let r = 0; r < rounds; r++) {
    const all = slots(value);
    if (!all.length) {
      value = randomValue(rng);
      continue;
    }
    const [holder, key] = rng.pick(all);
    switch (rng.int(9)) {
      case 0: holder[key] = structuredClone(rng.pick(EDGE_VALUES)); break;
      case 1: if (Array.isArray(holder)) holder.splice(Number(key), 1); else delete holder[key]; break;
      case 2: holder[rng.pick(['op', 'id', 'extra', 'fragment_size', 'compression', 'queue_length', 'throttle_rate', key])] = randomValue(rng); break;
      case 3: if (Array.isArray(holder[key])) holder[key].push(...structuredClone(holder[key])); else holder[key] = [holder[key]]; break;
      case 4: { // a piece of another corpus entry
        if (!corpusValues.length) break;
        const other = slots(structuredClone(rng.pick(corpusValues)));
        if (other.length) { const [h, k] = rng.pick(other); holder[key] = h[k]; }
        break;
      }
      case 5: { // deep nesting
        let v = holder[key];
        for (let i = 0, d = 1 + rng.int(200); i < d; i++) v = rng.chance(0.5) ? [v] : { x: v };
        holder[key] = v;
        break;
      }
      case 6: if (typeof holder[key] === 'number') holder[key] = rng.pick([holder[key] + 1, -holder[key], holder[key] * 65536, String(holder[key])]); else holder[key] = randomValue(rng); break;
      case 7: if (typeof holder[key] === 'string') holder[key] = rng.pick([holder[key].slice(1), holder[key] + holder[key], holder[key].toUpperCase(), `/${holder[key]}`, Number(holder[key]) || 7]); break;
      default: holder[key] = randomValue(rng);
    }
  }
  return JSON.stringify(value);
}

/**
 * The next input from a corpus: a mutated entry. JSON entries get structure
 * mutations half the time (`json` option), else byte mutations of the text.
 * @param {Random} rng
 * @param {Uint8Array[]} corpus
 * @param {{json?: boolean}} options
 */
export function nextInput(rng, corpus, { json = false, jsonValues = [] } = {}) {
  const base = corpus.length ? rng.pick(corpus) : new Uint8Array(0);
  if (json && rng.chance(0.5)) {
    const text = mutateJson(rng, dec.decode(base), jsonValues);
    if (text !== null) return enc.encode(text);
  }
  return mutateBytes(rng, base, corpus);
}
