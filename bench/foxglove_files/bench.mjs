// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The measurements of bench/foxglove, each against its floor in the same run:
 *
 *   node bench.mjs ws://FOXGLOVE_SERVER [--quick]
 *
 * Floor: a plain `ws` server (npm), in a Node.js process of its own as the
 * Foxglove server is, that echoes each binary message: the cost of the
 * WebSocket hops and of the processes' wake-ups alone.
 * (`node bench.mjs --floor-server` runs it and prints its URL.)
 *
 *  - 1 MiB echo: 1 MiB messages (demo_interfaces/msg/Frame, 592x591 rgb8,
 *    CDR by @foxglove/rosmsg2-serialization) published by a FoxgloveClient
 *    (clientPublish, cdr) on /bench/big and received back on the channel
 *    it subscribed to, 4 in flight; the same bytes through the floor;
 *  - meanwhile the 10 Hz /chatter of the demo talker is subscribed too:
 *    the largest gap between two of its messages says whether the big
 *    topic starved it;
 *
 * Prints one JSON line.
 */

const modules = new URL('../../tests/js/node_modules/', import.meta.url);
const { WebSocket, WebSocketServer } = await import(new URL('ws/wrapper.mjs', modules).href);
const { default: wsProtocol } = await import(new URL('@foxglove/ws-protocol/dist/cjs/src/index.js', modules).href);
const { default: rosmsg } = await import(new URL('@foxglove/rosmsg/dist/index.js', modules).href);
const { until } = await import(new URL('../until.mjs', modules).href);
const { default: serialization } = await import(new URL('@foxglove/rosmsg2-serialization/dist/index.js', modules).href);

import { spawn } from 'node:child_process';

const { FoxgloveClient } = wsProtocol;
const [url, ...flags] = process.argv.slice(2);
const quick = flags.includes('--quick');
const N = quick ? 60 : 400;
const IN_FLIGHT = 4;
const WIDTH = 592;
// demo_interfaces/msg/Frame, as the channel advertises it
const FRAME = 'uint32 height\nuint32 width\nstring encoding\nuint8 is_bigendian\nuint32 step\nuint8[] data\n';
const HEIGHT = 591;

function floorServer() {
  return new Promise((resolve) => {
    const child = spawn(process.execPath, [new URL(import.meta.url).pathname, '--floor-server'], { stdio: ['ignore', 'pipe', 'inherit'] });
    child.stdout.once('data', (d) => resolve({ url: String(d).trim(), child }));
  });
}

async function echo(send, onMessage, payloads) {
  let sent = 0;
  let received = 0;
  const t0 = performance.now();
  await new Promise((resolve) => {
    onMessage(() => {
      received++;
      if (received === payloads) resolve();
      else if (sent < payloads) { send(); sent++; }
    });
    for (; sent < IN_FLIGHT; sent++) send();
  });
  const s = (performance.now() - t0) / 1000;
  return { messages: payloads, seconds: s, rate: payloads / s };
}

async function floor(frame) {
  const { url: floorUrl, child } = await floorServer();
  const ws = new WebSocket(floorUrl);
  await new Promise((r) => ws.on('open', r));
  const handlers = [];
  ws.on('message', () => handlers.forEach((h) => h()));
  const r = await echo(() => ws.send(frame), (h) => handlers.push(h), N);
  ws.close();
  child.kill();
  return r;
}

function connect() {
  const ws = new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]);
  const client = new FoxgloveClient({ ws });
  const channels = new Map();
  client.on('advertise', (list) => { for (const c of list) channels.set(c.topic, c); });
  return { ws, client, channels };
}

async function foxglove() {
  const { client, channels } = connect();
  const chatter = await until('/chatter', () => channels.get('/chatter'));
  const writer = new serialization.MessageWriter(rosmsg.parse(FRAME, { ros2: true }));
  const frame = writer.writeMessage({
    height: HEIGHT, width: WIDTH, encoding: 'rgb8', is_bigendian: 0, step: WIDTH * 3,
    data: new Uint8Array(WIDTH * HEIGHT * 3).fill(7),
  });
  const out = client.advertise({ topic: '/bench/big', encoding: 'cdr', schemaName: 'demo_interfaces/msg/Frame' });
  const big = await until('/bench/big', () => channels.get('/bench/big'));
  const subBig = client.subscribe(big.id);
  const subChatter = client.subscribe(chatter.id);
  const handlers = [];
  const chatterTimes = [];
  client.on('message', (m) => {
    if (m.subscriptionId === subBig) handlers.forEach((h) => h());
    else if (m.subscriptionId === subChatter) chatterTimes.push(performance.now());
  });
  await new Promise((r) => setTimeout(r, 300));
  chatterTimes.length = 0;
  const r = await echo(() => client.sendMessage(out, frame), (h) => handlers.push(h), N);
  const gaps = chatterTimes.slice(1).map((t, i) => t - chatterTimes[i]);
  r.chatter = { received: chatterTimes.length, maxGapMs: gaps.length ? Math.max(...gaps) : null };
  client.unsubscribe(subBig);
  client.unsubscribe(subChatter);
  return { r, bytes: frame.byteLength, frame };
}

async function main() {
  const { r: bridge, bytes, frame } = await foxglove();
  const floorResult = await floor(frame);
  console.log(JSON.stringify({ bytes, bridge, floor: floorResult }));
  process.exit(0);
}

if (url === '--floor-server') {
  const server = new WebSocketServer({ host: '127.0.0.1', port: 0, maxPayload: 64 << 20 });
  server.on('connection', (ws) => ws.on('message', (data, binary) => ws.send(data, { binary })));
  server.on('listening', () => console.log(`ws://127.0.0.1:${server.address().port}`));
} else {
  main().catch((e) => { console.error(e.stack); process.exit(1); });
}
