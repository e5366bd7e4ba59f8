// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Tests of the page's MCAP reader and writer, its ros2msg schema texts, its
// rosbag2 QoS and its paced player (packages/wasm_js/src/page/), run by
// tests/test_mcap_page.py with `node --test`. MCAP_FIXTURES names the JSON
// file of inputs and expectations Python wrote: bags of the Python `mcap`
// writer and of serve's recorder, a zstd bag, the texts of
// colcon_wasm/ros2msg.py and qos.py, Fast CDR golden messages, and where to
// write the page's bag (which Python then reads with `mcap`).

import assert from 'node:assert/strict';
import { readFileSync, writeFileSync } from 'node:fs';
import { test } from 'node:test';

import { McapIndexedReader, McapStreamReader } from '@mcap/core';

import { McapError, McapRefused, readMcap } from '../../packages/wasm_js/src/page/mcap_reader.mjs';
import { crc32 } from '../../packages/wasm_js/src/page/mcap_records.mjs';
import { McapWriter } from '../../packages/wasm_js/src/page/mcap_writer.mjs';
import { PacedPlayer } from '../../packages/wasm_js/src/page/paced_player.mjs';
import { fromRosbag2, playerQos, toRosbag2 } from '../../packages/wasm_js/src/page/rosbag2_qos.mjs';
import { Ros2MsgSchemas } from '../../packages/wasm_js/src/page/ros2msg.mjs';

const fixtures = JSON.parse(readFileSync(process.env.MCAP_FIXTURES, 'utf-8'));
const types = JSON.parse(readFileSync(fixtures.types, 'utf-8'));
const schemas = Ros2MsgSchemas.fromDocuments([types]);
const fromHex = (h) => Uint8Array.from(h.match(/../g) || [], (b) => parseInt(b, 16));
const toHex = (bytes) => Buffer.from(bytes).toString('hex');
const file = (path) => new Uint8Array(readFileSync(path));
const topicOf = (type) => `/${type.split('/').pop().toLowerCase()}`;
const BASE_MS = 1.7e12;
const encoder = new TextEncoder();

/** The page's bag of the golden messages, as the recorder builds it from subscription batches. */
function writeGoldenBag(options = {}) {
  const writer = new McapWriter({ library: 'colcon-wasm page', chunkBytes: 256, ...options });
  const channels = new Map();
  fixtures.vectors.forEach((v, i) => {
    if (!channels.has(v.type)) {
      const schema = writer.addSchema(v.type, 'ros2msg', encoder.encode(schemas.fullText(v.type)));
      channels.set(v.type, writer.addChannel(topicOf(v.type), 'cdr', schema,
        { offered_qos_profiles: toRosbag2([{ depth: 3 }]) }));
    }
    const info = { receivedTime: BASE_MS + i, sourceTime: BASE_MS + i - 0.5 };
    assert.equal(writer.write(channels.get(v.type), [{ data: fromHex(v.hex), info }]), 1);
  });
  return { writer, bytes: new Uint8Array(Buffer.concat(writer.finish())) };
}

test('the schema texts are those of colcon_wasm/ros2msg.py', () => {
  const names = Object.keys(fixtures.texts);
  assert.ok(names.includes('cdr_test_msgs/msg/Nested'), names);
  for (const name of names) assert.equal(schemas.fullText(name), fixtures.texts[name], name);
  assert.equal(schemas.resolve('cdr_test_msgs/Inner'), 'cdr_test_msgs/msg/Inner');
  assert.throws(() => schemas.fullText('robot_msgs/msg/Odd'), /no type description of 'robot_msgs\/msg\/Odd'/);
});

test('the QoS YAML and the player QoS are those of colcon_wasm/record/qos.py', () => {
  for (const { profiles, yaml } of fixtures.qos) assert.equal(toRosbag2(profiles), yaml, JSON.stringify(profiles));
  for (const { text, qos } of fixtures.playerQos) assert.deepEqual(playerQos(text), qos, text);
  const [offer] = fromRosbag2(fixtures.qos[1].yaml);
  assert.equal(offer.reliability, 'best_effort');
  assert.equal(offer.lifespanMs, 1500.5);
});

test('a bag of the Python mcap writer reads in log-time order across chunks', () => {
  const content = readMcap(file(fixtures.pythonBag), { name: 'python.mcap' });
  assert.equal(content.error, null);
  assert.equal(content.profile, 'ros2');
  const topics = new Map([...content.channels.values()].map((c) => [c.id, c.topic]));
  const got = content.messages.map((m) => ({ topic: topics.get(m.channelId), logTime: String(m.logTime), hex: toHex(m.data) }));
  assert.deepEqual(got, fixtures.pythonExpected);
  // the file's order (message i holds i) is not the log-time order: the sort mattered
  assert.ok(content.messages.some((m, i) => i > 0 && m.data[4] < content.messages[i - 1].data[4]));
});

test("a bag of serve's recorder reads with its schema and QoS", () => {
  const content = readMcap(file(fixtures.recorderBag), { name: 'recorder.mcap' });
  assert.equal(content.error, null);
  const [channel] = content.channels.values();
  assert.equal(channel.topic, '/rec');
  assert.equal(content.schemas.get(channel.schemaId).name, 'cdr_test_msgs/msg/Inner');
  assert.equal(new TextDecoder().decode(content.schemas.get(channel.schemaId).data), fixtures.texts['cdr_test_msgs/msg/Inner']);
  assert.deepEqual(playerQos(channel.metadata.offered_qos_profiles),
    { history: 'keep_last', depth: 4, reliability: 'reliable', durability: 'transient_local' });
  assert.deepEqual(content.messages.map((m) => ({ topic: '/rec', logTime: String(m.logTime), hex: toHex(m.data) })),
    fixtures.recorderExpected);
});

test('a zstd bag is refused, naming the compression and what to do', () => {
  assert.throws(() => readMcap(file(fixtures.zstdBag), { name: 'zstd.mcap' }), (e) => {
    assert.ok(e instanceof McapRefused, e);
    assert.equal(e.compression, 'zstd');
    assert.match(e.message, /^'zstd.mcap': its chunks are compressed with zstd \(the Chunk record at byte offset \d+\)/);
    assert.match(e.message, /play it under 'colcon-wasm serve'/);
    assert.match(e.message, /mcap decompress IN\.mcap -o OUT\.mcap/);
    return true;
  });
});

test('the page bag is read back by @mcap/core (indexed and stream) and by the page', async () => {
  const { writer, bytes } = writeGoldenBag();
  writeFileSync(fixtures.out, bytes);
  assert.ok(writer.chunkIndexes.length >= 2, writer.chunkIndexes.length);
  const readable = {
    size: async () => BigInt(bytes.length),
    read: async (offset, length) => bytes.subarray(Number(offset), Number(offset + length)),
  };
  const indexed = await McapIndexedReader.Initialize({ readable });
  assert.equal(indexed.header.profile, 'ros2');
  assert.equal(indexed.chunkIndexes.length, writer.chunkIndexes.length);
  assert.equal(indexed.statistics.messageCount, BigInt(fixtures.vectors.length));
  const channels = new Map([...indexed.channelsById.values()].map((c) => [c.id, c]));
  const got = [];
  for await (const m of indexed.readMessages()) got.push(m);
  assert.equal(got.length, fixtures.vectors.length);
  got.forEach((m, i) => {
    const v = fixtures.vectors[i];
    const channel = channels.get(m.channelId);
    assert.equal(channel.topic, topicOf(v.type));
    assert.equal(indexed.schemasById.get(channel.schemaId).name, v.type);
    assert.equal(toHex(m.data), v.hex);
    assert.equal(m.logTime, BigInt(Math.round((BASE_MS + i) * 1e6)));
  });
  const stream = new McapStreamReader({ validateCrcs: true });
  stream.append(bytes);
  const kinds = [];
  for (let r = stream.nextRecord(); r; r = stream.nextRecord()) kinds.push(r.type);
  assert.ok(stream.done());
  assert.equal(kinds.filter((k) => k === 'Message').length, fixtures.vectors.length);
  assert.deepEqual(kinds.slice(-1), ['Footer']);
  const own = readMcap(bytes, { name: 'page.mcap' });
  assert.equal(own.error, null);
  assert.deepEqual(own.messages.map((m) => toHex(m.data)), fixtures.vectors.map((v) => v.hex));
});

test('past maxBytes messages are dropped and counted, and the file stays whole', async () => {
  const writer = new McapWriter({ maxBytes: 100 * 1024 });
  const channel = writer.addChannel('/big', 'cdr', writer.addSchema('x/msg/Big', 'ros2msg', encoder.encode('uint8[] data\n')));
  let kept = 0;
  for (let i = 0; i < 40; i++) kept += writer.write(channel, [{ data: new Uint8Array(10000).fill(i), info: { receivedTime: BASE_MS + i, sourceTime: BASE_MS + i } }]);
  assert.ok(kept >= 3 && kept < 10, kept);
  assert.equal(writer.dropped, 40 - kept);
  const bytes = new Uint8Array(Buffer.concat(writer.finish()));
  assert.ok(bytes.length <= 100 * 1024, bytes.length);
  const indexed = await McapIndexedReader.Initialize({ readable: {
    size: async () => BigInt(bytes.length),
    read: async (offset, length) => bytes.subarray(Number(offset), Number(offset + length)),
  } });
  assert.equal(indexed.statistics.messageCount, BigInt(kept));
});

test('a cut or damaged bag reads up to the damage and names it', () => {
  const { writer, bytes } = writeGoldenBag();
  const second = writer.chunkIndexes[1];
  const cut = readMcap(bytes.subarray(0, Number(second.offset) + 30), { name: 'cut.mcap' });
  assert.match(cut.error, new RegExp(`^'cut.mcap': the Chunk record at byte offset ${second.offset} is cut off`));
  const firstCount = readMcap(bytes).messages.filter((m) => m.logTime <= writer.chunkIndexes[0].end).length;
  assert.equal(cut.messages.length, firstCount);
  const flipped = bytes.slice();
  flipped[Number(second.offset) + 60] ^= 0xff;
  const damaged = readMcap(flipped, { name: 'crc.mcap' });
  assert.match(damaged.error, new RegExp(`the Chunk record at byte offset ${second.offset} is corrupt: the CRC`));
  const footerless = readMcap(bytes.subarray(0, Number(second.offset)), { name: 'short.mcap' });
  assert.match(footerless.error, /^'short.mcap' ends at byte \d+ without a Footer record: it was cut off/);
  assert.throws(() => readMcap(encoder.encode('{"not": "mcap"}'), { name: 'x.json' }),
    (e) => e instanceof McapError && /'x.json' is not an MCAP file/.test(e.message));
});

test('any damage gives a McapError or an error text, never another exception', () => {
  const { bytes } = writeGoldenBag();
  let seed = 41;
  const random = () => { seed = (seed * 1103515245 + 12345) % 2147483648; return seed / 2147483648; };
  let errors = 0;
  for (let round = 0; round < 2000; round++) {
    const damaged = bytes.slice(0, 8 + Math.floor(random() * (bytes.length - 8)) + (round % 2 ? 0 : 8));
    for (let k = 0; k < 1 + round % 4; k++) damaged[8 + Math.floor(random() * (damaged.length - 8))] = Math.floor(random() * 256);
    try {
      const content = readMcap(damaged);
      if (content.error) errors++;
      for (const m of content.messages) assert.ok(m.data instanceof Uint8Array);
    } catch (e) {
      assert.ok(e instanceof McapError, e.stack);
      errors++;
    }
  }
  assert.ok(errors > 1000, errors);
});

test('crc32 is zlib\'s', () => {
  assert.equal(crc32(encoder.encode('123456789')), 0xcbf43926);
  assert.equal(crc32(encoder.encode('56789'), crc32(encoder.encode('1234'))), 0xcbf43926);
});

/** A player of `gapsMs` (the time of each message from the first), recording what it sends. */
function player(timesMs) {
  const sent = [];
  const reports = [];
  const ticks = [];
  const messages = timesMs.map((t, i) => ({ channel: 1, logTime: 5000000000n + BigInt(t * 1e6), data: Uint8Array.of(i) }));
  const p = new PacedPlayer(messages, {
    send: (channel, positionMs, data) => sent.push({ i: data[0], positionMs, at: performance.now() }),
    report: (s) => reports.push({ ...s }),
    tick: (ns) => ticks.push(ns),
  });
  return { p, sent, reports, ticks };
}

const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

test('the player keeps the recorded gaps, and steps, seeks, pauses and changes rate', async () => {
  const { p, sent, reports } = player([0, 80, 160, 240, 320, 400, 480]);
  p.step();
  assert.deepEqual(sent.map((s) => s.i), [0]);
  assert.equal(p.state, 'paused');
  p.seek(150); // nothing between is sent; the next is message 2
  await sleep(100);
  assert.deepEqual(sent.map((s) => s.i), [0]);
  p.play();
  assert.deepEqual(sent.map((s) => s.i), [0, 2]); // the next message at once
  await sleep(120);
  assert.deepEqual(sent.map((s) => s.i), [0, 2, 3]);
  const gap = sent[2].at - sent[1].at;
  assert.ok(gap >= 78 && gap < 110, gap);
  p.pause();
  await sleep(200);
  assert.deepEqual(sent.map((s) => s.i), [0, 2, 3]);
  p.setRate(4);
  p.play();
  await sleep(150);
  assert.deepEqual(sent.map((s) => s.i), [0, 2, 3, 4, 5, 6]);
  const fast = sent[5].at - sent[4].at;
  assert.ok(fast >= 18 && fast < 45, fast);
  assert.equal(p.state, 'ended');
  assert.equal(reports.at(-1).state, 'ended');
  assert.equal(reports.at(-1).position_ms, 480);
  assert.equal(reports.at(-1).sent, 6);
  p.setRate(100);
  p.play(); // once it ended: from the start again
  await sleep(100);
  assert.deepEqual(sent.slice(6).map((s) => s.i), [0, 1, 2, 3, 4, 5, 6]);
  p.close();
});

test('the player ticks /clock with the bag time while playing, and at a step and a seek', async () => {
  const { p, ticks } = player([0, 100, 200, 300]);
  p.setClock(50);
  p.step();
  assert.deepEqual(ticks, [5000000000n]);
  p.seek(250);
  assert.deepEqual(ticks.slice(1), [5300000000n]);
  p.seek(0);
  p.play();
  await sleep(200);
  p.pause();
  const played = ticks.slice(3);
  assert.ok(played.length >= 5, played); // 50 Hz for 200 ms
  for (let i = 1; i < played.length; i++) assert.ok(played[i] >= played[i - 1]);
  assert.ok(played.at(-1) >= 5100000000n && played.at(-1) <= 5300000000n, played.at(-1));
  p.close();
});

test('an empty selection of messages ends at once', () => {
  const reports = [];
  const p = new PacedPlayer([], { send: () => assert.fail('nothing to send'), report: (s) => reports.push(s), error: 'cut' });
  p.play();
  assert.equal(reports.at(-1).state, 'ended');
  assert.equal(reports.at(-1).error, 'cut');
});
