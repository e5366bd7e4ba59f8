// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Nodes: the live list and, for the selected node, what `ros2 node info` shows.

import { breakable, h, setChildren, WHOLE_NAME } from '../dom.mjs';

export class NodesView {
  constructor(session) {
    this.title = 'Nodes';
    this.session = session;
    this.selected = null;
    this.table = h('tbody');
    this.detail = h('div');
    this.element = h('section.view', { dataset: { view: 'nodes' } },
      h('div.split', {},
        h('div.card', {}, h('h3', {}, 'Nodes'),
          h('table.list', {}, h('thead', {}, h('tr', {}, h('th', {}, 'Node'), h('th', {}, 'Process'),
            h('th', { title: 'publishers' }, 'Pub'), h('th', { title: 'subscriptions' }, 'Sub'),
            h('th', { title: 'services' }, 'Srv'))), this.table)),
        this.detail));
    session.on('graph', (model) => this.render(model));
    this.render(session.graph);
  }

  render(model) {
    setChildren(this.table, model.nodes.length ? model.nodes.map((n) => h(`tr.clickable${this.selected === n.fqn ? '.selected' : ''}`, {
      dataset: { node: n.fqn }, onclick: () => { this.selected = n.fqn; this.render(this.session.graph); },
    }, h('td.name', {}, breakable(n.fqn, WHOLE_NAME)), h('td.type', {}, breakable(n.process || '')),
    h('td.num', {}, String(n.publishers.length)), h('td.num', {}, String(n.subscriptions.length)),
    h('td.num', {}, String(n.services.length)))) : h('tr', {}, h('td.empty', { colSpan: 5 }, 'No nodes. Run an executable.')));
    const node = model.nodes.find((n) => n.fqn === this.selected);
    if (!node) {
      setChildren(this.detail, h('div.card.note', {}, this.selected ? `${this.selected} has left the graph.` : 'Select a node to see its endpoints.'));
      return;
    }
    const section = (title, items) => [h('div.note', { style: { marginTop: '8px' } }, title),
      items.length ? h('table.list', {}, h('tbody', {}, items.map((e) => h('tr', {}, h('td.name', {}, breakable(e.name, WHOLE_NAME)), h('td.type', {}, breakable(e.type))))))
        : h('div.empty', {}, 'none')];
    setChildren(this.detail, h('div.card', { dataset: { nodeInfo: node.fqn } }, h('h3', {}, node.fqn, node.process ? h('span.type', {}, node.process) : null),
      section('Subscribers', node.subscriptions), section('Publishers', node.publishers),
      section('Service Servers', node.services), section('Service Clients', node.clients)));
  }
}
