// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The Graph tab's layout (templates/launcher/views/graph_layout.mjs), on
// graph models as the page's session has them: columns left to right along
// publisher -> topic -> subscriber, a cycle drawn with one edge going back,
// rqt_graph's filters. Run by tests/test_page_graph.py (node --test).

import assert from 'node:assert/strict';
import { test } from 'node:test';

import { DEBUG_TOPICS, graphOf, layoutGraph } from '../../templates/launcher/views/graph_layout.mjs';

const node = (fqn, publishers = [], subscriptions = []) => ({
  fqn, name: fqn.split('/').pop(), namespace: '/',
  publishers: publishers.map((name) => ({ name, type: 'std_msgs/msg/String' })),
  subscriptions: subscriptions.map((name) => ({ name, type: 'std_msgs/msg/String' })),
});
const debug = DEBUG_TOPICS;

test('talker -> /chatter -> listener, left to right, debug topics hidden', () => {
  const model = { nodes: [node('/talker', ['/chatter', ...debug]), node('/listener', ['/rosout'], ['/chatter'])] };
  const graph = graphOf(model);
  assert.deepEqual(graph.vertices.map((v) => v.id).sort(), ['n:/listener', 'n:/talker', 't:/chatter']);
  const { boxes, edges } = layoutGraph(graph);
  const column = Object.fromEntries(boxes.map((b) => [b.label, b.column]));
  assert.deepEqual(column, { '/talker': 0, '/chatter': 1, '/listener': 2 });
  assert.equal(edges.length, 2);
  for (const e of edges) {
    assert.equal(e.reversed, false);
    assert.ok(e.points[0][0] < e.points[1][0], 'an edge points right');
  }
  const all = graphOf(model, { debug: true });
  assert.ok(all.vertices.some((v) => v.id === 't:/rosout'));
});

test('a cycle: one edge goes back, every vertex has a column', () => {
  // /a publishes /x, /b takes /x and publishes /y, /a takes /y
  const model = { nodes: [node('/a', ['/x'], ['/y']), node('/b', ['/y'], ['/x'])] };
  const { boxes, edges } = layoutGraph(graphOf(model));
  assert.equal(boxes.length, 4);
  assert.equal(edges.filter((e) => e.reversed).length, 1);
  assert.equal(new Set(boxes.map((b) => `${b.column}:${b.row}`)).size, 4, 'no two boxes in one place');
});

test('boxes of a column do not overlap, and columns do not either', () => {
  const nodes = [node('/camera', ['/image']), node('/lidar', ['/scan'])];
  for (let i = 0; i < 5; i++) nodes.push(node(`/user_${i}`, [], ['/image', '/scan']));
  const { boxes } = layoutGraph(graphOf({ nodes }));
  for (const a of boxes) {
    for (const b of boxes) {
      if (a === b) continue;
      const apart = a.x + a.width <= b.x || b.x + b.width <= a.x || a.y + a.height <= b.y || b.y + b.height <= a.y;
      assert.ok(apart, `${a.label} and ${b.label} overlap`);
    }
  }
});

test('nodes only: node -> node edges labelled with their topics; leaf topics can go', () => {
  const model = { nodes: [node('/talker', ['/chatter', '/news']), node('/listener', [], ['/chatter', '/news']), node('/lonely', ['/nobody'])] };
  const only = graphOf(model, { topics: false });
  assert.deepEqual(only.vertices.map((v) => v.kind), ['node', 'node', 'node']);
  assert.deepEqual(only.edges, [{ from: 'n:/talker', to: 'n:/listener', label: '/chatter, /news' }]);
  const noLeaves = graphOf(model, { leaves: false });
  assert.ok(!noLeaves.vertices.some((v) => v.id === 't:/nobody'));
  assert.ok(graphOf(model).vertices.some((v) => v.id === 't:/nobody'));
});

test('namespaces grouped: each framed, its members inside, edges between frames', () => {
  const model = {
    nodes: [node('/robot1/talker', ['/robot1/chatter']), node('/robot1/listener', [], ['/robot1/chatter']),
      node('/monitor', [], ['/robot1/chatter'])],
  };
  const { boxes, groups, edges } = layoutGraph(graphOf(model), { groups: true });
  assert.deepEqual(groups.map((g) => g.name), ['/robot1']);
  const frame = groups[0];
  for (const b of boxes.filter((x) => x.label.startsWith('/robot1/'))) {
    assert.ok(b.x >= frame.x && b.x + b.width <= frame.x + frame.width, `${b.label} is inside the frame`);
    assert.ok(b.y >= frame.y && b.y + b.height <= frame.y + frame.height, `${b.label} is inside the frame`);
  }
  const monitor = boxes.find((b) => b.label === '/monitor');
  assert.ok(monitor.y + monitor.height <= frame.y || monitor.y >= frame.y + frame.height, 'the root is outside');
  assert.equal(edges.length, 3);
  const flat = layoutGraph(graphOf(model));
  assert.deepEqual(flat.groups, []);
});
