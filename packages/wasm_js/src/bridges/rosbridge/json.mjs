// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * JSON that keeps 64-bit integers: `parseJson` reads integer literals
 * beyond 2^53 as BigInt (JSON.parse would round them), `stringifyJson`
 * writes BigInts as their digits, typed arrays as arrays and non-finite
 * numbers as null (what rosbridge_server writes for NaN and Infinity).
 *
 * @module bridges/rosbridge/json
 */

/** A text that is not JSON; `position` is the offset of the error. */
export class JsonError extends Error {
  constructor(message, position) {
    super(message);
    this.name = 'JsonError';
    this.position = position;
  }
}

const MAYBE_BIG = /\d{16,}/;

/**
 * Parse JSON text. Integers outside the safe range become BigInt.
 * @param {string} text
 */
export function parseJson(text) {
  if (!MAYBE_BIG.test(text)) {
    try {
      return JSON.parse(text);
    } catch (e) {
      throw new JsonError(e.message, undefined);
    }
  }
  return new PreciseParser(text).parse();
}

class PreciseParser {
  constructor(text) {
    this.s = text;
    this.i = 0;
  }

  fail(what) {
    throw new JsonError(`${what} at position ${this.i}`, this.i);
  }

  ws() {
    const s = this.s;
    while (this.i < s.length) {
      const c = s.charCodeAt(this.i);
      if (c === 32 || c === 9 || c === 10 || c === 13) this.i++;
      else break;
    }
  }

  parse() {
    this.ws();
    const v = this.value();
    this.ws();
    if (this.i !== this.s.length) this.fail('Unexpected text after the JSON value');
    return v;
  }

  value() {
    const c = this.s[this.i];
    if (c === '{') return this.object();
    if (c === '[') return this.array();
    if (c === '"') return this.string();
    if (c === '-' || (c >= '0' && c <= '9')) return this.number();
    for (const [word, v] of [['true', true], ['false', false], ['null', null]]) {
      if (this.s.startsWith(word, this.i)) {
        this.i += word.length;
        return v;
      }
    }
    return this.fail(c === undefined ? 'Unexpected end of JSON input' : `Unexpected token ${c}`);
  }

  object() {
    const o = {};
    this.i++;
    this.ws();
    if (this.s[this.i] === '}') { this.i++; return o; }
    for (;;) {
      this.ws();
      if (this.s[this.i] !== '"') this.fail('Expected a string key');
      const k = this.string();
      this.ws();
      if (this.s[this.i] !== ':') this.fail("Expected ':'");
      this.i++;
      this.ws();
      o[k] = this.value();
      this.ws();
      const c = this.s[this.i++];
      if (c === '}') return o;
      if (c !== ',') { this.i--; this.fail("Expected ',' or '}'"); }
    }
  }

  array() {
    const a = [];
    this.i++;
    this.ws();
    if (this.s[this.i] === ']') { this.i++; return a; }
    for (;;) {
      this.ws();
      a.push(this.value());
      this.ws();
      const c = this.s[this.i++];
      if (c === ']') return a;
      if (c !== ',') { this.i--; this.fail("Expected ',' or ']'"); }
    }
  }

  string() {
    // find the closing quote, then let JSON.parse unescape the literal
    const start = this.i;
    let j = start + 1;
    const s = this.s;
    for (;;) {
      const c = s.charCodeAt(j);
      if (Number.isNaN(c)) { this.i = j; this.fail('Unterminated string'); }
      if (c === 92) j += 2;
      else if (c === 34) break;
      else j++;
    }
    this.i = j + 1;
    try {
      return JSON.parse(s.slice(start, j + 1));
    } catch (e) {
      this.i = start;
      return this.fail(`Bad string (${e.message})`);
    }
  }

  number() {
    const m = /^-?(0|[1-9]\d*)(\.\d+)?([eE][+-]?\d+)?/.exec(this.s.slice(this.i, this.i + 400));
    if (!m) this.fail('Bad number');
    this.i += m[0].length;
    if (!m[2] && !m[3]) {
      const n = Number(m[0]);
      if (Number.isSafeInteger(n)) return n;
      return BigInt(m[0]);
    }
    return Number(m[0]);
  }
}

/**
 * JSON text of a value: BigInt as digits, typed arrays as arrays, NaN and
 * ±Infinity as null, undefined members left out.
 */
export function stringifyJson(value) {
  const out = [];
  write(value, out);
  return out.join('');
}

function write(v, out) {
  switch (typeof v) {
    case 'string': out.push(JSON.stringify(v)); return;
    case 'number': out.push(Number.isFinite(v) ? String(v) : 'null'); return;
    case 'bigint': out.push(v.toString()); return;
    case 'boolean': out.push(v ? 'true' : 'false'); return;
    case 'undefined': out.push('null'); return;
    default: break;
  }
  if (v === null) { out.push('null'); return; }
  if (ArrayBuffer.isView(v) || Array.isArray(v)) {
    out.push('[');
    for (let i = 0; i < v.length; i++) {
      if (i) out.push(',');
      write(v[i], out);
    }
    out.push(']');
    return;
  }
  if (typeof v.toJSON === 'function') { write(v.toJSON(), out); return; }
  out.push('{');
  let first = true;
  for (const k of Object.keys(v)) {
    if (v[k] === undefined) continue;
    if (!first) out.push(',');
    first = false;
    out.push(JSON.stringify(k), ':');
    write(v[k], out);
  }
  out.push('}');
}
