// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * roslibjs (npm `roslib`, the third-party client) against a rosbridge
 * server: `node rosbridge_roslib.mjs SCENARIO ws://127.0.0.1:PORT` runs one
 * scenario and prints one JSON line with what it saw, for
 * tests/test_rosbridge_server.py to assert. Every wait is bounded.
 */

import * as ROSLIB from 'roslib';

const [scenario, url] = process.argv.slice(2);
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
const within = (ms, what, promise) => Promise.race([promise, sleep(ms).then(() => { throw new Error(`timed out after ${ms} ms: ${what}`); })]);

async function connect() {
  const ros = new ROSLIB.Ros({ url });
  await within(10000, `connecting to ${url}`, new Promise((resolve, reject) => {
    ros.on('connection', resolve);
    ros.on('error', (e) => reject(new Error(`cannot connect: ${e.message || e}`)));
  }));
  return ros;
}

const cb = (fn) => new Promise((resolve, reject) => fn(resolve, (e) => reject(new Error(String(e)))));

function collect(ros, options, count, ms) {
  const topic = new ROSLIB.Topic({ ros, ...options });
  const got = [];
  return within(ms, `${count} messages of ${options.name}`, new Promise((resolve) => {
    topic.subscribe((m) => {
      got.push(m);
      if (got.length === count) {
        topic.unsubscribe();
        resolve(got);
      }
    });
  }));
}

const scenarios = {
  /** Wait (up to 60 s) until the server lists a topic (argv: TOPIC): the nodes behind it are up. */
  async ready() {
    // a topic, and optionally a node and a service, listed by rosapi
    const [topic, node, service] = process.argv.slice(4);
    const ros = await connect();
    const deadline = Date.now() + 60000;
    for (;;) {
      const { topics } = await cb((ok, fail) => ros.getTopics(ok, fail));
      const nodes = node ? await cb((ok, fail) => ros.getNodes(ok, fail)) : [];
      const services = service ? await cb((ok, fail) => ros.getServices(ok, fail)) : [];
      if (topics.includes(topic) && (!node || nodes.includes(node)) && (!service || services.includes(service))) break;
      if (Date.now() > deadline) {
        throw new Error(`${topic}, ${node}, ${service} were not all listed within 60 s (topics: ${topics.join(', ')}; `
          + `nodes: ${nodes.join(', ')}; services: ${services.join(', ')})`);
      }
      await sleep(250);
    }
    ros.close();
    return { topic };
  },

  /** rosapi, typed fields of a C++ publisher, publishing into a C++ listener, calling a C++ service. */
  async basic() {
    const ros = await connect();
    const topics = await cb((ok, fail) => ros.getTopics(ok, fail));
    const nodes = await cb((ok, fail) => ros.getNodes(ok, fail));
    const services = await cb((ok, fail) => ros.getServices(ok, fail));
    const topicType = await cb((ok, fail) => ros.getTopicType('/chatter', ok, fail));
    const details = await cb((ok, fail) => ros.getMessageDetails('sensor_msgs/msg/Image', ok, fail));
    const raw = await cb((ok, fail) => ros.getTopicsAndRawTypes(ok, fail));
    const heard = await collect(ros, { name: '/chatter', messageType: 'std_msgs/msg/String' }, 3, 10000);
    const out = new ROSLIB.Topic({ ros, name: '/chatter', messageType: 'std_msgs/msg/String' });
    for (let i = 0; i < 20; i++) {
      out.publish({ data: `from roslibjs ${i}` });
      await sleep(50);
    }
    const add = new ROSLIB.Service({ ros, name: '/add', serviceType: 'example_interfaces/srv/AddTwoInts' });
    const sum = await within(10000, 'the /add call', cb((ok, fail) => add.callService({ a: 40, b: 2 }, ok, fail)));
    const missing = new ROSLIB.Service({ ros, name: '/no_such_service', serviceType: 'example_interfaces/srv/AddTwoInts' });
    const missingError = await within(10000, 'the failing call', new Promise((resolve) => missing.callService({ a: 1, b: 2 }, () => resolve(null), resolve)));
    ros.close();
    return {
      topics, nodes, services, topicType, decoded: ros.decodeTypeDefs(details), details: details.map((d) => d.type), raw,
      heard: heard.map((m) => m.data), sum, missingError,
    };
  },

  /** Serve a service that a C++ client (probe caller) calls. */
  async serve() {
    const ros = await connect();
    const svc = new ROSLIB.Service({ ros, name: '/served', serviceType: 'example_interfaces/srv/AddTwoInts' });
    const requests = [];
    await svc.advertise((req, res) => {
      requests.push(req);
      res.sum = req.a * 100 + req.b;
      return true;
    });
    await within(20000, 'a request from the C++ client', (async () => { while (!requests.length) await sleep(50); })());
    await sleep(500); // the response reaches the caller
    ros.close();
    return { requests };
  },

  /** An action goal of a C++ action server: feedback and result, then a goal that is canceled. */
  async action() {
    const ros = await connect();
    const action = new ROSLIB.Action({ ros, name: '/fibonacci', actionType: 'example_interfaces/action/Fibonacci' });
    const feedback = [];
    const result = await within(20000, 'the result of goal order 3', new Promise((resolve, reject) => {
      action.sendGoal({ order: 3 }, resolve, (f) => feedback.push(f.sequence), (e) => reject(new Error(e)));
    }));
    const cancelled = await within(20000, 'the cancel of goal order 30', new Promise((resolve) => {
      const id = action.sendGoal({ order: 30 }, (r) => resolve({ finished: r }), () => action.cancelGoal(id), (e) => resolve({ error: String(e) }));
    }));
    ros.close();
    return { feedback, result, cancelled };
  },

  /** Serve an action (advertise_action) that a C++ action client uses: feedback, then the result. */
  async serveAction() {
    const ros = await connect();
    const action = new ROSLIB.Action({ ros, name: '/fibonacci', actionType: 'example_interfaces/action/Fibonacci' });
    const goals = [];
    action.advertise(async (goal, id) => {
      goals.push(goal);
      const seq = [0, 1];
      for (let i = 1; i < goal.order; i++) {
        seq.push(seq[i] + seq[i - 1]);
        action.sendFeedback(id, { sequence: seq });
        await sleep(20);
      }
      action.setSucceeded(id, { sequence: seq });
    }, () => {});
    await within(30000, 'a goal from the C++ client', (async () => { while (!goals.length) await sleep(50); })());
    await sleep(1500);
    ros.close();
    return { goals };
  },

  /**
   * roslibjs' getParams and Param (get, set, delete) on an rclcpp node's parameters (argv:
   * NODE, a probe param_talker), then rosapi's has_param and get_param's default, and the
   * failures, each with the reason roslibjs hands its failure callback.
   */
  async params() {
    const [node] = process.argv.slice(4);
    const ros = await connect();
    const param = (name) => new ROSLIB.Param({ ros, name: `${node}:${name}` });
    const get = (p) => within(10000, `getting ${p.name}`, new Promise((ok) => p.get((v) => ok({ value: v }), (e) => ok({ failed: e }))));
    const set = (p, v) => within(10000, `setting ${p.name}`, new Promise((ok) => p.set(v, () => ok({ set: true }), (e) => ok({ failed: e }))));
    const del = (p) => within(10000, `deleting ${p.name}`, new Promise((ok) => p.delete(() => ok({ deleted: true }), (e) => ok({ failed: e }))));
    const rosapi = (service, args) => within(10000, `rosapi/${service}`, cb((ok, fail) => new ROSLIB.Service({
      ros, name: `/rosapi/${service}`, serviceType: 'rosapi_msgs/srv/X',
    }).callService(args, ok, fail)));
    const out = {};
    out.names = await within(10000, 'getParams', cb((ok, fail) => ros.getParams(ok, fail)));
    out.before = await get(param('greeting'));
    out.set = await set(param('greeting'), 'hi from roslibjs');
    out.after = await get(param('greeting'));
    out.setPeriod = await set(param('period_ms'), 250);
    out.period = await get(param('period_ms'));
    out.wrongType = await set(param('period_ms'), 'fast');
    out.periodStill = await get(param('period_ms'));
    out.missing = await get(param('no_such'));
    out.noNode = await get(new ROSLIB.Param({ ros, name: '/nobody:x' }));
    out.malformed = await get(new ROSLIB.Param({ ros, name: 'no_colon' }));
    out.defaulted = await rosapi('get_param', { name: `${node}:no_such`, default_value: '7' });
    out.has = await rosapi('has_param', { name: `${node}:greeting` });
    out.hasNot = await rosapi('has_param', { name: `${node}:no_such` });
    out.notJson = await rosapi('set_param', { name: `${node}:greeting`, value: 'not json' });
    out.deleteMissing = await del(param('no_such'));
    out.deleteDeclared = await del(param('greeting'));
    out.afterDelete = await get(param('greeting'));
    ros.close();
    return out;
  },

  /** Publish TEXT (argv) on /chatter ten times, 100 ms apart: what a listener waits for. */
  async say() {
    const [text] = process.argv.slice(4);
    const ros = await connect();
    const chatter = new ROSLIB.Topic({ ros, name: '/chatter', messageType: 'std_msgs/msg/String' });
    for (let i = 0; i < 10; i++) {
      chatter.publish({ data: text });
      await sleep(100);
    }
    ros.close();
    return { said: text };
  },

  /** throttle_rate and queue_length on a 10 Hz topic, each on its own connection. */
  async throttle() {
    const count = async (options, ms) => {
      const ros = await connect();
      const topic = new ROSLIB.Topic({ ros, name: '/chatter', messageType: 'std_msgs/msg/String', ...options });
      const got = [];
      topic.subscribe((m) => got.push({ data: m.data, at: Date.now() }));
      await sleep(ms);
      topic.unsubscribe();
      ros.close();
      return got;
    };
    const [all, throttled, queued] = await Promise.all([
      count({}, 3000), count({ throttle_rate: 500 }, 3000), count({ throttle_rate: 1000, queue_length: 1 }, 3500),
    ]);
    const n = (m) => Number(m.data.split(' ').pop());
    return {
      all: all.length, throttled: throttled.length,
      throttledGaps: throttled.slice(1).map((m, i) => m.at - throttled[i].at),
      queued: queued.map(n), queuedGaps: queued.slice(1).map((m, i) => m.at - queued[i].at),
    };
  },

  /** 640x480 rgb8 images through a C++ node (probe bench_pong_image), received as cbor-raw and cbor. */
  async images() {
    const ros = await connect();
    const width = 640;
    const height = 480;
    const data = Buffer.alloc(width * height * 3);
    for (let i = 0; i < data.length; i++) data[i] = (i * 7) & 0xff;
    const image = {
      header: { stamp: { sec: 1, nanosec: 2 }, frame_id: 'camera' }, height, width, encoding: 'rgb8',
      is_bigendian: 0, step: width * 3, data: data.toString('base64'),
    };
    const raw = collect(ros, { name: '/bench/pong', messageType: 'sensor_msgs/msg/Image', compression: 'cbor-raw' }, 1, 20000);
    const ros2 = await connect();
    const cbor = collect(ros2, { name: '/bench/pong', messageType: 'sensor_msgs/msg/Image', compression: 'cbor' }, 1, 20000);
    const ping = new ROSLIB.Topic({ ros, name: '/bench/ping', messageType: 'sensor_msgs/msg/Image' });
    let stop = false;
    const pump = (async () => { while (!stop) { ping.publish(image); await sleep(100); } })();
    const [[r], [c]] = await Promise.all([raw, cbor]);
    stop = true;
    await pump;
    const bytes = Buffer.from(r.bytes);
    // CDR: header (4), stamp (8), frame_id (4 + 7 -> pad to 4), height, width at 4-byte alignment
    const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    const frameLen = view.getUint32(12, true);
    let off = 16 + frameLen;
    off = 4 + Math.ceil((off - 4) / 4) * 4;
    ros.close();
    ros2.close();
    return {
      rawBytes: bytes.length, rawHasTime: typeof r.secs === 'number' && typeof r.nsecs === 'number',
      rawHeight: view.getUint32(off, true), rawWidth: view.getUint32(off + 4, true),
      rawDataTail: Array.from(bytes.subarray(bytes.length - 3)),
      cborDataIsBytes: c.data instanceof Uint8Array, cborDataLength: c.data.length, cborEncoding: c.encoding,
      cborFrame: c.header.frame_id, expectedTail: Array.from(data.subarray(data.length - 3)),
    };
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
