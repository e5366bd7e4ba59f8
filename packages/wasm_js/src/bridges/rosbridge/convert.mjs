// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * ROS message values (as cdr.mjs decodes them) to and from rosbridge's
 * conventions, compiled once per type from the build's type descriptions:
 *
 *  - JSON out: `uint8[]`/`char[]` (sequences and arrays) as base64 strings,
 *    64-bit integers with every digit, NaN and ±Infinity as null, other
 *    numeric arrays as JSON arrays (rosbridge_library's message_conversion);
 *  - CBOR out (`compression: cbor`): byte arrays as byte strings, numeric
 *    arrays as RFC 8746 little-endian typed arrays, floats as float64
 *    (rosbridge_library's cbor_conversion);
 *  - JSON in: base64 strings (or number arrays, or CBOR byte strings) for
 *    byte arrays, `"now"` for a builtin_interfaces/Time, a missing
 *    std_msgs/Header (or its stamp) filled with the current time, null for a
 *    float as NaN; an unknown field or a value of the wrong type is an error
 *    naming the field;
 *  - rosapi's TypeDef lists (`/rosapi/message_details`).
 *
 * @module bridges/rosbridge/convert
 */

import { normalizeTypeName } from '../../cdr.mjs';

const NUMERIC = new Set(['byte', 'char', 'int8', 'uint8', 'int16', 'uint16', 'int32', 'uint32',
  'int64', 'uint64', 'float32', 'float64']);
const BIG = new Set(['int64', 'uint64']);
const FLOAT = new Set(['float32', 'float64']);
const BINARY = new Set(['uint8', 'char']);
const HEADER = 'std_msgs/msg/Header';
const TIME = 'builtin_interfaces/msg/Time';
/** The field type names rosapi gives (rclpy's spelling). */
const ROSAPI_NAMES = { float64: 'double', float32: 'float', bool: 'boolean', byte: 'octet' };

/** A value that does not fit the field it is for; `field` is the dotted path. */
export class ConvertError extends Error {
  constructor(type, field, message) {
    super(`${type}${field ? `: field '${field}'` : ''}: ${message}`);
    this.name = 'ConvertError';
    this.type = type;
    this.field = field;
  }
}

const B64 = 'ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/';
const NodeBuffer = globalThis.Buffer;

/** Base64 of bytes (standard alphabet, padded). */
export function toBase64(bytes) {
  if (NodeBuffer) return NodeBuffer.from(bytes.buffer, bytes.byteOffset, bytes.byteLength).toString('base64');
  let out = '';
  const n = bytes.length;
  let i = 0;
  const parts = [];
  for (; i + 2 < n; i += 3) {
    const v = (bytes[i] << 16) | (bytes[i + 1] << 8) | bytes[i + 2];
    out += B64[v >> 18] + B64[(v >> 12) & 63] + B64[(v >> 6) & 63] + B64[v & 63];
    if (out.length > 8192) { parts.push(out); out = ''; }
  }
  if (i < n) {
    const v = (bytes[i] << 16) | ((i + 1 < n ? bytes[i + 1] : 0) << 8);
    out += B64[v >> 18] + B64[(v >> 12) & 63] + (i + 1 < n ? B64[(v >> 6) & 63] : '=') + '=';
  }
  parts.push(out);
  return parts.join('');
}

/** Bytes of a base64 string; null when it is not base64. */
export function fromBase64(text) {
  if (!/^[A-Za-z0-9+/]*={0,2}$/.test(text) || text.length % 4 === 1) return null;
  if (NodeBuffer) {
    const b = NodeBuffer.from(text, 'base64');
    return new Uint8Array(b.buffer, b.byteOffset, b.length);
  }
  const bin = atob(text);
  const out = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) out[i] = bin.charCodeAt(i);
  return out;
}

const nowTime = () => {
  const ms = Date.now();
  return { sec: Math.floor(ms / 1000), nanosec: (ms % 1000) * 1e6 };
};

/** Converters of one TypeRegistry, compiled per type on first use. */
export class Converter {
  /** @param {import('../../cdr.mjs').TypeRegistry} registry */
  constructor(registry) {
    this.registry = registry;
    this._json = new Map();
    this._cbor = new Map();
    this._in = new Map();
  }

  /** Full name of a message type (`pkg/Name` -> `pkg/msg/Name`); throws for an unknown type. */
  messageType(name) {
    const full = normalizeTypeName(name);
    this.registry.message(full);
    return full;
  }

  /** A function: decoded value -> its rosbridge JSON text. */
  jsonWriter(type) {
    const full = normalizeTypeName(type);
    let f = this._json.get(full);
    if (!f) {
      this._json.set(full, (v) => this._json.get(full)(v)); // a type that contains itself
      f = this._compileJson(full);
      this._json.set(full, f);
    }
    return f;
  }

  _compileJson(full) {
    const fields = this.registry.message(full).fields.map((field) => {
      const key = `${JSON.stringify(field.name)}:`;
      const collection = field.sequence || field.array_size !== undefined;
      let one;
      if (field.type === 'string' || field.type === 'wstring') one = (v) => JSON.stringify(v);
      else if (field.type === 'bool') one = (v) => (v ? 'true' : 'false');
      else if (BIG.has(field.type)) one = (v) => String(v);
      else if (FLOAT.has(field.type)) one = (v) => (Number.isFinite(v) ? String(v) : 'null');
      else if (NUMERIC.has(field.type)) one = (v) => String(v);
      else {
        const type = normalizeTypeName(field.type);
        let nested = null;
        one = (v) => (nested || (nested = this.jsonWriter(type)))(v);
      }
      let write;
      if (!collection) write = one;
      else if (BINARY.has(field.type)) write = (v) => `"${toBase64(v)}"`;
      else if (NUMERIC.has(field.type) && !BIG.has(field.type) && !FLOAT.has(field.type)) write = (v) => `[${v.join(',')}]`;
      else write = (v) => { const out = new Array(v.length); for (let i = 0; i < v.length; i++) out[i] = one(v[i]); return `[${out.join(',')}]`; };
      return { name: field.name, key, write };
    });
    return (value) => {
      let s = '{';
      for (let i = 0; i < fields.length; i++) {
        const f = fields[i];
        s += (i ? ',' : '') + f.key + f.write(value[f.name]);
      }
      return `${s}}`;
    };
  }

  /** A function (writer: CborWriter, decoded value) writing rosbridge's CBOR form. */
  cborWriter(type) {
    const full = normalizeTypeName(type);
    let f = this._cbor.get(full);
    if (!f) {
      this._cbor.set(full, (w, v) => this._cbor.get(full)(w, v));
      f = this._compileCbor(full);
      this._cbor.set(full, f);
    }
    return f;
  }

  _compileCbor(full) {
    const fields = this.registry.message(full).fields.map((field) => {
      const collection = field.sequence || field.array_size !== undefined;
      let one;
      if (field.type === 'string' || field.type === 'wstring') one = (w, v) => w.string(v);
      else if (field.type === 'bool') one = (w, v) => w.bool(v);
      else if (FLOAT.has(field.type)) one = (w, v) => w.float64(v);
      else if (NUMERIC.has(field.type)) one = (w, v) => w.int(v);
      else {
        const type = normalizeTypeName(field.type);
        let nested = null;
        one = (w, v) => (nested || (nested = this.cborWriter(type)))(w, v);
      }
      let write;
      if (!collection) write = one;
      else if (NUMERIC.has(field.type)) write = (w, v) => w.typedArray(v);
      else write = (w, v) => { w.array(v.length); for (let i = 0; i < v.length; i++) one(w, v[i]); };
      return { name: field.name, write };
    });
    return (w, value) => {
      w.map(fields.length);
      for (const f of fields) {
        w.string(f.name);
        f.write(w, value[f.name]);
      }
    };
  }

  /**
   * Convert a rosbridge JSON (or CBOR-decoded) message object into a value
   * that `registry.encode(type, value)` takes.
   * @param {string} type
   * @param {*} msg
   * @returns {object}
   * @throws {ConvertError} naming the field
   */
  fromJson(type, msg) {
    const full = normalizeTypeName(type);
    return this._inConverter(full)(msg, '', full);
  }

  _inConverter(full) {
    let f = this._in.get(full);
    if (f) return f;
    this._in.set(full, (v, path, root) => this._in.get(full)(v, path, root));
    const fields = new Map(this.registry.message(full).fields.map((field) => [field.name, this._inField(field)]));
    const hasHeader = fields.has('header') && normalizeTypeName(this.registry.message(full).fields.find((x) => x.name === 'header').type) === HEADER;
    f = (msg, path, root) => {
      if (full === TIME && msg === 'now') return nowTime();
      if (msg === null || typeof msg !== 'object' || Array.isArray(msg) || ArrayBuffer.isView(msg)) {
        throw new ConvertError(root, path, `expected a JSON object for ${full}, got ${describe(msg)}`);
      }
      const out = {};
      for (const key of Object.keys(msg)) {
        const conv = fields.get(key);
        const p = path ? `${path}.${key}` : key;
        if (!conv) throw new ConvertError(root, p, `${full} has no field '${key}' (fields: ${[...fields.keys()].join(', ')})`);
        out[key] = conv(msg[key], p, root);
      }
      if (full === HEADER && !('stamp' in msg)) out.stamp = nowTime();
      if (hasHeader && !('header' in msg)) out.header = { stamp: nowTime(), frame_id: '' };
      return out;
    };
    this._in.set(full, f);
    return f;
  }

  _inField(field) {
    const collection = field.sequence || field.array_size !== undefined;
    const t = field.type;
    let one;
    if (t === 'string' || t === 'wstring') {
      one = (v, p, root) => { if (typeof v !== 'string') throw new ConvertError(root, p, `expected a string, got ${describe(v)}`); return v; };
    } else if (t === 'bool') {
      one = (v, p, root) => { if (typeof v !== 'boolean') throw new ConvertError(root, p, `expected a boolean, got ${describe(v)}`); return v; };
    } else if (FLOAT.has(t)) {
      one = (v, p, root) => {
        if (v === null) return NaN;
        if (typeof v !== 'number' && typeof v !== 'bigint') throw new ConvertError(root, p, `expected a number (${t}), got ${describe(v)}`);
        return Number(v);
      };
    } else if (NUMERIC.has(t)) {
      one = (v, p, root) => {
        const ok = typeof v === 'bigint' || (typeof v === 'number' && Number.isInteger(v))
          || (BIG.has(t) && typeof v === 'string' && /^\s*-?\d+\s*$/.test(v));
        if (!ok) throw new ConvertError(root, p, `expected an integer (${t}), got ${describe(v)}`);
        return v;
      };
    } else {
      const type = normalizeTypeName(t);
      let nested = null;
      one = (v, p, root) => (nested || (nested = this._inConverter(type)))(v, p, root);
    }
    if (!collection) return one;
    return (v, p, root) => {
      if (BINARY.has(t) || t === 'byte') {
        if (typeof v === 'string') {
          const bytes = fromBase64(v);
          if (!bytes) throw new ConvertError(root, p, `expected base64 text or an array of ${t}, got a string that is not base64`);
          return bytes;
        }
        if (v instanceof Uint8Array) return v;
      }
      if (ArrayBuffer.isView(v) && NUMERIC.has(t)) return v;
      if (!Array.isArray(v)) throw new ConvertError(root, p, `expected an array of ${t}, got ${describe(v)}`);
      const out = new Array(v.length);
      for (let i = 0; i < v.length; i++) out[i] = one(v[i], `${p}[${i}]`, root);
      return out;
    };
  }

  /**
   * rosapi TypeDefs of a message type and every type it contains
   * (`rosapi/MessageDetails`), the outer type first.
   */
  typedefs(type) {
    const seen = new Set();
    const out = [];
    const visit = (full) => {
      if (seen.has(full)) return;
      seen.add(full);
      const m = this.registry.message(full);
      const short = (name) => name.replace('/msg/', '/');
      const def = {
        type: short(full), fieldnames: [], fieldtypes: [], fieldarraylen: [], examples: [], constnames: [], constvalues: [],
      };
      const nested = [];
      for (const f of m.fields) {
        def.fieldnames.push(f.name);
        const primitive = NUMERIC.has(f.type) || f.type === 'bool' || f.type === 'string' || f.type === 'wstring';
        const ftype = primitive ? (ROSAPI_NAMES[f.type] || f.type) : short(normalizeTypeName(f.type));
        def.fieldtypes.push(ftype);
        const arraylen = f.array_size !== undefined ? f.array_size : f.sequence ? 0 : -1;
        def.fieldarraylen.push(arraylen);
        def.examples.push(arraylen >= 0 ? '[]' : primitive ? example(f.type) : '{}');
        if (!primitive) nested.push(normalizeTypeName(f.type));
      }
      for (const c of m.constants || []) {
        def.constnames.push(c.name);
        def.constvalues.push(String(c.value));
      }
      out.push(def);
      for (const n of nested) visit(n);
    };
    visit(normalizeTypeName(type));
    return out;
  }
}

function example(type) {
  if (type === 'bool') return 'False';
  if (type === 'string' || type === 'wstring') return '';
  if (FLOAT.has(type)) return '0.0';
  return '0';
}

/** A short description of a JSON value, for errors. */
export function describe(v) {
  if (v === null) return 'null';
  if (Array.isArray(v)) return 'an array';
  if (ArrayBuffer.isView(v)) return 'bytes';
  if (typeof v === 'object') return 'an object';
  if (typeof v === 'string') return `the string ${JSON.stringify(v.length > 40 ? `${v.slice(0, 40)}...` : v)}`;
  return `${typeof v === 'bigint' ? 'the integer' : `the ${typeof v}`} ${String(v)}`;
}
