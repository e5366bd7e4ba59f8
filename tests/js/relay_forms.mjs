// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The Node.js server's message forms, for tests/test_relay_units.py to
 * compare with the relay's (colcon_wasm/server/relay_forms.py): reads
 * `{"types": <types.json document>, "cases": [{"type", "json"}], "texts":
 * [...], "cdr": [{"topic", "hex", "timeMs", "ttl"}]}` on stdin and prints
 * one JSON line with, per case, the cbor form (hex) the server makes of the
 * message (fromJson, encode, decode, cborWriter, as topics.mjs does), per
 * text its png (png.mjs), per cdr item the client's CDR publish
 * (client_topics.mjs cdrPublish) in hex.
 */

import { TypeRegistry } from '../../packages/wasm_js/src/cdr.mjs';
import { CborWriter } from '../../packages/wasm_js/src/bridges/rosbridge/cbor.mjs';
import { cdrPublish } from '../../packages/wasm_js/src/bridges/rosbridge/client_topics.mjs';
import { Converter } from '../../packages/wasm_js/src/bridges/rosbridge/convert.mjs';
import { parseJson } from '../../packages/wasm_js/src/bridges/rosbridge/json.mjs';
import { pngEncodeText } from '../../packages/wasm_js/src/bridges/rosbridge/png.mjs';

const chunks = [];
for await (const c of process.stdin) chunks.push(c);
const input = parseJson(Buffer.concat(chunks).toString('utf-8'));
const registry = new TypeRegistry([input.types]);
const conv = new Converter(registry);
const hex = (b) => Buffer.from(b.buffer, b.byteOffset, b.byteLength).toString('hex');
const cbor = input.cases.map(({ type, json }) => {
  const value = registry.decode(type, registry.encode(type, conv.fromJson(type, json)));
  const w = new CborWriter();
  conv.cborWriter(type)(w, value);
  return hex(w.result());
});
const png = input.texts.map((t) => pngEncodeText(t));
const cdr = input.cdr.map(({ topic, hex: h, timeMs, ttl }) => hex(cdrPublish(topic, Buffer.from(h, 'hex'), timeMs, ttl === null ? undefined : ttl)));
process.stdout.write(`${JSON.stringify({ cbor, png, cdr })}\n`);
