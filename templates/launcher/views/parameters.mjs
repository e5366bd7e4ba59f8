// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Parameters of a node: list, get and set, over the node's rcl_interfaces
// parameter services (as ros2 param list/get/set do).

import { ParameterClient } from '../../wasm_js/page/ros_clients.mjs';
import { parseYaml } from '../../wasm_js/page/yaml.mjs';
import { breakable, h, setChildren, WHOLE_NAME } from '../dom.mjs';

function show(value) {
  if (Array.isArray(value)) return `[${value.map((v) => (typeof v === 'string' ? JSON.stringify(v) : String(v))).join(', ')}]`;
  return typeof value === 'string' ? value : String(value);
}

export class ParametersView {
  constructor(session) {
    this.title = 'Parameters';
    this.session = session;
    this.node = null;
    this.select = h('select', { onchange: () => this.load(this.select.value), 'aria-label': 'node' });
    this.body = h('div');
    this.element = h('section.view', { dataset: { view: 'parameters' } },
      h('div.card', {}, h('h3', {}, 'Parameters of', this.select,
        h('button', { onclick: () => this.load(this.node) }, 'Refresh')), this.body));
    session.on('graph', (model) => this.renderNodes(model));
    this.renderNodes(session.graph);
  }

  renderNodes(model) {
    const names = model.nodes.map((n) => n.fqn);
    const current = this.select.value;
    setChildren(this.select, h('option', { value: '' }, names.length ? '— choose a node —' : '(no nodes)'),
      names.map((n) => h('option', { value: n, selected: n === current }, n)));
    if (!this.node) setChildren(this.body, h('div.note', {}, 'Choose a node to list its parameters.'));
  }

  async load(node) {
    this.node = node || null;
    if (!node) return;
    const model = this.session.graph.nodes.find((n) => n.fqn === node);
    const prefix = node === '/' ? '' : node;
    if (model && !model.services.some((s) => s.name === `${prefix}/list_parameters`)) {
      setChildren(this.body, h('div.note', {}, `${node} offers no parameter services (${prefix}/list_parameters): `
        + 'only nodes built on rclcpp have them.'));
      return;
    }
    let client;
    try {
      client = new ParameterClient(this.session.toolsBus(), this.session.registry, node);
      this.session.registry.service('rcl_interfaces/srv/ListParameters');
    } catch (e) {
      setChildren(this.body, h('div.error-text', {}, `Parameters cannot be read: ${e.message}`));
      return;
    }
    setChildren(this.body, h('div.note', {}, 'listing…'));
    try {
      const names = await client.list();
      const values = names.length ? await client.get(names) : [];
      this.render(client, values);
    } catch (e) {
      setChildren(this.body, h('div.error-text', {}, e.message));
    }
  }

  render(client, values) {
    if (values.length === 0) {
      setChildren(this.body, h('div.empty', {}, 'This node has no parameters.'));
      return;
    }
    setChildren(this.body, h('table.list', { dataset: { params: client.node } },
      h('thead', {}, h('tr', {}, h('th', {}, 'Name'), h('th', {}, 'Type'), h('th', {}, 'Value'), h('th', {}, ''))),
      h('tbody', {}, values.map((p) => {
        const input = h('input', { type: 'text', value: show(p.value), spellcheck: false, dataset: { param: p.name },
          style: { width: '100%', fontFamily: 'var(--mono)' } });
        const status = h('div.note');
        const set = async () => {
          let value;
          try {
            value = p.type === 'string' ? input.value : parseYaml(input.value);
            const result = await client.set(p.name, value);
            status.className = result.successful ? 'ok-text' : 'error-text';
            status.textContent = result.successful ? 'set' : `refused: ${result.reason}`;
          } catch (e) {
            status.className = 'error-text';
            status.textContent = e.message;
          }
        };
        input.addEventListener('keydown', (e) => { if (e.key === 'Enter') set(); });
        return h('tr', {}, h('td.name', {}, breakable(p.name, WHOLE_NAME)), h('td.type', {}, p.type), h('td', {}, input, status),
          h('td', {}, h('button', { onclick: set }, 'Set')));
      }))));
  }
}
