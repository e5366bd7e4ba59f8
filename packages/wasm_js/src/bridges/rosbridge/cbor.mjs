// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * CBOR (RFC 8949), the subset rosbridge uses: unsigned and negative
 * integers (64-bit exact, as BigInt past 2^53), byte and text strings,
 * arrays, maps with text keys, false/true/null, float32/float64 (float16
 * decoded), and the little-endian typed-array tags of RFC 8746 that
 * rosbridge's `cbor` compression packs numeric arrays with (64-86).
 * Indefinite lengths are decoded, never written.
 *
 * @module bridges/rosbridge/cbor
 */

const enc = new TextEncoder();
const dec = new TextDecoder('utf-8', { fatal: true });

/** RFC 8746 tags of little-endian typed arrays, by constructor name. */
export const TYPED_ARRAY_TAGS = Object.freeze({
  Uint8Array: 64, Uint16Array: 69, Uint32Array: 70, BigUint64Array: 71, Int8Array: 72,
  Int16Array: 77, Int32Array: 78, BigInt64Array: 79, Float32Array: 85, Float64Array: 86,
});
const TAG_ARRAYS = {
  64: Uint8Array, 68: Uint8Array, 69: Uint16Array, 70: Uint32Array, 71: BigUint64Array, 72: Int8Array,
  77: Int16Array, 78: Int32Array, 79: BigInt64Array, 85: Float32Array, 86: Float64Array,
};

/** A growable output buffer with the CBOR item writers. */
export class CborWriter {
  constructor(capacity = 256) {
    this.bytes = new Uint8Array(capacity);
    this.view = new DataView(this.bytes.buffer);
    this.pos = 0;
  }

  _room(n) {
    if (this.pos + n <= this.bytes.length) return;
    let size = this.bytes.length * 2;
    while (size < this.pos + n) size *= 2;
    const bytes = new Uint8Array(size);
    bytes.set(this.bytes.subarray(0, this.pos));
    this.bytes = bytes;
    this.view = new DataView(bytes.buffer);
  }

  /** Major type `major` with argument `n` (a number up to 2^53, or a BigInt). */
  head(major, n) {
    this._room(9);
    const m = major << 5;
    if (typeof n === 'bigint' || n > 0xffffffff) {
      this.bytes[this.pos++] = m | 27;
      this.view.setBigUint64(this.pos, BigInt(n));
      this.pos += 8;
    } else if (n < 24) {
      this.bytes[this.pos++] = m | n;
    } else if (n < 0x100) {
      this.bytes[this.pos++] = m | 24;
      this.bytes[this.pos++] = n;
    } else if (n < 0x10000) {
      this.bytes[this.pos++] = m | 25;
      this.view.setUint16(this.pos, n);
      this.pos += 2;
    } else {
      this.bytes[this.pos++] = m | 26;
      this.view.setUint32(this.pos, n);
      this.pos += 4;
    }
  }

  /** An integer (number or BigInt). */
  int(v) {
    if (typeof v === 'bigint') {
      if (v >= 0n) this.head(0, v);
      else this.head(1, -1n - v);
    } else if (v >= 0) {
      this.head(0, v);
    } else {
      this.head(1, -1 - v);
    }
  }

  float64(v) {
    this._room(9);
    this.bytes[this.pos++] = 0xfb;
    this.view.setFloat64(this.pos, v);
    this.pos += 8;
  }

  /** A number: an integer when it is a safe integer, else a float64. */
  number(v) {
    if (Number.isSafeInteger(v)) this.int(v);
    else this.float64(v);
  }

  bool(v) {
    this._room(1);
    this.bytes[this.pos++] = v ? 0xf5 : 0xf4;
  }

  null() {
    this._room(1);
    this.bytes[this.pos++] = 0xf6;
  }

  string(s) {
    // one byte per UTF-16 unit is the common case; encodeInto needs at most 3
    if (s.length < 24 && /^[\x00-\x7f]*$/.test(s)) {
      this._room(1 + s.length);
      this.bytes[this.pos++] = 0x60 | s.length;
      for (let i = 0; i < s.length; i++) this.bytes[this.pos++] = s.charCodeAt(i);
      return;
    }
    const b = enc.encode(s);
    this.head(3, b.length);
    this.raw(b);
  }

  /** A byte string. */
  byteString(b) {
    this.head(2, b.length);
    this.raw(b);
  }

  raw(b) {
    this._room(b.length);
    this.bytes.set(b, this.pos);
    this.pos += b.length;
  }

  array(n) { this.head(4, n); }

  map(n) { this.head(5, n); }

  tag(n) { this.head(6, n); }

  /** A typed array as its RFC 8746 little-endian tag around a byte string. */
  typedArray(a) {
    const tag = TYPED_ARRAY_TAGS[a.constructor.name];
    if (a instanceof Uint8Array) {
      this.byteString(a);
      return;
    }
    this.tag(tag);
    this.byteString(new Uint8Array(a.buffer, a.byteOffset, a.byteLength));
  }

  /** Any JS value: objects as maps, arrays, typed arrays tagged, BigInt exact. */
  value(v) {
    if (v === null || v === undefined) this.null();
    else if (typeof v === 'boolean') this.bool(v);
    else if (typeof v === 'number') this.number(v);
    else if (typeof v === 'bigint') this.int(v);
    else if (typeof v === 'string') this.string(v);
    else if (ArrayBuffer.isView(v)) this.typedArray(v);
    else if (Array.isArray(v)) {
      this.array(v.length);
      for (const x of v) this.value(x);
    } else if (typeof v === 'object') {
      const keys = Object.keys(v).filter((k) => v[k] !== undefined);
      this.map(keys.length);
      for (const k of keys) {
        this.string(k);
        this.value(v[k]);
      }
    } else {
      throw new TypeError(`CBOR cannot encode a ${typeof v}`);
    }
  }

  /** The bytes written (a copy-free view). */
  result() {
    return this.bytes.subarray(0, this.pos);
  }
}

/** Encode a JS value as CBOR. */
export function encodeCbor(value) {
  const w = new CborWriter();
  w.value(value);
  return w.result();
}

/** Bytes that are not CBOR this decoder reads. */
/** How deep arrays, maps and tags may nest in a decoded item (deeper is a CborError, not a stack overflow). */
const MAX_DEPTH = 256;

export class CborError extends Error {
  constructor(message) {
    super(message);
    this.name = 'CborError';
  }
}

/**
 * Decode one CBOR item: maps become objects, byte strings Uint8Arrays,
 * typed-array tags typed arrays (copied, so aligned), integers numbers or
 * BigInts past 2^53, other tags their content.
 * @param {Uint8Array} bytes
 */
export function decodeCbor(bytes) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  let pos = 0;
  let depth = 0;
  const need = (n) => {
    // a 64-bit length (a BigInt) never fits
    if (typeof n === 'bigint' || pos + n > bytes.length) throw new CborError(`CBOR ends early (at byte ${pos}, ${n} more needed)`);
  };
  const count = (info) => {
    const n = arg(info);
    if (typeof n === 'bigint') throw new CborError(`a CBOR array or map of ${n} items is longer than the message (at byte ${pos})`);
    return n;
  };
  const arg = (info) => {
    if (info < 24) return info;
    if (info === 24) { need(1); return bytes[pos++]; }
    if (info === 25) { need(2); const v = view.getUint16(pos); pos += 2; return v; }
    if (info === 26) { need(4); const v = view.getUint32(pos); pos += 4; return v; }
    if (info === 27) {
      need(8);
      const v = view.getBigUint64(pos);
      pos += 8;
      return v <= BigInt(Number.MAX_SAFE_INTEGER) ? Number(v) : v;
    }
    if (info === 31) return -1;
    throw new CborError(`CBOR additional information ${info} is reserved (at byte ${pos})`);
  };
  const chunks = (major, info) => {
    if (info !== 31) {
      const n = arg(info);
      need(n);
      const b = bytes.subarray(pos, pos + n);
      pos += n;
      return b;
    }
    const parts = [];
    for (;;) {
      need(1);
      if (bytes[pos] === 0xff) { pos++; break; }
      const h = bytes[pos++];
      if (h >> 5 !== major) throw new CborError('an indefinite string holds a chunk of another type');
      parts.push(chunks(major, h & 31));
    }
    const out = new Uint8Array(parts.reduce((n, p) => n + p.length, 0));
    let off = 0;
    for (const p of parts) { out.set(p, off); off += p.length; }
    return out;
  };
  const item = () => {
    need(1);
    if (depth >= MAX_DEPTH) throw new CborError(`CBOR nested deeper than ${MAX_DEPTH} levels (at byte ${pos})`);
    depth++;
    try {
      return itemAt();
    } finally {
      depth--;
    }
  };
  const itemAt = () => {
    const h = bytes[pos++];
    const major = h >> 5;
    const info = h & 31;
    switch (major) {
      case 0: return arg(info);
      case 1: { const n = arg(info); return typeof n === 'bigint' ? -1n - n : -1 - n; }
      case 2: return chunks(2, info).slice();
      case 3: return dec.decode(chunks(3, info));
      case 4: {
        const n = count(info);
        const out = [];
        if (n < 0) { while (bytes[pos] !== 0xff) { out.push(item()); need(1); } pos++; } else for (let i = 0; i < n; i++) out.push(item());
        return out;
      }
      case 5: {
        const n = count(info);
        const out = {};
        const entry = () => {
          const k = item();
          const key = typeof k === 'string' ? k : String(k);
          const v = item();
          // an own property, as JSON.parse makes it: '__proto__' must not set the prototype
          if (key === '__proto__') Object.defineProperty(out, key, { value: v, enumerable: true, writable: true, configurable: true });
          else out[key] = v;
        };
        if (n < 0) { while (bytes[pos] !== 0xff) { entry(); need(1); } pos++; } else for (let i = 0; i < n; i++) entry();
        return out;
      }
      case 6: {
        const tag = arg(info);
        const content = item();
        const Ctor = TAG_ARRAYS[tag];
        if (Ctor && content instanceof Uint8Array) {
          if (content.length % Ctor.BYTES_PER_ELEMENT) throw new CborError(`a typed array of tag ${tag} has ${content.length} bytes, not a multiple of ${Ctor.BYTES_PER_ELEMENT}`);
          return new Ctor(content.buffer.slice(content.byteOffset, content.byteOffset + content.length));
        }
        return content;
      }
      default: {
        if (info === 20) return false;
        if (info === 21) return true;
        if (info === 22 || info === 23) return null;
        if (info === 25) { need(2); const v = halfToFloat(view.getUint16(pos)); pos += 2; return v; }
        if (info === 26) { need(4); const v = view.getFloat32(pos); pos += 4; return v; }
        if (info === 27) { need(8); const v = view.getFloat64(pos); pos += 8; return v; }
        throw new CborError(`CBOR simple value ${info} is not supported (at byte ${pos - 1})`);
      }
    }
  };
  const value = item();
  if (pos !== bytes.length) throw new CborError(`${bytes.length - pos} bytes follow the CBOR item`);
  return value;
}

function halfToFloat(h) {
  const s = h & 0x8000 ? -1 : 1;
  const e = (h >> 10) & 0x1f;
  const f = h & 0x3ff;
  if (e === 0) return s * 2 ** -14 * (f / 1024);
  if (e === 31) return f ? NaN : s * Infinity;
  return s * 2 ** (e - 15) * (1 + f / 1024);
}
