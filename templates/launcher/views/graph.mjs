// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The Graph tab: the nodes and topics of the bus and who publishes and
// subscribes to what, drawn as rqt_graph draws them (./graph_layout.mjs),
// redrawn when the graph changes, namespaces framed. A click marks a vertex
// and its edges and shows it in the inspector beside the graph (its
// endpoints, or its type, publishers and subscribers), with a button that
// opens it in its tab; a double click opens it at once.

import { h, setChildren } from '../dom.mjs';
import { graphOf, layoutGraph } from './graph_layout.mjs';

const SVG = 'http://www.w3.org/2000/svg';
const MARGIN = 16;

function svg(tag, attributes = {}, ...children) {
  const element = document.createElementNS(SVG, tag);
  for (const [name, value] of Object.entries(attributes)) element.setAttribute(name, String(value));
  for (const child of children) element.append(child);
  return element;
}

/** The path of an edge: a curve to the right, or below both ends for one that goes back. */
function edgePath([[x1, y1], [x2, y2]], reversed) {
  if (!reversed) {
    const bend = Math.max(30, (x2 - x1) / 2);
    return `M${x1},${y1} C${x1 + bend},${y1} ${x2 - bend},${y2} ${x2},${y2}`;
  }
  const below = Math.max(y1, y2) + 40;
  return `M${x1},${y1} C${x1 - 60},${below} ${x2 + 60},${below} ${x2},${y2}`;
}

export class GraphView {
  constructor(session) {
    this.title = 'Graph';
    this.session = session;
    this.options = { topics: true, debug: false, leaves: true, groups: true };
    this.marked = null;
    this.layout = null;
    this.onTopic = null;
    this.onNode = null;
    const toggle = (name, label, title) => h('label.graph-option', { title },
      h('input', {
        type: 'checkbox', checked: this.options[name], dataset: { option: name },
        onchange: (e) => { this.options[name] = e.target.checked; this.render(); },
      }), label);
    this.canvas = h('div.graph-canvas');
    this.inspector = h('div.graph-inspector');
    this.summary = h('span.note');
    this.element = h('section.view', { dataset: { view: 'graph' } },
      h('div.card.graph-card', {},
        h('div.graph-bar', {},
          toggle('topics', 'Topics', 'draw topics as boxes between their publishers and subscribers; off: node to node, labelled with the topics (rqt_graph "Nodes only")'),
          toggle('leaves', 'Leaf topics', 'topics with no publisher or no subscriber (rqt_graph "Dead sinks", "Leaf topics")'),
          toggle('debug', 'Debug', '/rosout, /parameter_events and hidden names (rqt_graph "Hide: Debug")'),
          toggle('groups', 'Namespaces', 'frame the nodes and topics of each namespace (rqt_graph "Group: Namespaces")'),
          h('span', { style: { flex: 1 } }), this.summary),
        h('div.graph-body', {}, this.canvas, this.inspector)));
    // drawn while the tab shows only
    session.on('graph', () => { if (!this.element.hidden) this.render(); });
  }

  /** The tab is shown: draw what the graph is now. */
  shown() {
    this.render();
  }

  /** How many publisher and subscriber links the tab would draw (its count). */
  links(model) {
    return graphOf(model, this.options).edges.length;
  }

  render() {
    const graph = graphOf(this.session.graph, this.options);
    this.layout = layoutGraph(graph, { groups: this.options.groups });
    const { boxes, edges, groups, width, height } = this.layout;
    const nodes = boxes.filter((b) => b.kind === 'node').length;
    this.summary.textContent = `${nodes} nodes, ${boxes.length - nodes} topics, ${edges.length} edges`;
    if (boxes.length === 0) {
      setChildren(this.canvas, h('div.empty', {}, 'No nodes. Run an executable or a launch file.'));
      this.inspect(null);
      return;
    }
    const marked = this.marked && boxes.some((b) => b.id === this.marked) ? this.marked : null;
    this.inspect(marked && boxes.find((b) => b.id === marked));
    const near = new Set(marked ? [marked] : []);
    for (const e of edges) if (e.from === marked || e.to === marked) { near.add(e.from); near.add(e.to); }
    const root = svg('svg', {
      viewBox: `${-MARGIN} ${-MARGIN} ${width + 2 * MARGIN} ${height + 2 * MARGIN + 40}`,
      width: width + 2 * MARGIN, height: height + 2 * MARGIN + 40, class: 'graph', role: 'img',
      'aria-label': this.summary.textContent,
    });
    root.append(svg('defs', {}, svg('marker', {
      id: 'graph-arrow', viewBox: '0 0 10 10', refX: 10, refY: 5, markerWidth: 7, markerHeight: 7, orient: 'auto-start-reverse',
    }, svg('path', { d: 'M0,0 L10,5 L0,10 z', class: 'graph-arrow' }))));
    for (const g of groups) {
      root.append(svg('rect', { x: g.x, y: g.y, width: g.width, height: g.height, rx: 8, class: 'graph-group', 'data-group': g.name }));
      root.append(svg('text', { x: g.x + 10, y: g.y + 16, class: 'graph-group-label' }, g.name));
    }
    for (const e of edges) {
      const on = marked && (e.from === marked || e.to === marked);
      const path = svg('path', {
        d: edgePath(e.points, e.reversed), class: `graph-edge${on ? ' marked' : ''}${marked && !on ? ' faded' : ''}`,
        'marker-end': 'url(#graph-arrow)', 'data-from': e.from, 'data-to': e.to,
      });
      root.append(path);
      if (e.label) {
        const [[x1, y1], [x2, y2]] = e.points;
        root.append(svg('text', { x: (x1 + x2) / 2, y: (y1 + y2) / 2 - 5, class: 'graph-edge-label', 'text-anchor': 'middle' }, e.label));
      }
    }
    for (const b of boxes) {
      const group = svg('g', {
        class: `graph-vertex ${b.kind}${b.id === marked ? ' marked' : ''}${marked && !near.has(b.id) ? ' faded' : ''}`,
        'data-id': b.id, tabindex: 0,
      });
      group.append(svg('title', {}, b.kind === 'node' ? `node ${b.label}` : `topic ${b.label}`));
      group.append(b.kind === 'node'
        ? svg('ellipse', { cx: b.x + b.width / 2, cy: b.y + b.height / 2, rx: b.width / 2, ry: b.height / 2 })
        : svg('rect', { x: b.x, y: b.y, width: b.width, height: b.height, rx: 3 }));
      group.append(svg('text', { x: b.x + b.width / 2, y: b.y + b.height / 2 + 4, 'text-anchor': 'middle' }, b.label));
      group.addEventListener('click', () => { this.marked = this.marked === b.id ? null : b.id; this.render(); });
      group.addEventListener('dblclick', () => {
        if (b.kind === 'topic' && this.onTopic) this.onTopic(b.label);
        if (b.kind === 'node' && this.onNode) this.onNode(b.label);
      });
      root.append(group);
    }
    setChildren(this.canvas, root);
  }

  /** Show a marked vertex in the inspector: a node's endpoints, a topic's type and ends. */
  inspect(box) {
    this.inspector.hidden = !box;
    if (!box) return;
    const model = this.session.graph;
    const list = (title, items) => [h('div.note', {}, `${title} (${items.length})`),
      h('ul.graph-list', {}, items.length ? items.map((text) => h('li', {}, text)) : h('li.note', {}, 'none'))];
    if (box.kind === 'node') {
      const node = model.nodes.find((n) => n.fqn === box.label);
      if (!node) return;
      setChildren(this.inspector, h('h3', {}, 'Node'), h('div.mono', {}, node.fqn),
        node.process ? h('div.note', {}, `process ${node.process}`) : null,
        ...list('publishes', node.publishers.map((e) => e.name)),
        ...list('subscribes', node.subscriptions.map((e) => e.name)),
        ...list('services', node.services.map((e) => e.name)),
        h('button', { onclick: () => this.onNode && this.onNode(node.fqn) }, 'Open in Nodes'));
      return;
    }
    const topic = model.topics.find((t) => t.name === box.label);
    const ends = (key) => model.nodes.filter((n) => n[key].some((e) => e.name === box.label)).map((n) => n.fqn);
    setChildren(this.inspector, h('h3', {}, 'Topic'), h('div.mono', {}, box.label),
      h('div.note', {}, topic ? topic.types.join(', ') : ''),
      ...list('publishers', ends('publishers')), ...list('subscribers', ends('subscriptions')),
      h('button', { onclick: () => this.onTopic && this.onTopic(box.label) }, 'Echo in Topics'));
  }
}
