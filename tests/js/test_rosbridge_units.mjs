// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The rosbridge modules without a bus (node --test): WebSocket frames and
// connections against the npm `ws` package, CBOR against npm `cbor-x`,
// JSON with 64-bit integers, the JSON/CBOR forms of messages, capability
// lists. (tests/test_rosbridge_units.py runs this file.)

import assert from 'node:assert/strict';
import http from 'node:http';
import { test } from 'node:test';

import { decode as cborxDecode, encode as cborxEncode } from 'cbor-x';
import { WebSocket } from 'ws';

import { TypeRegistry } from '../../packages/wasm_js/src/cdr.mjs';
import { Capabilities } from '../../packages/wasm_js/src/bridges/rosbridge/capabilities.mjs';
import { CborWriter, decodeCbor, encodeCbor } from '../../packages/wasm_js/src/bridges/rosbridge/cbor.mjs';
import { Converter, fromBase64, toBase64 } from '../../packages/wasm_js/src/bridges/rosbridge/convert.mjs';
import { parseJson, stringifyJson } from '../../packages/wasm_js/src/bridges/rosbridge/json.mjs';
import { acceptWebSocket, NodeWebSocket } from '../../packages/wasm_js/src/bridges/rosbridge/ws_node.mjs';

const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

/** An echo server on 127.0.0.1 with our WebSocket; `oversized` counts skipped messages. */
async function echoServer(maxMessageBytes = 1 << 20) {
  const state = { oversized: [], closes: [] };
  const server = http.createServer();
  server.on('upgrade', (req, socket, head) => {
    const conn = acceptWebSocket(req, socket, head, { maxMessageBytes, onOversize: (n) => { state.oversized.push(n); conn.send('oversize'); } });
    conn.onmessage = (e) => conn.send(e.binary ? new Uint8Array(e.data) : e.data);
    conn.onclose = (e) => state.closes.push(e.code);
  });
  await new Promise((r) => server.listen(0, '127.0.0.1', r));
  state.url = `ws://127.0.0.1:${server.address().port}`;
  state.close = () => new Promise((r) => server.close(r));
  state.server = server;
  return state;
}

function wsClient(url) {
  return new Promise((resolve, reject) => {
    const ws = new WebSocket(url, { perMessageDeflate: false });
    const got = [];
    const waiters = [];
    ws.on('message', (d, binary) => {
      got.push(binary ? new Uint8Array(d) : d.toString());
      while (waiters.length && got.length) waiters.shift()(got.shift());
    });
    ws.on('open', () => resolve({ ws, next: () => (got.length ? Promise.resolve(got.shift()) : new Promise((r) => waiters.push(r))) }));
    ws.on('error', reject);
  });
}

test('the WebSocket server talks to the npm ws client: text, binary, fragments, ping, close', async () => {
  const s = await echoServer();
  const c = await wsClient(s.url);
  c.ws.send('héllo');
  assert.equal(await c.next(), 'héllo');
  const big = new Uint8Array(200000).map((_, i) => i & 0xff);
  c.ws.send(big);
  assert.deepEqual(await c.next(), big);
  c.ws.send('frag', { fin: false });
  c.ws.send('ment', { fin: false });
  c.ws.send('ed', { fin: true });
  assert.equal(await c.next(), 'fragmented');
  const pong = new Promise((r) => c.ws.once('pong', (d) => r(d.toString())));
  c.ws.ping('are you there');
  assert.equal(await pong, 'are you there');
  const closed = new Promise((r) => c.ws.once('close', (code) => r(code)));
  c.ws.close(1000, 'bye');
  assert.equal(await closed, 1000);
  await sleep(50);
  assert.deepEqual(s.closes, [1000]);
  await s.close();
});

test('a message over the limit is skipped and reported; the connection stays', async () => {
  const s = await echoServer(1000);
  const c = await wsClient(s.url);
  c.ws.send('x'.repeat(5000));
  assert.equal(await c.next(), 'oversize');
  c.ws.send('a', { fin: false });
  c.ws.send('b'.repeat(2000), { fin: true }); // over the limit once reassembled
  assert.equal(await c.next(), 'oversize');
  c.ws.send('small');
  assert.equal(await c.next(), 'small');
  assert.deepEqual(s.oversized, [5000, 2001]);
  c.ws.close();
  await s.close();
});

test('the Node.js client (NodeWebSocket) masks, reassembles and reports a refusal', async () => {
  const s = await echoServer();
  const ws = new NodeWebSocket(s.url);
  await new Promise((r) => { ws.onopen = r; });
  const got = [];
  ws.onmessage = (e) => got.push(e.data);
  ws.send('one');
  ws.send(new Uint8Array([1, 2, 3]));
  await sleep(100);
  assert.equal(got[0], 'one');
  assert.deepEqual(new Uint8Array(got[1]), new Uint8Array([1, 2, 3]));
  ws.close(1000);
  await s.close();
  const refusing = http.createServer((req, res) => { res.writeHead(401); res.end('no token'); });
  refusing.on('upgrade', (req, socket) => socket.end('HTTP/1.1 401 Unauthorized\r\nContent-Length: 8\r\nConnection: close\r\n\r\nno token'));
  await new Promise((r) => refusing.listen(0, '127.0.0.1', r));
  const bad = new NodeWebSocket(`ws://127.0.0.1:${refusing.address().port}`);
  const error = await new Promise((r) => { bad.onerror = r; });
  assert.match(error.message, /HTTP 401: no token/);
  await new Promise((r) => refusing.close(r));
});

test('CBOR: what we write cbor-x reads, and what cbor-x writes we read', () => {
  const value = {
    op: 'publish', n: -5, big: 2n ** 62n, neg: -(2n ** 63n), f: 1.5, t: true, nil: null, s: 'ünïcode',
    bytes: new Uint8Array([1, 2, 3]), floats: new Float64Array([0.5, -2]), ints: new Int32Array([1, -1]),
    list: [1, 'a', [2]], nested: { a: { b: 1 } },
  };
  const back = cborxDecode(Buffer.from(encodeCbor(value)));
  assert.equal(back.op, 'publish');
  assert.equal(back.n, -5);
  assert.equal(BigInt(back.big), 2n ** 62n);
  assert.equal(BigInt(back.neg), -(2n ** 63n));
  assert.equal(back.f, 1.5);
  assert.deepEqual([...back.bytes], [1, 2, 3]);
  assert.deepEqual([...back.floats], [0.5, -2]);
  assert.deepEqual([...back.ints], [1, -1]);
  assert.deepEqual(back.list, [1, 'a', [2]]);
  assert.deepEqual(back.nested, { a: { b: 1 } });
  const ours = decodeCbor(new Uint8Array(cborxEncode({ a: [1, 2.25, 'x'], b: new Uint8Array([9]), c: false, d: 1e300 })));
  assert.deepEqual(ours.a, [1, 2.25, 'x']);
  assert.deepEqual([...ours.b], [9]);
  assert.equal(ours.c, false);
  assert.equal(ours.d, 1e300);
  assert.throws(() => decodeCbor(new Uint8Array([0x82, 0x01])), /ends early/);
  const w = new CborWriter(1);
  w.value('grows past its first buffer'.repeat(10));
  assert.equal(decodeCbor(w.result()), 'grows past its first buffer'.repeat(10));
});

test('JSON keeps 64-bit integers', () => {
  const v = parseJson('{"a": 9007199254740993, "b": -9223372036854775808, "c": 1.5, "d": "9007199254740993", "e": [12345678901234567890]}');
  assert.equal(v.a, 9007199254740993n);
  assert.equal(v.b, -9223372036854775808n);
  assert.equal(v.c, 1.5);
  assert.equal(v.d, '9007199254740993');
  assert.equal(v.e[0], 12345678901234567890n);
  assert.equal(stringifyJson({ a: 2n ** 64n - 1n, n: NaN, t: new Uint8Array([1, 2]) }), '{"a":18446744073709551615,"n":null,"t":[1,2]}');
  assert.throws(() => parseJson('{"a": 12345678901234567890,'), /position/);
});

test("messages in rosbridge's JSON and CBOR forms", () => {
  const registry = new TypeRegistry([{
    schema: 1, package: 't',
    messages: {
      't/msg/M': {
        fields: [
          { name: 'data', type: 'uint8', sequence: true }, { name: 'big', type: 'int64' },
          { name: 'x', type: 'float64' }, { name: 'v', type: 'float32', sequence: true },
          { name: 'flag', type: 'bool' }, { name: 'name', type: 'string' },
        ],
        constants: [{ name: 'K', type: 'int32', value: 3 }],
      },
    },
  }]);
  const conv = new Converter(registry);
  const value = { data: new Uint8Array([0, 255, 7]), big: 2n ** 62n + 1n, x: NaN, v: new Float32Array([0.5]), flag: true, name: 'n' };
  const bytes = registry.encode('t/msg/M', value);
  const json = conv.jsonWriter('t/msg/M')(registry.decode('t/msg/M', bytes));
  assert.equal(json, `{"data":"${toBase64(new Uint8Array([0, 255, 7]))}","big":4611686018427387905,"x":null,"v":[0.5],"flag":true,"name":"n"}`);
  const back = conv.fromJson('t/msg/M', parseJson(json));
  assert.deepEqual([...back.data], [0, 255, 7]);
  assert.ok(Number.isNaN(back.x));
  assert.deepEqual(registry.encode('t/msg/M', back), bytes);
  assert.throws(() => conv.fromJson('t/msg/M', { flag: 'yes' }), /field 'flag': expected a boolean/);
  assert.throws(() => conv.fromJson('t/msg/M', { nope: 1 }), /has no field 'nope'/);
  assert.throws(() => conv.fromJson('t/msg/M', { data: '!!' }), /not base64/);
  assert.equal(fromBase64('*'), null);
  const w = new CborWriter();
  conv.cborWriter('t/msg/M')(w, registry.decode('t/msg/M', bytes));
  const c = cborxDecode(Buffer.from(w.result()));
  assert.deepEqual([...c.data], [0, 255, 7]);
  assert.deepEqual([...c.v], [0.5]);
  const td = conv.typedefs('t/msg/M')[0];
  assert.deepEqual(td.fieldtypes, ['uint8', 'int64', 'double', 'float', 'boolean', 'string']);
  assert.deepEqual(td.fieldarraylen, [0, -1, -1, 0, -1, -1]);
  assert.deepEqual([td.constnames, td.constvalues], [['K'], ['3']]);
});

test('capability lists: fnmatch patterns per verb, refusals say what is allowed', () => {
  const caps = new Capabilities({ subscribe: ['/chatter', '/camera/*'], call: ['/rosapi/*'] });
  assert.ok(caps.allows('subscribe', '/camera/image'));
  assert.ok(caps.allows('subscribe', 'chatter'));
  assert.ok(!caps.allows('subscribe', '/secret'));
  assert.ok(!caps.allows('publish', '/chatter'));
  assert.match(caps.refusal('publish', '/chatter'), /grants no 'publish'/);
  assert.match(caps.refusal('subscribe', '/x'), /allows 'subscribe' only for \/chatter, \/camera\/\*/);
  assert.ok(new Capabilities(null).allows('advertise', '/anything'));
  assert.throws(() => new Capabilities({ fly: [] }), /unknown capability 'fly'/);
});
