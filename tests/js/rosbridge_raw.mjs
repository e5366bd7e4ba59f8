// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * Raw rosbridge requests over the npm `ws` client (third party), for what
 * roslibjs never sends: bad input, a client that stops reading, tokens,
 * capability refusals, oversized messages, 64-bit integers.
 * `node rosbridge_raw.mjs SCENARIO ws://127.0.0.1:PORT [ARG]` prints one
 * JSON line. Every wait is bounded.
 */

import { WebSocket } from 'ws';
import { decode } from 'cbor-x';

const [scenario, url, arg] = process.argv.slice(2);
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

/** A connection that keeps what arrives and waits for messages matching a test. */
function open(target = url, options = {}) {
  return new Promise((resolve, reject) => {
    const ws = new WebSocket(target, options);
    const got = [];
    const waiters = [];
    ws.on('message', (data, binary) => {
      const m = binary ? decode(data) : JSON.parse(data.toString());
      got.push(m);
      for (const w of [...waiters]) if (w.test(m)) { waiters.splice(waiters.indexOf(w), 1); w.resolve(m); }
    });
    ws.on('open', () => resolve({
      ws, got,
      send: (m) => ws.send(typeof m === 'string' ? m : JSON.stringify(m)),
      wait: (test, ms = 10000) => {
        const found = got.find(test);
        if (found) return Promise.resolve(found);
        return new Promise((res, rej) => {
          const w = { test, resolve: res };
          waiters.push(w);
          setTimeout(() => rej(new Error(`timed out after ${ms} ms waiting for a message`)), ms);
        });
      },
    }));
    ws.on('unexpected-response', (req, res) => reject(new Error(`HTTP ${res.statusCode}`)));
    ws.on('error', reject);
  });
}

const BAD = [
  ['malformed', '{"op": "subscribe", "id": "m1", "topic": '],
  ['not an object', '[1, 2, 3]'],
  ['no op', { id: 'n1', topic: '/chatter' }],
  ['unknown op', { op: 'fly', id: 'u1' }],
  ['missing topic', { op: 'subscribe', id: 's1' }],
  ['topic wrong type', { op: 'subscribe', id: 's2', topic: 42 }],
  ['bad throttle', { op: 'subscribe', id: 's3', topic: '/chatter', throttle_rate: 'fast' }],
  ['bad compression', { op: 'subscribe', id: 's4', topic: '/chatter', compression: 'zip' }],
  ['unknown type', { op: 'advertise', id: 'a1', topic: '/x', type: 'no_pkg/msg/Nothing' }],
  ['bad topic name', { op: 'advertise', id: 'a2', topic: '/bad name!', type: 'std_msgs/msg/String' }],
  ['wrong field type', { op: 'publish', id: 'p1', topic: '/chatter', msg: { data: 5 } }],
  ['unknown field', { op: 'publish', id: 'p2', topic: '/chatter', msg: { text: 'x' } }],
  ['missing msg', { op: 'publish', id: 'p3', topic: '/chatter' }],
  ['wrong args', { op: 'call_service', id: 'c1', service: '/add', args: { a: 'two', b: 3 } }],
  ['missing service', { op: 'call_service', id: 'c2' }],
  ['bad level', { op: 'set_level', id: 'l1', level: 'loud' }],
  ['bad fragment', { op: 'fragment', id: 'f1', num: 5, total: 2, data: 'x' }],
  ['unknown action type', { op: 'send_action_goal', id: 'g1', action: '/fibonacci', action_type: 'nope/action/Nope' }],
  ['response without advertise', { op: 'service_response', id: 'r1', service: '/x', result: true }],
];

const scenarios = {
  /** Every bad input gets a status error with the request's id; the connection stays up. */
  async bad() {
    const c = await open();
    const out = [];
    for (const [what, request] of BAD) {
      c.send(request);
      const id = typeof request === 'string' ? (request.match(/"id": "(\w+)"/) || [])[1] : request.id;
      const status = await c.wait((m) => m.op === 'status' && (id === undefined ? !out.some((o) => o.status === m) : m.id === id)).catch((e) => ({ timeout: e.message }));
      out.push({ what, id, status });
    }
    // still up: a rosapi call answers, and a fragmented request is reassembled
    c.send({ op: 'call_service', id: 'after', service: '/rosapi/nodes' });
    const after = await c.wait((m) => m.op === 'service_response' && m.id === 'after');
    const text = JSON.stringify({ op: 'call_service', id: 'fragmented', service: '/rosapi/topics' });
    const parts = [text.slice(0, 20), text.slice(20, 40), text.slice(40)];
    parts.forEach((data, num) => c.send({ op: 'fragment', id: 'frag-1', data, num, total: parts.length }));
    const fragmented = await c.wait((m) => m.op === 'service_response' && m.id === 'fragmented');
    c.ws.close();
    return { out, after: after.result, nodes: after.values.nodes, fragmented: fragmented.result };
  },

  /** int64 keeps its precision both ways (JSON.parse would round these). */
  async int64() {
    const c = await open();
    const a = '9007199254740993';
    c.send(`{"op":"call_service","id":"big","service":"/add","args":{"a":${a},"b":10}}`);
    const m = await new Promise((resolve) => c.ws.once('message', (d) => resolve(d.toString())));
    c.ws.close();
    return { text: m };
  },

  /** A client that stops reading is cut off at its bound; another client keeps receiving. */
  async slow() {
    const slow = await open();
    const fast = await open();
    slow.send({ op: 'subscribe', id: 'slow', topic: '/flood', type: 'std_msgs/msg/String' });
    fast.send({ op: 'subscribe', id: 'fast', topic: '/flood', type: 'std_msgs/msg/String' });
    fast.send({ op: 'advertise', id: 'adv', topic: '/flood', type: 'std_msgs/msg/String' });
    await sleep(500);
    slow.ws._socket.pause(); // stop reading
    let closed = null;
    slow.ws.on('close', (code, reason) => { closed = { code, reason: reason.toString() }; });
    const big = 'y'.repeat(100000);
    const started = Date.now();
    let sent = 0;
    // publish until the server has cut the slow client off (its socket closes), at most 15 s
    while (Date.now() - started < 15000 && sent < 400 && !slow.ws._socket.destroyed) {
      fast.send({ op: 'publish', topic: '/flood', msg: { data: `${sent} ${big}` } });
      sent++;
      if (sent % 10 === 0) await sleep(10);
    }
    for (let i = 0; i < 20 && sent < 50; i++) {
      fast.send({ op: 'publish', topic: '/flood', msg: { data: `${sent++} ${big}` } });
      await sleep(10);
    }
    slow.ws._socket.resume();
    await sleep(1500);
    const received = fast.got.filter((m) => m.op === 'publish').length;
    fast.ws.close();
    return { sent, received, closed: closed || (slow.ws.readyState === WebSocket.CLOSED ? { code: 'closed without code' } : null) };
  },

  /** A token is checked on connect. */
  async token() {
    const attempt = async (target) => {
      try {
        const c = await open(target);
        c.ws.close();
        return 'open';
      } catch (e) {
        return e.message;
      }
    };
    const base = url.replace(/\/$/, '');
    return {
      none: await attempt(base),
      wrong: await attempt(`${base}/?token=wrong`),
      right: await attempt(`${base}/?token=${arg}`),
      header: await (async () => {
        try {
          const c = await open(base, { headers: { Authorization: `Bearer ${arg}` } });
          c.ws.close();
          return 'open';
        } catch (e) {
          return e.message;
        }
      })(),
    };
  },

  /** The capability list refuses with status errors; what it allows works. */
  async capabilities() {
    const c = await open();
    const ask = async (request) => {
      c.send(request);
      return c.wait((m) => m.op === 'status' && m.id === request.id, 3000).then((m) => m.msg, () => null);
    };
    const refused = {
      subscribe: await ask({ op: 'subscribe', id: 'cs1', topic: '/secret', type: 'std_msgs/msg/String' }),
      publish: await ask({ op: 'publish', id: 'cp1', topic: '/chatter', msg: { data: 'x' } }),
      call: await ask({ op: 'call_service', id: 'cc1', service: '/add', args: { a: 1, b: 2 } }),
      advertise: await ask({ op: 'advertise_service', id: 'ca1', service: '/mine', type: 'example_interfaces/srv/AddTwoInts' }),
    };
    c.send({ op: 'subscribe', id: 'ok', topic: '/chatter', type: 'std_msgs/msg/String' });
    const heard = await c.wait((m) => m.op === 'publish' && m.topic === '/chatter');
    c.send({ op: 'call_service', id: 'nodes', service: '/rosapi/nodes' });
    const nodes = await c.wait((m) => m.op === 'service_response' && m.id === 'nodes');
    c.ws.close();
    return { refused, heard: heard.msg.data, rosapi: nodes.result };
  },

  /** A message over --rosbridge-max-message-bytes is dropped with a status error; the connection stays. */
  async oversize() {
    const c = await open();
    c.send({ op: 'publish', id: 'huge', topic: '/chatter', msg: { data: 'z'.repeat(Number(arg) + 10) } });
    const status = await c.wait((m) => m.op === 'status', 5000).catch((e) => ({ timeout: e.message }));
    c.send({ op: 'call_service', id: 'after', service: '/rosapi/nodes' });
    const after = await c.wait((m) => m.op === 'service_response' && m.id === 'after');
    c.ws.close();
    return { status, after: after.result };
  },
};

try {
  const result = await scenarios[scenario]();
  process.stdout.write(`${JSON.stringify({ ok: true, ...result })}\n`);
  process.exit(0);
} catch (e) {
  process.stdout.write(`${JSON.stringify({ ok: false, error: String(e.stack || e) })}\n`);
  process.exit(1);
}
