// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The measurements of bench/bridge, each against its floor in the same run:
 *
 *   node bench.mjs ws://BRIDGE [--quick]
 *
 * Floor: a plain `ws` server (npm), in a Node.js process of its own as the
 * bridge is, that forwards each message of one client to the others
 * unchanged and answers call_service with a fixed service_response: the
 * cost of the WebSocket hops and of the processes' wake-ups alone.
 * (`node bench.mjs --floor-server` runs it and prints its URL.)
 *
 *  - small messages: a roslibjs publisher -> server -> a roslibjs
 *    subscriber (std_msgs/String, 32 chars); msg/s with the publisher
 *    going as fast as it can (20 000 messages), and one-way latency p50/p99
 *    at 1 000 msg/s (both clients in this process, one clock);
 *  - images: 640x480 rgb8 sensor_msgs/Image sent as CBOR (the serialized
 *    message, cbor-raw's form) and received by a roslibjs subscriber with
 *    compression cbor-raw, 4 in flight;
 *  - service calls: roslibjs calls of /add (example_interfaces/AddTwoInts,
 *    the C++ probe add_server behind the bridge), 8 in flight.
 *
 * Prints one JSON line.
 */

// the npm packages of the tests (tests/js/node_modules: npm ci there)
const modules = new URL('../../tests/js/node_modules/', import.meta.url);
const ROSLIB = await import(new URL('roslib/dist/RosLib.js', modules).href);
const { WebSocket, WebSocketServer } = await import(new URL('ws/wrapper.mjs', modules).href);
const { encode: cborEncode } = await import(new URL('cbor-x/node-index.js', modules).href);

import { spawn } from 'node:child_process';

const [bridgeUrl, ...flags] = process.argv.slice(2);
const quick = flags.includes('--quick');
const N_SMALL = quick ? 3000 : 20000;
const N_LATENCY = quick ? 500 : 2000;
const N_IMAGES = quick ? 60 : 300;
const CALL_MS = quick ? 1000 : 3000;
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
const now = () => performance.now();

function percentile(values, p) {
  const s = [...values].sort((a, b) => a - b);
  return s.length ? s[Math.min(s.length - 1, Math.floor(p * s.length))] : NaN;
}

/** The floor: forwards every message to the other clients; answers calls. */
function floorServer() {
  return new Promise((resolve) => {
    const wss = new WebSocketServer({ host: '127.0.0.1', port: 0, perMessageDeflate: false });
    wss.on('connection', (ws) => {
      ws.on('message', (data, binary) => {
        if (!binary && data.length < 512) {
          const text = data.toString();
          if (text.includes('"call_service"')) {
            const m = JSON.parse(text);
            ws.send(JSON.stringify({ op: 'service_response', service: m.service, values: { sum: m.args.a + m.args.b }, result: true, id: m.id }));
            return;
          }
          if (!text.includes('"publish"')) return; // advertise, subscribe: nothing to do
        }
        for (const other of wss.clients) if (other !== ws && other.readyState === 1) other.send(data, { binary });
      });
    });
    wss.on('listening', () => resolve({ url: `ws://127.0.0.1:${wss.address().port}`, close: () => wss.close() }));
  });
}

async function ros(url) {
  const r = new ROSLIB.Ros({ url });
  await new Promise((resolve, reject) => { r.on('connection', resolve); r.on('error', reject); });
  return r;
}

/** Small messages: throughput and latency, roslibjs to roslibjs. */
async function small(url) {
  const a = await ros(url);
  const b = await ros(url);
  const topic = '/bench/small';
  const sub = new ROSLIB.Topic({ ros: b, name: topic, messageType: 'std_msgs/msg/String', queue_length: 0 });
  const pub = new ROSLIB.Topic({ ros: a, name: topic, messageType: 'std_msgs/msg/String', queue_size: 1000 });
  let received = 0;
  let first = 0;
  let last = 0;
  const latencies = [];
  let mode = 'warm';
  sub.subscribe((m) => {
    const t = now();
    if (mode === 'latency') latencies.push(t - Number(m.data.slice(0, 20)));
    else if (mode === 'rate') {
      if (!received) first = t;
      received++;
      last = t;
    }
  });
  pub.advertise();
  await sleep(500);
  const pad = 'x'.repeat(12);
  for (let i = 0; i < 50; i++) { pub.publish({ data: `${now().toFixed(6).padStart(20, '0')}${pad}` }); await sleep(2); }
  await sleep(300);
  mode = 'latency';
  for (let i = 0; i < N_LATENCY; i++) {
    pub.publish({ data: `${now().toFixed(6).padStart(20, '0')}${pad}` });
    await sleep(1);
  }
  await sleep(500);
  mode = 'rate';
  for (let i = 0; i < N_SMALL; i++) {
    pub.publish({ data: `${'0'.padStart(20, '0')}${pad}` });
    if (i % 200 === 199) await sleep(0); // let the socket write
  }
  const deadline = Date.now() + 20000;
  let seen = -1;
  while (Date.now() < deadline && received < N_SMALL && received !== seen) { seen = received; await sleep(300); }
  a.close();
  b.close();
  return {
    rate: received > 1 ? (received - 1) / ((last - first) / 1000) : 0, received, sent: N_SMALL,
    p50: percentile(latencies, 0.5), p99: percentile(latencies, 0.99), latencySamples: latencies.length,
  };
}

/** The CDR of a 640x480 rgb8 sensor_msgs/Image (what a camera driver publishes). */
function imageCdr(n) {
  const w = 640;
  const h = 480;
  const frame = 'camera';
  const enc = 'rgb8';
  const size = 4 + 8 + 4 + frame.length + 1 + 3 + 8 + 4 + enc.length + 1 + 3 + 8 + w * h * 3;
  const out = new Uint8Array(size);
  const v = new DataView(out.buffer);
  let o = 0;
  out.set([0, 1, 0, 0]); o = 4;
  const align = (k) => { o = 4 + Math.ceil((o - 4) / k) * k; };
  v.setInt32(o, n, true); v.setUint32(o + 4, 0, true); o += 8;
  v.setUint32(o, frame.length + 1, true); o += 4; out.set(Buffer.from(frame), o); o += frame.length + 1;
  align(4); v.setUint32(o, h, true); v.setUint32(o + 4, w, true); o += 8;
  v.setUint32(o, enc.length + 1, true); o += 4; out.set(Buffer.from(enc), o); o += enc.length + 1;
  out[o++] = 0; // is_bigendian
  align(4); v.setUint32(o, w * 3, true); o += 4;
  v.setUint32(o, w * h * 3, true); o += 4;
  out.fill(0x5a, o, o + w * h * 3);
  o += w * h * 3;
  return out.subarray(0, o);
}

/** Images: CBOR publish in, cbor-raw out to roslibjs; `inFlight` images outstanding. */
async function images(url, inFlight = 4) {
  const b = await ros(url);
  const topic = '/bench/image';
  const sub = new ROSLIB.Topic({ ros: b, name: topic, messageType: 'sensor_msgs/msg/Image', compression: 'cbor-raw' });
  const pub = new WebSocket(url, { perMessageDeflate: false });
  await new Promise((r) => pub.on('open', r));
  pub.send(JSON.stringify({ op: 'advertise', topic, type: 'sensor_msgs/msg/Image' }));
  let received = 0;
  let bytes = 0;
  let first = 0;
  let last = 0;
  let wake = null;
  sub.subscribe((m) => {
    const t = now();
    if (!received) first = t;
    received++;
    bytes = m.bytes.length;
    last = t;
    if (wake) wake();
  });
  await sleep(500);
  const frames = [0, 1].map((i) => cborEncode({ op: 'publish', topic, msg: { bytes: imageCdr(i) } }));
  let sent = 0;
  const deadline = Date.now() + 60000;
  while (received < N_IMAGES && Date.now() < deadline) {
    while (sent - received < inFlight && sent < N_IMAGES + inFlight) pub.send(frames[sent++ % 2]);
    await new Promise((r) => { wake = r; setTimeout(r, 1000); });
    wake = null;
  }
  pub.close();
  b.close();
  return { rate: received > 1 ? (received - 1) / ((last - first) / 1000) : 0, received, bytes };
}

/** Service calls/s with `inFlight` outstanding. */
async function calls(url, inFlight = 8) {
  const a = await ros(url);
  const add = new ROSLIB.Service({ ros: a, name: '/add', serviceType: 'example_interfaces/srv/AddTwoInts' });
  await new Promise((r, j) => add.callService({ a: 1, b: 2 }, r, j));
  let done = 0;
  const end = now() + CALL_MS;
  const worker = async () => {
    while (now() < end) {
      await new Promise((r, j) => add.callService({ a: done, b: 1 }, r, j));
      done++;
    }
  };
  const t0 = now();
  await Promise.all(Array.from({ length: inFlight }, worker));
  const s = (now() - t0) / 1000;
  a.close();
  return { rate: done / s, calls: done };
}

if (bridgeUrl === '--floor-server') {
  const server = await floorServer();
  process.stdout.write(`${server.url}\n`);
  await new Promise(() => {}); // until killed
}

/** The floor server in its own process. */
function floorProcess() {
  const child = spawn(process.execPath, [new URL(import.meta.url).pathname, '--floor-server'], { stdio: ['ignore', 'pipe', 'inherit'] });
  return new Promise((resolve) => {
    child.stdout.once('data', (d) => resolve({ url: String(d).trim(), close: () => child.kill() }));
  });
}

const floor = await floorProcess();
const out = { quick, floor: {}, bridge: {} };
for (const [name, url] of [['floor', floor.url], ['bridge', bridgeUrl]]) {
  out[name].small = await small(url);
  out[name].images = await images(url);
  out[name].calls = await calls(url);
}
floor.close();
process.stdout.write(`${JSON.stringify(out)}\n`);
process.exit(0);
