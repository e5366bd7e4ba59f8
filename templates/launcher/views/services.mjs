// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Services: the live list and a call form (request fields or YAML, the
// response decoded, the round-trip time).

import { formatYaml } from '../../wasm_js/page/yaml.mjs';
import { breakable, h, setChildren, WHOLE_NAME } from '../dom.mjs';
import { MessageForm } from './message_form.mjs';

export class ServicesView {
  constructor(session) {
    this.title = 'Services';
    this.session = session;
    this.selected = null;
    this.showHidden = h('input', { type: 'checkbox', onchange: () => this.render(session.graph) });
    this.table = h('tbody');
    this.detail = h('div');
    this.element = h('section.view', { dataset: { view: 'services' } },
      h('div.split', {},
        h('div.card', {},
          h('h3', {}, 'Services', h('span', { style: { flex: 1 } }), h('label.note', {}, this.showHidden, ' hidden')),
          h('table.list', {}, h('thead', {}, h('tr', {}, h('th', {}, 'Name'), h('th', {}, 'Type'),
            h('th', { title: 'servers' }, 'Srv'), h('th', { title: 'clients' }, 'Cli'))), this.table)),
        this.detail));
    session.on('graph', (model) => this.render(model));
    this.render(session.graph);
  }

  render(model) {
    const services = model.services.filter((s) => this.showHidden.checked || !s.hidden);
    setChildren(this.table, services.length ? services.map((s) => h(`tr.clickable${this.selected === s.name ? '.selected' : ''}`, {
      dataset: { service: s.name }, onclick: () => this.select(s),
    }, h('td.name', {}, breakable(s.name, WHOLE_NAME), s.remote || s.remoteToo ? h('span.type', { title: 'on the rosbridge server' }, ' remote') : null), h('td.type', {}, breakable(s.types.join(', '))), h('td.num', {}, String(s.servers)),
    h('td.num', {}, String(s.clients)))) : h('tr', {}, h('td.empty', { colSpan: 4 }, 'No services yet.')));
    if (!this.selected) setChildren(this.detail, h('div.card.note', {}, 'Select a service to call it.'));
  }

  select(service) {
    this.selected = service.name;
    setChildren(this.detail, new CallPanel(this.session, service.name, service.types[0]).element);
    this.render(this.session.graph);
  }
}

export class CallPanel {
  constructor(session, name, type) {
    this.session = session;
    this.name = name;
    this.type = type;
    const registry = session.registry;
    let entry = null;
    try { entry = registry && registry.service(type); } catch (e) { entry = null; }
    this.result = h('div');
    if (!entry) {
      this.element = h('div.card', {}, h('h3', {}, name, h('span.type', {}, type)),
        h('div.note', {}, `${type} cannot be called from here: its type description is not in the install space.`));
      return;
    }
    this.entry = entry;
    this.form = new MessageForm(registry, entry.request);
    this.timeout = h('input', { type: 'number', min: '0.1', step: 'any', value: '5', 'aria-label': 'timeout in seconds' });
    this.button = h('button.primary', { onclick: () => this.call() }, 'Call');
    this.element = h('div.card.call-panel', { dataset: { call: name } },
      h('h3', {}, name, h('span.type', {}, type)),
      h('div.note', {}, 'Request'), this.form.element,
      h('div.actions-row', {}, this.button, h('span.note', {}, 'timeout'), this.timeout, h('span.note', {}, 's')),
      this.result);
  }

  async call() {
    let bytes;
    try { bytes = this.form.encode(); } catch (e) { return; }
    this.button.disabled = true;
    setChildren(this.result, h('div.note', {}, 'calling…'));
    const started = performance.now();
    try {
      const response = await this.session.call(this.name, this.type, bytes, Number(this.timeout.value) * 1000);
      const ms = performance.now() - started;
      const value = this.session.registry.decode(this.entry.response, response);
      setChildren(this.result, h('div.result', { dataset: { response: this.name } },
        h('div.ok-text', {}, `response in ${ms.toFixed(1)} ms`), h('pre.yaml', {}, formatYaml(value))));
    } catch (e) {
      setChildren(this.result, h('div.result.error', {}, h('div.error-text', {}, e.message)));
    } finally {
      this.button.disabled = false;
    }
  }
}
