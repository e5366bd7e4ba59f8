// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The layout of the ROS graph drawn by the Graph tab (./graph.mjs), as
 * rqt_graph draws it: nodes (ellipses) and topics (boxes) in columns from
 * left to right, each publisher -> topic -> subscriber edge pointing right.
 *
 * Pure: a graph model (wasm_js page/graph.mjs graphModel) in, boxes and
 * edges with coordinates out. A layered layout (Sugiyama's, in small):
 *   1. edges that close a cycle are turned around (depth-first search, in name
 *      order), so that the rest is acyclic;
 *   2. each vertex goes into the column after its furthest predecessor
 *      (longest path), so a talker is left of /chatter, left of the listener;
 *   3. within a column, vertices are ordered by the mean row of their
 *      neighbours, sweeping right then left a few times (fewer crossings);
 *   4. columns are centred on one another.
 * With `groups`, each namespace (a name's first part, `/robot1` of
 * `/robot1/talker` and `/robot1/chatter`) is laid out by itself and framed,
 * as rqt_graph clusters namespaces; the frames are stacked, the root
 * namespace first, and edges between them drawn from box to box.
 *
 * @module views/graph_layout
 */

/** Topics rqt_graph hides by default ("Hide: Debug"): each node has them. */
export const DEBUG_TOPICS = ['/rosout', '/parameter_events'];

const CHAR_WIDTH = 7.2; // 12 px monospace
const PAD_X = 18;
const BOX_HEIGHT = 30;
const ROW_GAP = 18;
const COLUMN_GAP = 70;
const SWEEPS = 4;
const GROUP_PAD = 14;
const GROUP_LABEL = 18;
const GROUP_GAP = 24;

/** The namespace a name is grouped in: its first part when it has more ('' for the root). */
export function namespaceOf(name) {
  const parts = name.split('/').filter(Boolean);
  return parts.length > 1 ? `/${parts[0]}` : '';
}

/**
 * The vertices and edges to draw.
 * @param {object} model a graphModel: nodes with publishers and subscriptions
 * @param {object} [options]
 * @param {boolean} [options.debug=false] keep /rosout, /parameter_events and hidden names
 * @param {boolean} [options.topics=true] draw topics as boxes; false: node -> node edges,
 *   each labelled with its topics (rqt_graph's "Nodes only")
 * @param {boolean} [options.leaves=true] keep topics with no publisher or no subscriber
 * @returns {{vertices: Array<{id, kind, label}>, edges: Array<{from, to, label}>}}
 */
export function graphOf(model, { debug = false, topics = true, leaves = true } = {}) {
  const keepTopic = (name) => debug || (!DEBUG_TOPICS.includes(name) && !name.split('/').some((p) => p.startsWith('_')));
  const vertices = new Map();
  const edges = [];
  const publishers = new Map(); // topic -> [node ids]
  const subscribers = new Map();
  for (const node of model.nodes || []) {
    if (!debug && node.name.startsWith('_')) continue;
    vertices.set(`n:${node.fqn}`, { id: `n:${node.fqn}`, kind: 'node', label: node.fqn });
    for (const e of node.publishers) if (keepTopic(e.name)) push(publishers, e.name, `n:${node.fqn}`);
    for (const e of node.subscriptions) if (keepTopic(e.name)) push(subscribers, e.name, `n:${node.fqn}`);
  }
  const names = [...new Set([...publishers.keys(), ...subscribers.keys()])].sort();
  if (topics) {
    for (const name of names) {
      const from = publishers.get(name) || [];
      const to = subscribers.get(name) || [];
      if (!leaves && (from.length === 0 || to.length === 0)) continue;
      vertices.set(`t:${name}`, { id: `t:${name}`, kind: 'topic', label: name });
      for (const n of from) edges.push({ from: n, to: `t:${name}`, label: '' });
      for (const n of to) edges.push({ from: `t:${name}`, to: n, label: '' });
    }
  } else {
    const labels = new Map();
    for (const name of names) {
      for (const from of publishers.get(name) || []) {
        for (const to of subscribers.get(name) || []) {
          const key = `${from}\u0000${to}`;
          if (!labels.has(key)) labels.set(key, []);
          labels.get(key).push(name);
        }
      }
    }
    for (const [key, list] of labels) {
      const [from, to] = key.split('\u0000');
      edges.push({ from, to, label: list.join(', ') });
    }
  }
  return { vertices: [...vertices.values()], edges };
}

function push(map, key, value) {
  if (!map.has(key)) map.set(key, []);
  if (!map.get(key).includes(value)) map.get(key).push(value);
}

/**
 * Lay a graph out (see the module).
 * @param {{vertices: Array<{id, kind, label}>, edges: Array<{from, to, label}>}} graph
 * @param {object} [options]
 * @param {boolean} [options.groups=false] frame each namespace (see the module)
 * @returns {{boxes: Array<{id, kind, label, x, y, width, height, column, row, group}>,
 *   edges: Array<{from, to, label, reversed, points: number[][]}>,
 *   groups: Array<{name, x, y, width, height}>, width: number, height: number}}
 */
export function layoutGraph(graph, { groups = false } = {}) {
  const edges = graph.edges.filter((e) => e.from !== e.to);
  const names = groups ? [...new Set(graph.vertices.map((v) => namespaceOf(v.label)))].sort() : [''];
  const boxes = new Map();
  const frames = [];
  let top = 0;
  let width = 0;
  for (const name of names) {
    const members = graph.vertices.filter((v) => !groups || namespaceOf(v.label) === name);
    const inside = new Set(members.map((v) => v.id));
    const part = layered(members, edges.filter((e) => inside.has(e.from) && inside.has(e.to)));
    const framed = groups && name !== '';
    const dx = framed ? GROUP_PAD : 0;
    const dy = top + (framed ? GROUP_PAD + GROUP_LABEL : 0);
    for (const b of part.boxes) boxes.set(b.id, { ...b, x: b.x + dx, y: b.y + dy, group: name });
    const frameWidth = part.width + 2 * dx;
    const frameHeight = part.height + (framed ? 2 * GROUP_PAD + GROUP_LABEL : 0);
    if (framed) frames.push({ name, x: 0, y: top, width: frameWidth, height: frameHeight });
    width = Math.max(width, frameWidth);
    top += frameHeight + GROUP_GAP;
  }
  const laid = [];
  for (const e of edges) {
    const a = boxes.get(e.from);
    const b = boxes.get(e.to);
    if (!a || !b) continue;
    const back = a.group === b.group ? b.column <= a.column : b.x <= a.x + a.width;
    const start = back ? [a.x, a.y + a.height / 2] : [a.x + a.width, a.y + a.height / 2];
    const end = back ? [b.x + b.width, b.y + b.height / 2] : [b.x, b.y + b.height / 2];
    laid.push({ from: e.from, to: e.to, label: e.label || '', reversed: back, points: [start, end] });
  }
  return { boxes: [...boxes.values()], edges: laid, groups: frames, width, height: Math.max(0, top - GROUP_GAP) };
}

/** The layered layout of one set of vertices (steps 1-4 of the module). */
function layered(vertices, edges) {
  const ids = vertices.map((v) => v.id).sort();
  const out = new Map(ids.map((id) => [id, []]));
  for (const e of edges) out.get(e.from).push(e.to);
  for (const list of out.values()) list.sort();
  const reversed = backEdges(ids, out);
  // the acyclic graph: edges that close a cycle point the other way
  const forward = edges.map((e) => (reversed.has(`${e.from}\u0000${e.to}`) ? { from: e.to, to: e.from } : e));
  const preds = new Map(ids.map((id) => [id, []]));
  const succs = new Map(ids.map((id) => [id, []]));
  for (const e of forward) {
    preds.get(e.to).push(e.from);
    succs.get(e.from).push(e.to);
  }
  const column = longestPath(ids, preds, succs);
  const columns = [];
  for (const id of ids) (columns[column.get(id)] ||= []).push(id);
  order(columns, preds, succs);
  const byId = new Map(vertices.map((v) => [v.id, v]));
  const boxes = [];
  let x = 0;
  let height = 0;
  const columnHeights = columns.map((c) => c.length * BOX_HEIGHT + Math.max(0, c.length - 1) * ROW_GAP);
  const tallest = Math.max(0, ...columnHeights);
  columns.forEach((list, c) => {
    const width = Math.max(...list.map((id) => textWidth(byId.get(id).label))) + 2 * PAD_X;
    let y = (tallest - columnHeights[c]) / 2;
    list.forEach((id, row) => {
      const v = byId.get(id);
      const w = textWidth(v.label) + 2 * PAD_X;
      boxes.push({ ...v, x: x + (width - w) / 2, y, width: w, height: BOX_HEIGHT, column: c, row });
      y += BOX_HEIGHT + ROW_GAP;
    });
    height = Math.max(height, y - ROW_GAP);
    x += width + COLUMN_GAP;
  });
  return { boxes, width: Math.max(0, x - COLUMN_GAP), height };
}

/** The edges that close a cycle, found by a depth-first search in id order. */
function backEdges(ids, out) {
  const state = new Map(); // 1: on the path, 2: done
  const back = new Set();
  for (const root of ids) {
    if (state.has(root)) continue;
    const stack = [[root, 0]];
    state.set(root, 1);
    while (stack.length) {
      const top = stack[stack.length - 1];
      const next = out.get(top[0])[top[1]++];
      if (next === undefined) {
        state.set(top[0], 2);
        stack.pop();
      } else if (state.get(next) === 1) {
        back.add(`${top[0]}\u0000${next}`);
      } else if (!state.has(next)) {
        state.set(next, 1);
        stack.push([next, 0]);
      }
    }
  }
  return back;
}

/** Each vertex' column: one after its furthest predecessor (in topological order). */
function longestPath(ids, preds, succs) {
  const column = new Map();
  const waiting = new Map(ids.map((id) => [id, preds.get(id).length]));
  const ready = ids.filter((id) => waiting.get(id) === 0);
  while (ready.length) {
    const id = ready.shift();
    column.set(id, Math.max(-1, ...preds.get(id).map((p) => column.get(p))) + 1);
    for (const s of succs.get(id)) {
      waiting.set(s, waiting.get(s) - 1);
      if (waiting.get(s) === 0) ready.push(s);
    }
  }
  return column;
}

/** Order each column by the mean row of its neighbours in the column before (after). */
function order(columns, preds, succs) {
  const row = new Map();
  const index = () => columns.forEach((list) => list.forEach((id, i) => row.set(id, i)));
  index();
  const mean = (list, fallback) => (list.length ? list.reduce((s, id) => s + row.get(id), 0) / list.length : fallback);
  for (let sweep = 0; sweep < SWEEPS; sweep++) {
    const down = sweep % 2 === 0;
    const range = down ? columns.map((_, i) => i).slice(1) : columns.map((_, i) => i).reverse().slice(1);
    for (const c of range) {
      const neighbours = down ? preds : succs;
      const keyed = columns[c].map((id) => ({ id, key: mean(neighbours.get(id), row.get(id)) }));
      keyed.sort((a, b) => a.key - b.key || (a.id < b.id ? -1 : 1));
      columns[c] = keyed.map((k) => k.id);
      columns[c].forEach((id, i) => row.set(id, i));
    }
  }
}

function textWidth(text) {
  return Math.ceil(text.length * CHAR_WIDTH);
}
