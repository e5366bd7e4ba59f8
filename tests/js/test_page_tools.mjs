// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Tests of the pure helpers of packages/wasm_js/src/page/, run by
// tests/test_page_tools.py with `node --test` (CDR_TYPES: cdr_test_msgs types).

import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { test } from 'node:test';

import { TypeRegistry } from '../../packages/wasm_js/src/cdr.mjs';
import { asNumber, getPath, numericPaths } from '../../packages/wasm_js/src/page/fields.mjs';
import { compressedMimeType, ImageError, imageKind, imageToRgba } from '../../packages/wasm_js/src/page/image.mjs';
import { formatBandwidth, TopicStats } from '../../packages/wasm_js/src/page/stats.mjs';
import { formatYaml, parseYaml, YamlError } from '../../packages/wasm_js/src/page/yaml.mjs';

const registry = new TypeRegistry([JSON.parse(readFileSync(process.env.CDR_TYPES, 'utf-8'))]);

test('formatYaml prints messages as ros2 topic echo does', () => {
  const text = formatYaml({
    header: { stamp: { sec: 1, nanosec: 5n }, frame_id: 'map' },
    data: Float64Array.of(1.5, -2),
    names: ['a', 'true', '', 'x: y'],
    points: [{ x: 1, y: 2 }],
    empty: [],
    flag: false,
    ratio: NaN,
  });
  assert.equal(text, [
    'header:', '  stamp:', '    sec: 1', '    nanosec: 5', '  frame_id: map',
    'data:', '- 1.5', '- -2',
    'names:', '- a', "- 'true'", "- ''", "- 'x: y'",
    'points:', '- x: 1', '  y: 2',
    'empty: []', 'flag: false', 'ratio: .nan'].join('\n'));
});

test('formatYaml cuts long arrays and says how much was left out', () => {
  const text = formatYaml({ data: new Uint8Array(1000) }, { maxArray: 3 });
  assert.equal(text, "data:\n- 0\n- 0\n- 0\n- '...' # 997 more, 1000 in all");
});

test('parseYaml reads what users type in ros2 topic pub style', () => {
  assert.deepEqual(parseYaml("{data: 'hello world'}"), { data: 'hello world' });
  assert.deepEqual(parseYaml('data: hello # a comment'), { data: 'hello' });
  assert.deepEqual(parseYaml('linear: {x: 0.5, y: 0, z: 0}\nangular:\n  z: -1.25e-1\n'),
    { linear: { x: 0.5, y: 0, z: 0 }, angular: { z: -0.125 } });
  assert.deepEqual(parseYaml('values:\n- 1\n- 2\nnames: [a, "b c", \'d\'\'e\']'),
    { values: [1, 2], names: ['a', 'b c', "d'e"] });
  assert.deepEqual(parseYaml('points:\n  - x: 1\n    y: 2\n  - {x: 3, y: 4}'),
    { points: [{ x: 1, y: 2 }, { x: 3, y: 4 }] });
  assert.deepEqual(parseYaml('{"a": [1, 2], "b": {"c": null}}'), { a: [1, 2], b: { c: null } });
  assert.deepEqual(parseYaml('s: "tab\\there"\nt: true\nf: False\nn: ~'),
    { s: 'tab\there', t: true, f: false, n: null });
  assert.deepEqual(parseYaml('{a: 1,\n b: [2,\n 3]}'), { a: 1, b: [2, 3] });
  assert.deepEqual(parseYaml(''), {});
  assert.equal(parseYaml('big: 18446744073709551615').big, 18446744073709551615n);
  assert.ok(Number.isNaN(parseYaml('x: .nan').x));
});

test('parseYaml round-trips formatYaml', () => {
  const value = { a: { b: [1, 2], c: 'text', d: [{ e: 1 }, { e: 2 }] }, f: -0.5, g: [] };
  assert.deepEqual(parseYaml(formatYaml(value)), value);
});

test('parseYaml errors say the line', () => {
  assert.throws(() => parseYaml('a: 1\n  b: 2'), (e) => e instanceof YamlError && /^line 2: unexpected indentation/.test(e.message));
  assert.throws(() => parseYaml('{a: 1'), /line 1: expected ',' or '}' in a \{\.\.\.\} mapping/);
  assert.throws(() => parseYaml('a: 1\na: 2'), /line 2: the key 'a' appears twice/);
  assert.throws(() => parseYaml("a: 'open"), /single-quoted string is not closed/);
  assert.throws(() => parseYaml('a: 1\nnot a mapping'), /line 2: expected 'key: value'/);
});

test('parsed YAML encodes with the type descriptions', () => {
  const value = parseYaml('tag: 3\nx: 1.5\nlabel: "hi"');
  assert.deepEqual(registry.decode('cdr_test_msgs/msg/Inner', registry.encode('cdr_test_msgs/msg/Inner', value)),
    { tag: 3, x: 1.5, label: 'hi' });
});

test('numericPaths lists plottable fields, getPath reads them', () => {
  const paths = numericPaths(registry, 'cdr_test_msgs/msg/Nested');
  assert.deepEqual(paths, ['lead', 'inner.tag', 'inner.x', 'strings.after', 'tail']);
  assert.deepEqual(numericPaths(registry, 'cdr_test_msgs/msg/Arrays').slice(0, 4),
    ['lead', 'f64s[0]', 'f64s[1]', 'bools[0]']);
  const value = { inner: { x: 2.5 }, list: [{ v: 1n }] };
  assert.equal(getPath(value, 'inner.x'), 2.5);
  assert.equal(asNumber(getPath(value, 'list[0].v')), 1);
  assert.equal(getPath(value, 'missing.x'), undefined);
  assert.throws(() => getPath(value, 'a..b'), /is not a field path/);
});

test('TopicStats gives rate, jitter and bandwidth like ros2 topic hz/bw', () => {
  const stats = new TopicStats({ window: 100 });
  assert.equal(stats.summary(0), null);
  for (let i = 0; i < 250; i++) stats.add(i * 10 + (i % 2), 100);  // 100 Hz with 1 ms jitter
  const s = stats.summary(2500);
  assert.equal(s.window, 100);
  assert.ok(Math.abs(s.rate - 100) < 1, `rate ${s.rate}`);
  assert.ok(Math.abs(s.min - 0.009) < 1e-9 && Math.abs(s.max - 0.011) < 1e-9);
  assert.ok(Math.abs(s.std - 0.001) < 1e-6);
  assert.ok(Math.abs(s.bytesPerSecond - 10000) < 200);
  assert.equal(stats.total, 250);
  assert.equal(formatBandwidth(10000), '10.00 KB/s');
  assert.equal(formatBandwidth(2.5e6), '2.50 MB/s');
});

test('imageToRgba converts the common encodings', () => {
  const rgb = imageToRgba({ width: 2, height: 1, encoding: 'rgb8', step: 6, is_bigendian: 0,
    data: Uint8Array.of(1, 2, 3, 4, 5, 6) });
  assert.deepEqual(Array.from(rgb.rgba), [1, 2, 3, 255, 4, 5, 6, 255]);
  const bgr = imageToRgba({ width: 1, height: 2, encoding: 'bgr8', step: 4, is_bigendian: 0,
    data: Uint8Array.of(1, 2, 3, 0, 7, 8, 9, 0) });
  assert.deepEqual(Array.from(bgr.rgba), [3, 2, 1, 255, 9, 8, 7, 255]);
  const mono16 = imageToRgba({ width: 1, height: 1, encoding: 'mono16', step: 2, is_bigendian: 0,
    data: Uint8Array.of(0x00, 0x80) });
  assert.deepEqual(Array.from(mono16.rgba), [128, 128, 128, 255]);
  const f = new Uint8Array(8);
  new DataView(f.buffer).setFloat32(0, 1, true);
  new DataView(f.buffer).setFloat32(4, 3, true);
  assert.deepEqual(Array.from(imageToRgba({ width: 2, height: 1, encoding: '32FC1', step: 8,
    is_bigendian: 0, data: f }).rgba), [0, 0, 0, 255, 255, 255, 255, 255]);
  assert.throws(() => imageToRgba({ width: 1, height: 1, encoding: 'yuv422', step: 2, data: new Uint8Array(2) }),
    (e) => e instanceof ImageError && /encoding 'yuv422' is not shown/.test(e.message));
  assert.throws(() => imageToRgba({ width: 4, height: 4, encoding: 'rgb8', step: 12, data: new Uint8Array(10) }),
    /needs 48 bytes, the message has 10/);
  assert.equal(compressedMimeType('jpeg'), 'image/jpeg');
  assert.equal(compressedMimeType('rgb8; png compressed bgr8'), 'image/png');
  assert.throws(() => compressedMimeType('tiff'), /'tiff' is not shown/);
});

test('actionsOf finds actions by their hidden send_goal services', async () => {
  const { actionsOf } = await import('../../packages/wasm_js/src/page/ros_clients.mjs');
  assert.deepEqual(actionsOf([
    { name: '/fibonacci/_action/send_goal', types: ['example_interfaces/action/Fibonacci_SendGoal'], servers: 1, clients: 0 },
    { name: '/fibonacci/_action/get_result', types: ['example_interfaces/action/Fibonacci_GetResult'], servers: 1, clients: 0 },
    { name: '/add_two_ints', types: ['example_interfaces/srv/AddTwoInts'], servers: 1, clients: 0 },
  ]), [{ name: '/fibonacci', type: 'example_interfaces/action/Fibonacci', servers: 1, clients: 0 }]);
});

test('parameter values convert as ros2 param set infers them', async () => {
  const { parameterValue, toParameterValue, ParameterType } = await import('../../packages/wasm_js/src/page/ros_clients.mjs');
  assert.deepEqual(toParameterValue(true), { type: ParameterType.BOOL, bool_value: true });
  assert.deepEqual(toParameterValue(5), { type: ParameterType.INTEGER, integer_value: 5n });
  assert.deepEqual(toParameterValue(2.5), { type: ParameterType.DOUBLE, double_value: 2.5 });
  assert.deepEqual(toParameterValue('x'), { type: ParameterType.STRING, string_value: 'x' });
  assert.deepEqual(toParameterValue([1, 2]), { type: ParameterType.INTEGER_ARRAY, integer_array_value: [1n, 2n] });
  assert.deepEqual(toParameterValue([1.5, 2]), { type: ParameterType.DOUBLE_ARRAY, double_array_value: [1.5, 2] });
  assert.deepEqual(toParameterValue(['a']), { type: ParameterType.STRING_ARRAY, string_array_value: ['a'] });
  assert.throws(() => toParameterValue([1, 'a']), /only bools, only integers, only numbers or only strings/);
  assert.throws(() => toParameterValue({ a: 1 }), /cannot hold a mapping/);
  assert.deepEqual(parameterValue({ type: 8, double_array_value: Float64Array.of(1, 2) }), { type: 'double[]', value: [1, 2] });
  assert.deepEqual(parameterValue({ type: 4, string_value: 'hi' }), { type: 'string', value: 'hi' });
});

test('graphModel: nodes with endpoints, counts, hidden names, the tools process left out', async () => {
  const { graphModel } = await import('../../packages/wasm_js/src/page/graph.mjs');
  const ep = (node, pid, type) => ({ node, namespace: '/', type, pid });
  const model = graphModel({
    nodes: [{ name: 'talker', namespace: '/', pid: 2, process: 'talker-1' },
      { name: 'wasm_js_tools_9', namespace: '/', pid: 9, process: 'tools' }],
    topics: [
      { name: '/chatter', types: ['std_msgs/msg/String'], publishers: [ep('talker', 2, 'std_msgs/msg/String')],
        subscriptions: [ep('wasm_js_tools_9', 9, 'std_msgs/msg/String')] },
      { name: '/only_tools', types: ['std_msgs/msg/String'], publishers: [ep('wasm_js_tools_9', 9, 'x')], subscriptions: [] },
      { name: '/fib/_action/feedback', types: ['a/action/F_FeedbackMessage'], publishers: [ep('talker', 2, 'x')], subscriptions: [] },
    ],
    services: [{ name: '/talker/list_parameters', types: ['rcl_interfaces/srv/ListParameters'],
      servers: [ep('talker', 2, 'rcl_interfaces/srv/ListParameters')], clients: [] }],
  }, { toolsPid: 9 });
  assert.deepEqual(model.nodes.map((n) => [n.fqn, n.process]), [['/talker', 'talker-1']]);
  assert.deepEqual(model.topics.map((t) => [t.name, t.publishers, t.subscribers, t.hidden]),
    [['/chatter', 1, 0, false], ['/fib/_action/feedback', 1, 0, true]]);
  assert.deepEqual(model.nodes[0].services, [{ name: '/talker/list_parameters', type: 'rcl_interfaces/srv/ListParameters' }]);
});

test('imageKind knows image types and messages of their shape', () => {
  const shaped = new TypeRegistry([{ schema: 1, package: 'p', messages: {
    'p/msg/Frame': { fields: [{ name: 'height', type: 'uint32' }, { name: 'width', type: 'uint32' },
      { name: 'encoding', type: 'string' }, { name: 'step', type: 'uint32' }, { name: 'data', type: 'uint8', sequence: true }] },
    'p/msg/Jpeg': { fields: [{ name: 'format', type: 'string' }, { name: 'data', type: 'uint8', sequence: true }] },
    'p/msg/Other': { fields: [{ name: 'data', type: 'uint8', sequence: true }] },
  } }]);
  assert.equal(imageKind(shaped, 'sensor_msgs/msg/Image'), 'raw');
  assert.equal(imageKind(shaped, 'sensor_msgs/msg/CompressedImage'), 'compressed');
  assert.equal(imageKind(shaped, 'p/msg/Frame'), 'raw');
  assert.equal(imageKind(shaped, 'p/msg/Jpeg'), 'compressed');
  assert.equal(imageKind(shaped, 'p/msg/Other'), null);
  assert.equal(imageKind(shaped, 'p/msg/Unknown'), null);
});

test('subscriptionQos hears every publisher, as ros2 topic echo chooses', async () => {
  const { subscriptionQos } = await import('../../packages/wasm_js/src/page/graph.mjs');
  const reliable = { reliability: 'reliable', durability: 'volatile' };
  const sensor = { reliability: 'best_effort', durability: 'volatile' };
  const latched = { reliability: 'reliable', durability: 'transient_local' };
  assert.deepEqual(subscriptionQos([]), { history: 'keep_last', depth: 100, reliability: 'reliable', durability: 'volatile' });
  assert.equal(subscriptionQos([reliable, sensor]).reliability, 'best_effort');
  assert.equal(subscriptionQos([latched]).durability, 'transient_local');
  assert.equal(subscriptionQos([latched, reliable]).durability, 'volatile');
});

test('the log dock merges the processes\' lines by their ROS time stamps', async () => {
  const { insertionIndex, logStamp, mergeByStamp } = await import('../../templates/launcher/views/log_order.mjs');
  const origin = 1_700_000_000_000;  // performance.timeOrigin, ms
  // a stamped line takes its stamp; a plain one, or a stamp of another clock, when it came in
  assert.equal(logStamp({ text: '[INFO] [1700000001.250000] [talker]: Publishing', time: 1300 }, origin), 1_700_000_001_250);
  assert.equal(logStamp({ text: 'starting demo_nodes/talker', time: 1300 }, origin), origin + 1300);
  assert.equal(logStamp({ text: '[INFO] [12.5] [sim]: a sim time stamp', time: 1300 }, origin), origin + 1300);
  // the talker's line reached the page after the listener's, but was logged first
  const talker = [{ seq: 1, stamp: 5 }, { seq: 4, stamp: 10 }, { seq: 5, stamp: 20 }];
  const listener = [{ seq: 2, stamp: 3 }, { seq: 3, stamp: 11 }, { seq: 6, stamp: 20 }];
  const merged = mergeByStamp([talker, listener], (e) => e.stamp);
  assert.deepEqual(merged.map((e) => e.seq), [2, 1, 4, 3, 5, 6]);  // equal stamps: the order they came in
  // one process' lines keep their order whatever their stamps say
  const odd = [{ seq: 1, stamp: 30 }, { seq: 2, stamp: 1 }];
  assert.deepEqual(mergeByStamp([odd, [{ seq: 3, stamp: 10 }]], (e) => e.stamp).map((e) => e.seq), [3, 1, 2]);
  // a new line goes before the later-logged lines of other processes, never before its own
  const shown = [{ stamp: 1, proc: 'a' }, { stamp: 5, proc: 'b' }, { stamp: 7, proc: 'a' }, { stamp: 9, proc: 'b' }];
  const at = (i) => shown[i];
  assert.equal(insertionIndex(shown.length, at, { stamp: 10, proc: 'a' }), 4);
  assert.equal(insertionIndex(shown.length, at, { stamp: 6, proc: 'a' }), 3);  // before b's 9, after its own 7
  assert.equal(insertionIndex(shown.length, at, { stamp: 6, proc: 'c' }), 2);
  assert.equal(insertionIndex(shown.length, at, { stamp: 4, proc: 'b' }), 4);  // after its own 9
  assert.equal(insertionIndex(shown.length, at, { stamp: 0, proc: 'c' }), 0);
  assert.equal(insertionIndex(shown.length, at, { stamp: 0, proc: 'c' }, 2), 2);  // looks back 2 lines at most
});
