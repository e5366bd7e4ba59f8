// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * CDR (XCDR1, little endian) encoding and decoding of ROS messages in JS,
 * byte-identical to Fast CDR 1.x as rosidl_typesupport_fastrtps (Humble)
 * drives it, from the type descriptions that `colcon_wasm/typedesc.py`
 * writes to `share/<pkg>/colcon_wasm/types.json`.
 *
 * Wire format:
 *  - a 4-byte encapsulation header `00 01 00 00` (CDR_LE; `00 00` is
 *    big endian and is decoded too);
 *  - every primitive aligned to its size (8 for 64-bit types), relative to the
 *    first byte after the header; padding bytes are zero;
 *  - bool, byte, char, int8, uint8: 1 byte;
 *  - string: uint32 length including the NUL, the UTF-8 bytes, NUL;
 *  - wstring: uint32 count of UTF-16 code units, each as a uint32 (no NUL);
 *  - sequence: uint32 count, then the elements; array: the elements only;
 *  - nested messages inline, without padding of their own.
 *
 * JS values: numbers, with BigInt for int64/uint64; strings; arrays and
 * sequences of numeric types as typed arrays (Uint8Array, Float64Array,
 * BigInt64Array, ...), of other types as Arrays; messages as plain objects.
 * `encode` also accepts plain arrays, numbers or decimal strings for 64-bit
 * fields and 'NaN'/'Infinity'/'-Infinity' for floats (the JSON forms).
 *
 * Over 500 lines on purpose: one codec. The type registry compiles each
 * type into codecs built from the private Writer, Reader and field codecs
 * here; split across modules, those internals would become exports that
 * nothing else should use.
 */

export const SCHEMA_VERSION = 1;
export const HEADER_BYTES = 4;

const LITTLE_ENDIAN_HOST = new Uint8Array(new Uint16Array([1]).buffer)[0] === 1;
const utf8Encoder = new TextEncoder();
const utf8Decoder = new TextDecoder('utf-8');

/** A value that does not fit its type, or bytes that are not valid CDR. */
export class CdrError extends Error {
  constructor(message) {
    super(message);
    this.name = 'CdrError';
  }
}

// Thrown inside the codecs; encode() turns it into a CdrError naming the type.
class FieldError extends Error {
  constructor(path, what, joiner = ': ') {
    super(what);
    this.path = path;
    this.joiner = joiner;
  }
}

/** A type name that no loaded type description defines. */
export class UnknownTypeError extends Error {
  constructor(message) {
    super(message);
    this.name = 'UnknownTypeError';
  }
}

const INT_RANGES = {
  byte: [0, 255], char: [0, 255], int8: [-128, 127], uint8: [0, 255],
  int16: [-32768, 32767], uint16: [0, 65535],
  int32: [-2147483648, 2147483647], uint32: [0, 4294967295],
};
const BIG_RANGES = {
  int64: [-(2n ** 63n), 2n ** 63n - 1n], uint64: [0n, 2n ** 64n - 1n],
};

// size, DataView setter/getter names, typed array for collections
const PRIMITIVES = {
  bool: { size: 1 },
  byte: { size: 1, set: 'setUint8', get: 'getUint8', array: Uint8Array },
  char: { size: 1, set: 'setUint8', get: 'getUint8', array: Uint8Array },
  int8: { size: 1, set: 'setInt8', get: 'getInt8', array: Int8Array },
  uint8: { size: 1, set: 'setUint8', get: 'getUint8', array: Uint8Array },
  int16: { size: 2, set: 'setInt16', get: 'getInt16', array: Int16Array },
  uint16: { size: 2, set: 'setUint16', get: 'getUint16', array: Uint16Array },
  int32: { size: 4, set: 'setInt32', get: 'getInt32', array: Int32Array },
  uint32: { size: 4, set: 'setUint32', get: 'getUint32', array: Uint32Array },
  int64: { size: 8, set: 'setBigInt64', get: 'getBigInt64', array: BigInt64Array },
  uint64: { size: 8, set: 'setBigUint64', get: 'getBigUint64', array: BigUint64Array },
  float32: { size: 4, set: 'setFloat32', get: 'getFloat32', array: Float32Array },
  float64: { size: 8, set: 'setFloat64', get: 'getFloat64', array: Float64Array },
};

/**
 * Normalise a type name to `pkg/kind/Name`.
 * Accepts `pkg/msg/Name`, `pkg/Name` (a message) and the DDS spelling
 * `pkg::msg::dds_::Name_`.
 */
export function normalizeTypeName(name) {
  if (typeof name !== 'string') {
    throw new UnknownTypeError(`a type name must be a string, not ${typeof name}`);
  }
  let n = name.trim();
  if (n.includes('::')) {
    const parts = n.split('::').filter((p) => p !== 'dds_');
    let last = parts.pop();
    if (last.endsWith('_')) last = last.slice(0, -1);
    n = [...parts, last].join('/');
  }
  const parts = n.split('/');
  if (parts.length === 2) return `${parts[0]}/msg/${parts[1]}`;
  return n;
}

// ---------------------------------------------------------------- writing

class Writer {
  constructor(capacity) {
    this.bytes = new Uint8Array(Math.max(64, capacity));
    this.view = new DataView(this.bytes.buffer);
    this.bytes[1] = 1;  // CDR_LE encapsulation, options 0
    this.pos = HEADER_BYTES;
  }

  reserve(n) {
    const need = this.pos + n;
    if (need <= this.bytes.length) return;
    let size = this.bytes.length * 2;
    while (size < need) size *= 2;
    const bytes = new Uint8Array(size);
    bytes.set(this.bytes.subarray(0, this.pos));
    this.bytes = bytes;
    this.view = new DataView(bytes.buffer);
  }

  // Padding is never written, so it stays zero in the fresh buffer.
  align(n) {
    const pad = (n - ((this.pos - HEADER_BYTES) % n)) % n;
    this.reserve(pad + n);
    this.pos += pad;
  }

  uint32(v) {
    this.align(4);
    this.view.setUint32(this.pos, v, true);
    this.pos += 4;
  }

  raw(bytes) {
    this.reserve(bytes.length);
    this.bytes.set(bytes, this.pos);
    this.pos += bytes.length;
  }

  result() {
    return this.bytes.slice(0, this.pos);
  }
}

// ---------------------------------------------------------------- reading

class Reader {
  constructor(bytes, typeName) {
    if (!(bytes instanceof Uint8Array)) {
      if (ArrayBuffer.isView(bytes)) {
        bytes = new Uint8Array(bytes.buffer, bytes.byteOffset, bytes.byteLength);
      } else if (bytes instanceof ArrayBuffer || bytes instanceof SharedArrayBuffer) {
        bytes = new Uint8Array(bytes);
      } else {
        throw new CdrError(`decoding ${typeName}: expected bytes (Uint8Array), got ${typeof bytes}`);
      }
    }
    if (bytes.length < HEADER_BYTES) {
      throw new CdrError(`decoding ${typeName}: ${bytes.length} bytes is shorter than the 4-byte CDR header`);
    }
    if (bytes[0] !== 0 || bytes[1] > 1) {
      throw new CdrError(`decoding ${typeName}: unsupported encapsulation ${hex(bytes.subarray(0, 2))} (expected 00 01, plain CDR little endian)`);
    }
    this.little = bytes[1] === 1;
    this.bytes = bytes;
    this.view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    this.pos = HEADER_BYTES;
    this.typeName = typeName;
  }

  fail(path, what) {
    return new CdrError(`decoding ${this.typeName}: ${path ? `field '${path}': ` : ''}${what}`);
  }

  need(n, path) {
    if (this.pos + n > this.bytes.length) {
      throw this.fail(path, `the message ends at byte ${this.bytes.length}, but ${n} more bytes are needed at byte ${this.pos}`);
    }
  }

  align(n) {
    this.pos += (n - ((this.pos - HEADER_BYTES) % n)) % n;
  }

  uint32(path) {
    this.align(4);
    this.need(4, path);
    const v = this.view.getUint32(this.pos, this.little);
    this.pos += 4;
    return v;
  }

  count(path, elementBytes) {
    const n = this.uint32(path);
    if (n * elementBytes > this.bytes.length - this.pos) {
      throw this.fail(path, `a count of ${n} elements does not fit in the ${this.bytes.length - this.pos} bytes left`);
    }
    return n;
  }
}

function hex(bytes) {
  return Array.from(bytes, (b) => b.toString(16).padStart(2, '0')).join(' ');
}

// ---------------------------------------------------------------- codecs

function describeValue(v) {
  if (typeof v === 'string') return JSON.stringify(v.length > 40 ? `${v.slice(0, 40)}...` : v);
  if (typeof v === 'bigint') return `${v}n`;
  if (v === null) return 'null';
  if (Array.isArray(v)) return 'an array';
  if (typeof v === 'object') return 'an object';
  return String(v);
}

function scalarCodec(type, where) {
  const p = PRIMITIVES[type];
  if (type === 'bool') {
    return {
      size: 1,
      write(w, v, path) {
        if (v !== true && v !== false && v !== 0 && v !== 1) {
          throw where(path, `${describeValue(v)} is not a bool (true/false)`);
        }
        w.reserve(1);
        w.view.setUint8(w.pos++, v ? 1 : 0);
      },
      read(r, path) {
        r.need(1, path);
        return r.view.getUint8(r.pos++) !== 0;
      },
      zero: () => false,
    };
  }
  const { size, set, get } = p;
  let check;
  let zero;
  if (type in INT_RANGES) {
    const [lo, hi] = INT_RANGES[type];
    check = (v, path) => {
      if (typeof v === 'bigint') v = Number(v);
      if (typeof v !== 'number' || !Number.isInteger(v) || v < lo || v > hi) {
        throw where(path, `${describeValue(v)} is not a ${type} (an integer from ${lo} to ${hi})`);
      }
      return v;
    };
    zero = () => 0;
  } else if (type in BIG_RANGES) {
    const [lo, hi] = BIG_RANGES[type];
    check = (v, path) => {
      let b;
      try {
        if (typeof v === 'bigint') b = v;
        else if (typeof v === 'number' && Number.isSafeInteger(v)) b = BigInt(v);
        else if (typeof v === 'string' && /^\s*-?\d+\s*$/.test(v)) b = BigInt(v.trim());
      } catch (e) { b = undefined; }
      if (b === undefined || b < lo || b > hi) {
        throw where(path, `${describeValue(v)} is not a ${type} (an integer from ${lo} to ${hi}; use a BigInt or a decimal string beyond 2^53)`);
      }
      return b;
    };
    zero = () => 0n;
  } else {
    check = (v, path) => {
      if (typeof v === 'number') return v;
      if (v === 'NaN') return NaN;
      if (v === 'Infinity') return Infinity;
      if (v === '-Infinity') return -Infinity;
      throw where(path, `${describeValue(v)} is not a ${type} (a number)`);
    };
    zero = () => 0;
  }
  return {
    size,
    check,
    write(w, v, path) {
      v = check(v, path);
      w.align(size);
      w.view[set](w.pos, v, true);
      w.pos += size;
    },
    read(r, path) {
      r.align(size);
      r.need(size, path);
      const v = r.view[get](r.pos, r.little);
      r.pos += size;
      return v;
    },
    zero,
  };
}

function stringCodec(bound, where) {
  return {
    size: 4,
    write(w, v, path) {
      if (typeof v !== 'string') throw where(path, `${describeValue(v)} is not a string`);
      const bytes = utf8Encoder.encode(v);
      if (bound !== undefined && bytes.length > bound) {
        throw where(path, `the string has ${bytes.length} bytes, more than its bound of ${bound}`);
      }
      if (bytes.includes(0)) throw where(path, 'a string cannot contain a NUL character');
      w.uint32(bytes.length + 1);
      w.reserve(bytes.length + 1);
      w.bytes.set(bytes, w.pos);
      w.pos += bytes.length + 1;
    },
    read(r, path) {
      const n = r.count(path, 1);
      if (n === 0) return '';
      // as the encoder: what the type bounds is refused, not passed on
      if (bound !== undefined && n - 1 > bound) throw r.fail(path, `the string has ${n - 1} bytes, more than its bound of ${bound}`);
      const end = r.pos + n - 1;
      if (r.bytes[end] !== 0) throw r.fail(path, `a string of length ${n} does not end with NUL`);
      const s = utf8Decoder.decode(r.bytes.subarray(r.pos, end));
      r.pos += n;
      return s;
    },
    zero: () => '',
  };
}

function wstringCodec(bound, where) {
  return {
    size: 4,
    write(w, v, path) {
      if (typeof v !== 'string') throw where(path, `${describeValue(v)} is not a string`);
      if (bound !== undefined && v.length > bound) {
        throw where(path, `the wstring has ${v.length} characters, more than its bound of ${bound}`);
      }
      w.uint32(v.length);
      w.reserve(4 * v.length);
      for (let i = 0; i < v.length; i++) {
        w.view.setUint32(w.pos, v.charCodeAt(i), true);
        w.pos += 4;
      }
    },
    read(r, path) {
      const n = r.count(path, 4);
      if (bound !== undefined && n > bound) throw r.fail(path, `the wstring has ${n} characters, more than its bound of ${bound}`);
      const units = new Array(n);
      for (let i = 0; i < n; i++) {
        units[i] = r.view.getUint32(r.pos, r.little) & 0xffff;
        r.pos += 4;
      }
      let s = '';
      for (let i = 0; i < n; i += 4096) s += String.fromCharCode.apply(null, units.slice(i, i + 4096));
      return s;
    },
    zero: () => '',
  };
}

function isNumericPrimitive(type) {
  return type in PRIMITIVES && type !== 'bool';
}

function collectionCodec(field, element, where) {
  const fixed = field.array_size;
  const bound = field.sequence_bound;
  const TypedArray = isNumericPrimitive(field.type) ? PRIMITIVES[field.type].array : null;
  const esize = element.size;
  const label = fixed !== undefined ? `an array of ${fixed}` : (bound !== undefined ? `a sequence of at most ${bound}` : 'a sequence');
  return {
    write(w, v, path) {
      if (!Array.isArray(v) && !(ArrayBuffer.isView(v) && !(v instanceof DataView))) {
        throw where(path, `${describeValue(v)} is not ${label} ${field.type} values (an array)`);
      }
      const n = v.length;
      if (fixed !== undefined && n !== fixed) {
        throw where(path, `has ${n} elements, the array needs exactly ${fixed}`);
      }
      if (bound !== undefined && n > bound) {
        throw where(path, `has ${n} elements, more than the sequence bound of ${bound}`);
      }
      if (fixed === undefined) w.uint32(n);
      if (n === 0) return;
      if (TypedArray && v instanceof TypedArray && (LITTLE_ENDIAN_HOST || esize === 1)) {
        w.align(esize);
        w.raw(new Uint8Array(v.buffer, v.byteOffset, v.byteLength));
        return;
      }
      for (let i = 0; i < n; i++) element.write(w, v[i], `${path}[${i}]`);
    },
    read(r, path) {
      const n = fixed !== undefined ? fixed : r.count(path, esize);
      if (bound !== undefined && n > bound) throw r.fail(path, `has ${n} elements, more than the sequence bound of ${bound}`);
      if (TypedArray) {
        if (n === 0) return new TypedArray(0);
        r.align(esize);
        r.need(n * esize, path);
        if (LITTLE_ENDIAN_HOST && r.little) {
          const start = r.bytes.byteOffset + r.pos;
          const out = new TypedArray(r.bytes.buffer.slice(start, start + n * esize));
          r.pos += n * esize;
          return out;
        }
        const out = new TypedArray(n);
        for (let i = 0; i < n; i++) out[i] = element.read(r, path);
        return out;
      }
      const out = new Array(n);
      for (let i = 0; i < n; i++) out[i] = element.read(r, `${path}[${i}]`);
      return out;
    },
    zero() {
      if (fixed === undefined) return TypedArray ? new TypedArray(0) : [];
      if (TypedArray) return new TypedArray(fixed);
      return Array.from({ length: fixed }, () => element.zero());
    },
  };
}

function convertDefault(field, value) {
  const one = (v) => {
    if (field.type === 'int64' || field.type === 'uint64') return BigInt(v);
    if (v === 'NaN') return NaN;
    if (v === 'Infinity') return Infinity;
    if (v === '-Infinity') return -Infinity;
    return v;
  };
  if (!Array.isArray(value)) return one(value);
  const TypedArray = isNumericPrimitive(field.type) ? PRIMITIVES[field.type].array : null;
  const items = value.map(one);
  return TypedArray ? TypedArray.from(items) : items;
}

function cloneDefault(v) {
  if (Array.isArray(v)) return v.slice();
  if (ArrayBuffer.isView(v)) return v.slice();
  return v;
}

// ---------------------------------------------------------------- registry

/**
 * The type descriptions of an install space: load each package's types.json
 * with `add`, then encode and decode messages by type name.
 */
export class TypeRegistry {
  constructor(documents = []) {
    this.messages = new Map();
    this.services = new Map();
    this.actions = new Map();
    this.codecs = new Map();
    this.packages = [];
    for (const d of documents) this.add(d);
  }

  /** Fetch types.json documents (browser or Node 20 fetch) and add them. */
  static async fetch(urls) {
    const docs = await Promise.all(urls.map(async (url) => {
      const res = await fetch(url);
      if (!res.ok) throw new Error(`loading type descriptions ${url}: HTTP ${res.status}`);
      return res.json();
    }));
    return new TypeRegistry(docs);
  }

  /** Add one package's types.json document. */
  add(doc) {
    if (!doc || doc.schema !== SCHEMA_VERSION) {
      throw new Error(`type descriptions of ${doc && doc.package}: schema ${doc && doc.schema} is not supported (expected ${SCHEMA_VERSION}); rebuild with this colcon-wasm`);
    }
    for (const [name, m] of Object.entries(doc.messages || {})) this.messages.set(name, m);
    for (const [name, s] of Object.entries(doc.services || {})) this.services.set(name, s);
    for (const [name, a] of Object.entries(doc.actions || {})) this.actions.set(name, a);
    this.packages.push(doc.package);
    this.codecs.clear();
    return this;
  }

  /** True when the message type is known. */
  has(name) {
    return this.messages.has(normalizeTypeName(name));
  }

  /** The description of a message type: {fields, constants}. */
  message(name) {
    const full = normalizeTypeName(name);
    const m = this.messages.get(full);
    if (!m) throw this.unknown('message', name, full);
    return m;
  }

  /**
   * The service entry {request, response} of a service type; also of an
   * action's own services, as rcl_action names them (`pkg/action/X_SendGoal`,
   * `pkg/action/X_GetResult`).
   */
  service(name) {
    const full = normalizeTypeName(name).replace('/msg/', '/srv/');
    const s = this.services.get(full) || this.actionService(full);
    if (!s) throw this.unknown('service', name, full);
    return s;
  }

  /** The send_goal or get_result entry of `pkg/action/X_SendGoal` or `_GetResult`, or undefined. */
  actionService(full) {
    const m = /^(.+\/action\/.+)_(SendGoal|GetResult)$/.exec(full);
    const a = m ? this.actions.get(m[1]) : undefined;
    if (!a) return undefined;
    return m[2] === 'SendGoal' ? a.send_goal : a.get_result;
  }

  /** The action entry of an action type. */
  action(name) {
    const full = normalizeTypeName(name).replace('/msg/', '/action/');
    const a = this.actions.get(full);
    if (!a) throw this.unknown('action', name, full);
    return a;
  }

  unknown(kind, name, full) {
    const pkg = full.split('/')[0];
    const hint = this.packages.includes(pkg)
      ? `package '${pkg}' has type descriptions, but not this ${kind}`
      : `no types.json of package '${pkg}' is loaded: build '${pkg}' with colcon build --wasm into this install space`;
    return new UnknownTypeError(`unknown ${kind} type '${name}': ${hint}`);
  }

  /** The compiled codec of a message type: {encode(value), decode(bytes), create()}. */
  codec(name) {
    const full = normalizeTypeName(name);
    let c = this.codecs.get(full);
    if (!c) {
      c = this.compile(full, []);
      this.codecs.set(full, c);
    }
    return c.api;
  }

  compile(full, stack) {
    const cached = this.codecs.get(full);
    if (cached) return cached;
    if (stack.includes(full)) {
      throw new Error(`type ${full} contains itself (${[...stack, full].join(' -> ')})`);
    }
    const description = this.message(full);
    const where = (path, what) => new FieldError(path, what);
    const fields = description.fields.map((field) => {
      let element;
      if (field.type === 'string') element = stringCodec(field.string_bound, where);
      else if (field.type === 'wstring') element = wstringCodec(field.string_bound, where);
      else if (field.type in PRIMITIVES) element = scalarCodec(field.type, where);
      else element = this.compile(normalizeTypeName(field.type), [...stack, full]).element;
      const codec = (field.array_size !== undefined || field.sequence)
        ? collectionCodec(field, element, where) : element;
      const hasDefault = Object.prototype.hasOwnProperty.call(field, 'default');
      const def = hasDefault ? convertDefault(field, field.default) : undefined;
      return {
        name: field.name,
        codec,
        initial: hasDefault ? () => cloneDefault(def) : codec.zero,
      };
    });
    const names = new Set(fields.map((f) => f.name));
    const create = () => {
      const o = {};
      for (const f of fields) o[f.name] = f.initial();
      return o;
    };
    const element = {
      size: 1,
      write(w, v, path) {
        if (v === null || typeof v !== 'object' || Array.isArray(v)) {
          throw new FieldError(path, `${describeValue(v)} is not a ${full} message (an object)`);
        }
        for (const key of Object.keys(v)) {
          if (!names.has(key)) {
            throw new FieldError(path, `no field '${key}' (fields: ${[...names].join(', ')})`, ' has ');
          }
        }
        for (const f of fields) {
          const p = path ? `${path}.${f.name}` : f.name;
          const value = v[f.name];
          f.codec.write(w, value === undefined ? f.initial() : value, p);
        }
      },
      read(r, path) {
        const o = {};
        for (const f of fields) o[f.name] = f.codec.read(r, path ? `${path}.${f.name}` : f.name);
        return o;
      },
      zero: create,
    };
    let lastSize = 64;
    const api = {
      type: full,
      description,
      encode(value) {
        const w = new Writer(lastSize);
        try {
          element.write(w, value, '');
        } catch (e) {
          if (!(e instanceof FieldError)) throw e;
          const where = e.path ? `field '${e.path}'${e.joiner}` : '';
          throw new CdrError(`encoding ${full}: ${where}${e.message}`);
        }
        lastSize = w.pos;
        return w.result();
      },
      decode(bytes) {
        const r = new Reader(bytes, full);
        const v = element.read(r, '');
        return v;
      },
      create,
    };
    const compiled = { element, api };
    this.codecs.set(full, compiled);
    return compiled;
  }

  /** Encode a message value as CDR with its 4-byte header. */
  encode(type, value) {
    return this.codec(type).encode(value);
  }

  /** Decode CDR bytes (with header) into a message value. */
  decode(type, bytes) {
    return this.codec(type).decode(bytes);
  }

  /** A new message value with every field at its default. */
  create(type) {
    return this.codec(type).create();
  }
}

/**
 * A JSON-safe copy of a decoded value: typed arrays become arrays, BigInts
 * numbers when safe and decimal strings otherwise (always strings with
 * `{bigint: 'string'}`), non-finite floats the strings 'NaN', 'Infinity',
 * '-Infinity'.
 */
export function toPlain(value, options = {}) {
  const bigAsString = options.bigint === 'string';
  const convert = (v) => {
    if (typeof v === 'bigint') {
      if (!bigAsString && v >= MIN_SAFE && v <= MAX_SAFE) return Number(v);
      return v.toString();
    }
    if (typeof v === 'number') {
      if (Number.isFinite(v)) return v;
      return Number.isNaN(v) ? 'NaN' : (v > 0 ? 'Infinity' : '-Infinity');
    }
    if (ArrayBuffer.isView(v)) return Array.from(v, convert);
    if (Array.isArray(v)) return v.map(convert);
    if (v && typeof v === 'object') {
      const o = {};
      for (const k of Object.keys(v)) o[k] = convert(v[k]);
      return o;
    }
    return v;
  };
  return convert(value);
}

const MIN_SAFE = BigInt(Number.MIN_SAFE_INTEGER);
const MAX_SAFE = BigInt(Number.MAX_SAFE_INTEGER);

/** Lower-case hex of bytes, for logs and tests. */
export function toHex(bytes) {
  return Array.from(bytes, (b) => b.toString(16).padStart(2, '0')).join('');
}
