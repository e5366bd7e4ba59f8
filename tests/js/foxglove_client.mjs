// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * Third-party Foxglove clients against `colcon-wasm launch --foxglove`
 * (tests/test_foxglove_*.py): npm `@foxglove/ws-protocol`'s FoxgloveClient
 * over npm `ws`, decoding and encoding with `@foxglove/rosmsg` and
 * `@foxglove/rosmsg2-serialization` from the schemas the server advertises.
 *
 *   node foxglove_client.mjs demo URL      # the demo talker, listener, add_two_ints_server
 *   node foxglove_client.mjs params URL NODE PARAM VALUE [OTHER_NODE...]  # all parameters once every node has them
 *   node foxglove_client.mjs refused URL   # no subprotocol offered
 *   node foxglove_client.mjs clock URL [ROSBRIDGE_URL]  # publishes /clock (through a rosbridge server when given); a second client gets the time
 *   node foxglove_client.mjs slow URL      # a client that stops reading while a big topic floods
 *   node foxglove_client.mjs relay URL     # serve --foxglove: a page's talker, listener, add_two_ints_server, and its graph
 *   node foxglove_client.mjs paramErrors URL NODE PARAM OTHER_PARAM  # bad parameter requests, unsubscribing
 *   node foxglove_client.mjs publish URL TOPIC TYPE JSON  # one message (clientPublish, json)
 *   node foxglove_client.mjs assets URL URI...  # fetchAsset of each URI (request ids 1, 2, ...)
 *
 * Prints one JSON line {ok, ...}; every wait is bounded.
 */

import { createHash } from 'node:crypto';

import rosmsg from '@foxglove/rosmsg';
import serialization from '@foxglove/rosmsg2-serialization';
import wsProtocol from '@foxglove/ws-protocol';
import WebSocket from 'ws';

import { until } from './until.mjs';

// CommonJS packages: their exports through the default import
const { FoxgloveClient } = wsProtocol;
const { parse } = rosmsg;
const { MessageReader, MessageWriter } = serialization;

const [mode, url, ...rest] = process.argv.slice(2);
const done = (result) => {
  console.log(JSON.stringify(result, (k, v) => (typeof v === 'bigint' ? Number(v) : v)));
  process.exit(result.ok ? 0 : 1);
};
setTimeout(() => done({ ok: false, error: `timed out in mode ${mode}` }), 60000).unref();

function connect(protocol = FoxgloveClient.SUPPORTED_SUBPROTOCOL) {
  const ws = new WebSocket(url, [protocol]);
  const client = new FoxgloveClient({ ws });
  const state = { ws, client, channels: new Map(), services: new Map(), status: [], info: null };
  client.on('serverInfo', (m) => { state.info = m; });
  client.on('advertise', (channels) => { for (const c of channels) state.channels.set(c.topic, c); });
  client.on('advertiseServices', (services) => { for (const s of services) state.services.set(s.name, s); });
  client.on('status', (m) => state.status.push(m));
  client.on('error', (e) => state.status.push({ error: String(e && e.message) }));
  return state;
}

const reply = (client, event, match, send, what) => new Promise((resolve, reject) => {
  const timer = setTimeout(() => reject(new Error(`no ${event} for ${what}`)), 10000);
  const on = (m) => {
    if (!match(m)) return;
    clearTimeout(timer);
    client.off(event, on);
    resolve(m);
  };
  client.on(event, on);
  send();
});

async function callService(state, name, request, encoding, callId) {
  const service = await until(`service ${name}`, () => state.services.get(name));
  let data;
  if (encoding === 'cdr') data = new MessageWriter(parse(service.request.schema, { ros2: true })).writeMessage(request);
  else data = new TextEncoder().encode(JSON.stringify(request));
  const r = await reply(state.client, 'serviceCallResponse', (m) => m.callId === callId,
    () => state.client.sendServiceCallRequest({ serviceId: service.id, callId, encoding, data }), name);
  if (r.encoding === 'cdr') return new MessageReader(parse(service.response.schema, { ros2: true })).readMessage(r.data);
  return JSON.parse(new TextDecoder().decode(r.data));
}

async function demo() {
  const state = connect();
  const { client } = state;
  const chatter = await until('the /chatter channel', () => state.channels.get('/chatter'));
  const reader = new MessageReader(parse(chatter.schema, { ros2: true }));
  const heard = [];
  const timestamps = [];
  client.on('message', (m) => {
    heard.push(reader.readMessage(new Uint8Array(m.data.buffer, m.data.byteOffset, m.data.byteLength)));
    timestamps.push(m.timestamp);
  });
  client.subscribe(chatter.id);
  await until('3 messages on /chatter', () => heard.length >= 3);

  // bad input: the connection stays up
  state.ws.send('{"op": "subscribe", bad json');
  state.ws.send(JSON.stringify({ op: 'noSuchOp' }));
  state.ws.send(new Uint8Array([0x7f, 1, 2]));
  await until('three status messages', () => state.status.length >= 3);

  // publish to the C++ listener, in cdr and in json
  const writer = new MessageWriter(parse(chatter.schema, { ros2: true }));
  const cdrId = client.advertise({ topic: '/chatter', encoding: 'cdr', schemaName: 'demo_interfaces/msg/Chatter' });
  const jsonId = client.advertise({ topic: '/chatter', encoding: 'json', schemaName: 'demo_interfaces/msg/Chatter' });
  await new Promise((r) => setTimeout(r, 500));
  for (let i = 0; i < 5; i++) {
    client.sendMessage(cdrId, writer.writeMessage({ data: `from foxglove cdr ${i}`, count: 1000 + i }));
    client.sendMessage(jsonId, new TextEncoder().encode(JSON.stringify({ data: `from foxglove json ${i}`, count: 2000 + i })));
    await new Promise((r) => setTimeout(r, 100));
  }

  const sumCdr = await callService(state, '/add_two_ints', { a: 40n, b: 2n }, 'cdr', 7);
  const sumJson = await callService(state, '/add_two_ints', { a: 5, b: 6 }, 'json', 8);
  const missing = await reply(client, 'serviceCallFailure', (m) => m.callId === 9,
    () => client.sendServiceCallRequest({ serviceId: 9999, callId: 9, encoding: 'cdr', data: new Uint8Array(0) }), 'a missing service');

  const graph = await reply(client, 'connectionGraphUpdate', () => true, () => client.subscribeConnectionGraph(), 'the graph');

  // the other subprotocol
  const sdk = connect('foxglove.sdk.v1');
  await until('serverInfo over foxglove.sdk.v1', () => sdk.info && sdk.channels.get('/chatter'));
  sdk.ws.close();
  done({
    ok: true, info: state.info, channel: { ...chatter, schema: chatter.schema }, heard, timestamps: timestamps.slice(0, 3),
    status: state.status, sumCdr, sumJson, missing, graph, sdkProtocol: sdk.ws.protocol, protocol: state.ws.protocol,
    services: [...state.services.keys()],
  });
}

/** The connection graph a client knows from the updates it got (as Foxglove's Topic Graph keeps it). */
function followGraph(client) {
  const graph = { published: {}, subscribed: {}, services: {}, updates: [] };
  client.on('connectionGraphUpdate', (m) => {
    graph.updates.push(m);
    for (const t of m.publishedTopics) graph.published[t.name] = t.publisherIds;
    for (const t of m.subscribedTopics) graph.subscribed[t.name] = t.subscriberIds;
    for (const t of m.advertisedServices) graph.services[t.name] = t.providerIds;
    for (const name of m.removedTopics) { delete graph.published[name]; delete graph.subscribed[name]; }
    for (const name of m.removedServices) delete graph.services[name];
  });
  client.subscribeConnectionGraph();
  return graph;
}

const copy = (graph) => JSON.parse(JSON.stringify({ published: graph.published, subscribed: graph.subscribed, services: graph.services }));

async function relay() {
  const state = connect();
  const { client } = state;
  await until('serverInfo', () => state.info);
  const chatter = await until('the /chatter channel', () => state.channels.get('/chatter'), 40000);
  // the page's nodes by name, then the listener leaving (the page stops it once it heard us)
  const graph = followGraph(client);
  const has = (list, node) => (list || []).includes(node);
  await until('the page nodes in the connection graph', () => has(graph.published['/chatter'], '/talker')
    && has(graph.subscribed['/chatter'], '/listener') && has(graph.services['/add_two_ints'], '/add_two_ints_server'), 20000);
  const graphBefore = copy(graph);
  const reader = new MessageReader(parse(chatter.schema, { ros2: true }));
  const heard = [];
  client.on('message', (m) => heard.push(reader.readMessage(new Uint8Array(m.data.buffer, m.data.byteOffset, m.data.byteLength))));
  client.subscribe(chatter.id);
  await until('3 messages on /chatter', () => heard.filter((h) => h.data.startsWith('Hello World')).length >= 3, 20000);

  state.ws.send('{"op": "subscribe", bad json');
  state.ws.send(JSON.stringify({ op: 'noSuchOp' }));
  state.ws.send(new Uint8Array([0x7f, 1, 2]));
  await until('three status messages', () => state.status.length >= 3);

  const jsonId = client.advertise({ topic: '/chatter', encoding: 'json', schemaName: 'demo_interfaces/msg/Chatter' });
  const cdrId = client.advertise({ topic: '/chatter', encoding: 'cdr', schemaName: 'demo_interfaces/msg/Chatter' });
  await new Promise((r) => setTimeout(r, 1000));
  for (let i = 0; i < 5; i++) {
    client.sendMessage(jsonId, new TextEncoder().encode(JSON.stringify({ data: `from foxglove json ${i}`, count: 2000 + i })));
    await new Promise((r) => setTimeout(r, 150));
  }
  client.sendMessage(cdrId, new Uint8Array([0, 1, 0, 0]));
  await until('the refusal of cdr', () => state.status.length >= 4);
  await until('the listener leaving the connection graph', () => !has(graph.subscribed['/chatter'], '/listener'), 30000);
  const graphAfter = copy(graph);
  const sumJson = await callService(state, '/add_two_ints', { a: 5, b: 6 }, 'json', 8);
  const service = state.services.get('/add_two_ints');
  const cdrRefused = await reply(client, 'serviceCallFailure', (m) => m.callId === 9,
    () => client.sendServiceCallRequest({ serviceId: service.id, callId: 9, encoding: 'cdr', data: new Uint8Array(4) }), 'a cdr call');
  const missing = await reply(client, 'serviceCallFailure', (m) => m.callId === 10,
    () => client.sendServiceCallRequest({ serviceId: 9999, callId: 10, encoding: 'json', data: new Uint8Array(0) }), 'a missing service');
  const echoed = heard.filter((h) => h.data.startsWith('from foxglove')).map((h) => h.data);
  const sdk = connect('foxglove.sdk.v1');
  await until('serverInfo over foxglove.sdk.v1', () => sdk.info && sdk.channels.get('/chatter'));
  sdk.ws.close();
  // the last call: the page waits for it before it closes
  const last = await callService(state, '/add_two_ints', { a: 4242, b: 1 }, 'json', 11);
  done({
    ok: true, info: state.info, channel: chatter, heard: heard.slice(0, 5), echoed, status: state.status, sumJson,
    cdrRefused, missing, service, sdkProtocol: sdk.ws.protocol, protocol: state.ws.protocol, last,
    graphBefore, graphAfter, firstGraph: graph.updates[0],
  });
}

async function params() {
  const [node, param, value, ...others] = rest;
  const state = connect();
  const { client } = state;
  await until('serverInfo', () => state.info);
  // /parameter_events (nested types: Time, Parameter, ParameterValue), decoded from its schema
  const eventsChannel = await until('the /parameter_events channel', () => state.channels.get('/parameter_events'), 40000);
  const eventReader = new MessageReader(parse(eventsChannel.schema, { ros2: true }));
  const events = [];
  client.on('message', (m) => events.push(eventReader.readMessage(new Uint8Array(m.data.buffer, m.data.byteOffset, m.data.byteLength))));
  client.subscribe(eventsChannel.id);
  await new Promise((r) => setTimeout(r, 300));
  const name = `${node}.${param}`;
  // the nodes' parameter services are on the graph (advertised as services too)
  for (const n of [node, ...others]) await until(`the service ${n}/get_parameters`, () => state.services.get(`${n}/get_parameters`), 40000);
  const all = await reply(client, 'parameterValues', (m) => m.id === 'all', () => client.getParameters([], 'all'), 'all parameters');
  const before = await reply(client, 'parameterValues', (m) => m.id === 'get', () => client.getParameters([name], 'get'), name);
  const updates = [];
  client.on('parameterValues', (m) => { if (m.id === undefined) updates.push(...m.parameters); });
  client.subscribeParameterUpdates([name]);
  await new Promise((r) => setTimeout(r, 500));
  const parsed = JSON.parse(value);
  const after = await reply(client, 'parameterValues', (m) => m.id === 'set',
    () => client.setParameters([{ name, value: parsed }], 'set'), `set ${name}`);
  await until('a parameter update', () => updates.length > 0, 10000).catch(() => null);
  await until('a parameter event', () => events.length > 0, 10000).catch(() => null);
  done({
    events: events.map((e) => ({ node: e.node, stamp: e.stamp, changed: e.changed_parameters })),
    eventsSchema: eventsChannel.schema,
    ok: true, info: state.info, all: all.parameters.map((p) => p.name), before: before.parameters, after: after.parameters,
    updates, status: state.status,
  });
}

/**
 * Bad parameter requests get an error status with their id, and the
 * connection stays; a name unsubscribed from gets no more updates.
 */
async function paramErrors() {
  const [node, param, other] = rest;
  const state = connect();
  const { client } = state;
  await until('serverInfo', () => state.info);
  const values = [];
  client.on('parameterValues', (m) => values.push(m));
  const answer = (id) => until(`parameterValues ${id}`, () => values.find((m) => m.id === id), 10000);
  const statusOf = (id) => until(`a status for ${id}`, () => state.status.find((m) => m.id === id), 10000);
  const name = `${node}.${param}`;
  const otherName = `${node}.${other}`;
  const out = {};
  client.getParameters(['/nobody_here.rate'], 'unknown');
  out.unknown = { status: await statusOf('unknown'), values: await answer('unknown') };
  client.getParameters(['no_dot_here'], 'bad-name');
  out.badName = await statusOf('bad-name');
  client.setParameters([{ name, value: { an: 'object' } }], 'bad-value');
  out.badValue = await statusOf('bad-value');
  client.setParameters([{ name: otherName, value: 'not an integer' }], 'refused');
  out.refused = { status: await statusOf('refused'), values: await answer('refused') };
  state.ws.send(JSON.stringify({ op: 'getParameters', parameterNames: 'not a list', id: 'not-a-list' }));
  out.notAList = await statusOf('not-a-list');
  client.getParameters([name], 'still-up');
  out.stillUp = await answer('still-up');
  // updates: both names watched, then one unsubscribed; set it, then the other: the
  // other's update comes after the first's would have (one node, one /parameter_events)
  const updates = [];
  client.on('parameterValues', (m) => { if (m.id === undefined) updates.push(...m.parameters); });
  client.subscribeParameterUpdates([name, otherName]);
  client.setParameters([{ name, value: 'watched' }], 'set-watched');
  await answer('set-watched');
  await until(`an update of ${name}`, () => updates.some((p) => p.name === name && p.value === 'watched'), 10000);
  client.unsubscribeParameterUpdates([name]);
  client.setParameters([{ name, value: 'not watched' }], 'set-unwatched');
  out.setUnwatched = await answer('set-unwatched');
  client.setParameters([{ name: otherName, value: 250 }], 'set-other');
  await answer('set-other');
  await until(`an update of ${otherName}`, () => updates.some((p) => p.name === otherName), 10000);
  out.updates = updates;
  done({ ok: true, info: state.info, ...out, status: state.status });
}

/** Publish one JSON message on a channel of our own, once the server has greeted us. */
async function publish() {
  const [topic, schemaName, json] = rest;
  const state = connect();
  await until('serverInfo', () => state.info);
  const id = state.client.advertise({ topic, encoding: 'json', schemaName });
  state.client.sendMessage(id, new TextEncoder().encode(json));
  state.ws.close();
  await new Promise((r) => state.ws.on('close', r));
  done({ ok: true, status: state.status });
}

async function refused() {
  const ws = new WebSocket(url);
  const r = await new Promise((resolve) => {
    ws.on('unexpected-response', (req, res) => {
      let body = '';
      res.on('data', (c) => { body += c; });
      res.on('end', () => resolve({ status: res.statusCode, body }));
    });
    ws.on('open', () => resolve({ status: 101 }));
    ws.on('error', () => {});
  });
  done({ ok: true, ...r });
}

/**
 * A FoxgloveClient floods /fox/big (256 KiB messages) while a raw `ws`
 * client subscribed to it and to the 10 Hz /chatter stops reading for a
 * while: the big topic's queue drops, /chatter's does not.
 */
async function slow() {
  const pub = connect();
  const chatterChannel = await until('/chatter', () => pub.channels.get('/chatter'));
  const bigId = pub.client.advertise({ topic: '/fox/big', encoding: 'cdr', schemaName: 'demo_interfaces/msg/Frame' });
  const big = await until('/fox/big', () => pub.channels.get('/fox/big'));
  const frameWriter = new MessageWriter(parse(big.schema, { ros2: true }));
  const frame = frameWriter.writeMessage({ height: 256, width: 341, encoding: 'rgb8', is_bigendian: 0, step: 1023, data: new Uint8Array(256 * 1023) });

  const ws = new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]);
  const got = [];
  const status = [];
  ws.on('message', (data, binary) => {
    if (!binary) {
      const m = JSON.parse(String(data));
      if (m.op === 'status') status.push(m);
      return;
    }
    const view = new DataView(data.buffer, data.byteOffset, data.byteLength);
    got.push({ sub: view.getUint32(1, true), data: new Uint8Array(data.buffer, data.byteOffset + 13, data.byteLength - 13) });
  });
  await new Promise((r) => ws.on('open', r));
  ws.send(JSON.stringify({ op: 'subscribe', subscriptions: [{ id: 1, channelId: big.id }, { id: 2, channelId: chatterChannel.id }] }));
  await new Promise((r) => setTimeout(r, 300));
  ws._socket.pause();
  const SENT = 100;
  for (let i = 0; i < SENT; i++) {
    pub.client.sendMessage(bigId, frame);
    if (i % 10 === 9) await new Promise((r) => setTimeout(r, 5));
  }
  await new Promise((r) => setTimeout(r, 300));
  ws._socket.resume();
  await new Promise((r) => setTimeout(r, 1500));
  const reader = new MessageReader(parse(chatterChannel.schema, { ros2: true }));
  const chatter = got.filter((m) => m.sub === 2).map((m) => reader.readMessage(m.data).count);
  ws.close();
  done({ ok: true, sent: SENT, big: got.filter((m) => m.sub === 1).length, chatter, status });
}

/**
 * Publish rosgraph_msgs/Clock on /clock (json), by clientPublish or, with a
 * rosbridge URL, as a rosbridge v2 client of that server (as a page is of
 * serve's relay); a client connecting then gets 'time' and TIME messages.
 */
async function clock() {
  const pub = connect();
  await until('serverInfo', () => pub.info);
  const [rosbridgeUrl] = rest;
  let send;
  if (rosbridgeUrl) {
    const rb = new WebSocket(rosbridgeUrl);
    await new Promise((resolve, reject) => { rb.on('open', resolve); rb.on('error', reject); });
    rb.send(JSON.stringify({ op: 'advertise', topic: '/clock', type: 'rosgraph_msgs/msg/Clock' }));
    send = (msg) => rb.send(JSON.stringify({ op: 'publish', topic: '/clock', msg }));
  } else {
    const id = pub.client.advertise({ topic: '/clock', encoding: 'json', schemaName: 'rosgraph_msgs/msg/Clock' });
    send = (msg) => pub.client.sendMessage(id, new TextEncoder().encode(JSON.stringify(msg)));
  }
  let sec = 1000;
  const timer = setInterval(() => {
    sec++;
    send({ clock: { sec, nanosec: 500 } });
  }, 50);
  await until('the /clock channel', () => pub.channels.get('/clock'));
  await new Promise((r) => setTimeout(r, 300));
  const late = connect();
  const times = [];
  late.client.on('time', (m) => times.push(m.timestamp));
  await until('time messages', () => times.length >= 3);
  clearInterval(timer);
  done({ ok: true, before: pub.info.capabilities, after: late.info.capabilities, times: times.slice(0, 3).map(String) });
}

/**
 * FoxgloveClient.fetchAsset of each URI, request ids 1, 2, ...; then a
 * fetchAsset without a requestId, which gets a status and no response.
 */
async function assets() {
  const state = connect();
  await until('serverInfo', () => state.info);
  const responses = [];
  for (const [i, uri] of rest.entries()) {
    const requestId = i + 1;
    const r = await reply(state.client, 'fetchAssetResponse', (m) => m.requestId === requestId,
      () => state.client.fetchAsset(uri, requestId), uri);
    responses.push({
      uri, requestId: r.requestId, status: r.status, error: r.error,
      // a digest: a long stdout line may be cut by process.exit
      bytes: r.data ? r.data.byteLength : null,
      sha256: r.data ? createHash('sha256').update(new Uint8Array(r.data.buffer, r.data.byteOffset, r.data.byteLength)).digest('hex') : null,
    });
  }
  state.ws.send(JSON.stringify({ op: 'fetchAsset', uri: rest[0] }));
  await until('a status for a fetchAsset without requestId', () => state.status.length);
  done({ ok: true, capabilities: state.info.capabilities, responses, status: state.status });
}

({ demo, params, paramErrors, publish, refused, slow, clock, relay, assets }[mode] || (() => done({ ok: false, error: `unknown mode ${mode}` })))()
  .catch((e) => done({ ok: false, error: e.stack }));
