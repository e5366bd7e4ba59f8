// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Topics: the live list (type, publishers, subscribers) and, for the selected
// topic, echo (decoded fields), rate and bandwidth, plot, image and publish.
// Messages arrive in batches; decoding and drawing happen once per frame, so
// a 1 kHz topic does not freeze the page.

import { formatYaml } from '../../wasm_js/page/yaml.mjs';
import { formatBandwidth, TopicStats } from '../../wasm_js/page/stats.mjs';
import { imageKind } from '../../wasm_js/page/image.mjs';
import { breakable, h, setChildren, WHOLE_NAME } from '../dom.mjs';
import { ImageView } from './image_view.mjs';
import { MessageForm } from './message_form.mjs';
import { Plot } from './plot.mjs';

const ECHO_KEEP = 30;

export class TopicsView {
  constructor(session) {
    this.title = 'Topics';
    this.session = session;
    this.selected = null;
    this.inspector = null;
    this.showHidden = h('input', { type: 'checkbox', onchange: () => this.render(session.graph) });
    this.table = h('tbody');
    this.detail = h('div');
    this.element = h('section.view', { dataset: { view: 'topics' } },
      h('div.split', {},
        h('div.card', {},
          h('h3', {}, 'Topics', h('span', { style: { flex: 1 } }),
            h('label.note', {}, this.showHidden, ' hidden')),
          h('table.list', {}, h('thead', {}, h('tr', {}, h('th', {}, 'Name'), h('th', {}, 'Type'),
            h('th', { title: 'publishers' }, 'Pub'), h('th', { title: 'subscribers' }, 'Sub'))), this.table)),
        this.detail));
    session.on('graph', (model) => this.render(model));
    this.render(session.graph);
  }

  render(model) {
    const topics = model.topics.filter((t) => this.showHidden.checked || !t.hidden);
    if (topics.length === 0) {
      setChildren(this.table, h('tr', {}, h('td.empty', { colSpan: 4 }, 'No topics yet. Start a node.')));
    } else {
      setChildren(this.table, topics.map((t) => h(`tr.clickable${this.selected === t.name ? '.selected' : ''}`, {
        dataset: { topic: t.name }, onclick: () => this.select(t.name),
      }, h('td.name', {}, breakable(t.name, WHOLE_NAME), t.remote || t.remoteToo ? h('span.type', { title: 'on the rosbridge server' }, ' remote') : null), h('td.type', {}, breakable(t.types.join(', '))),
      h('td.num', {}, String(t.publishers)), h('td.num', {}, String(t.subscribers)))));
    }
    if (this.inspector) this.inspector.update(model.topics.find((t) => t.name === this.selected));
    else if (!this.selected) setChildren(this.detail, h('div.card.note', {}, 'Select a topic to echo it, measure its rate, plot it or publish to it.'));
  }

  select(name) {
    if (this.inspector) this.inspector.close();
    this.selected = name;
    const topic = this.session.graph.topics.find((t) => t.name === name);
    this.inspector = new TopicInspector(this.session, topic);
    setChildren(this.detail, this.inspector.element);
    this.render(this.session.graph);
  }
}

class TopicInspector {
  constructor(session, topic) {
    this.session = session;
    this.topic = topic;
    this.type = topic.types[0];
    this.registry = session.registry;
    this.canDecode = Boolean(this.registry && this.type && this.registry.has(this.type));
    this.stats = new TopicStats({ window: 1000 });
    this.received = 0;
    this.echoItems = [];
    this.paused = false;
    this.pending = [];
    this.scheduled = false;
    this.tab = 'echo';
    this.plot = null;
    this.imageView = null;
    this.decodeError = null;
    this.image = imageKind(this.registry, this.type);

    this.counter = h('strong', {}, '0');
    this.rateText = h('strong', {}, '–');
    this.echoList = h('div.echo-list', { dataset: { echo: topic.name } });
    this.pauseButton = h('button', { onclick: () => this.togglePause() }, 'Pause');
    this.statsGrid = h('div.stats');
    this.body = h('div');
    const tabs = [['echo', 'Echo'], ['rate', 'Rate'], ['plot', 'Plot']];
    if (this.image) tabs.push(['image', 'Image']);
    tabs.push(['publish', 'Publish']);
    this.tabButtons = tabs.map(([id, label]) => h('button', {
      dataset: { subtab: id }, onclick: () => this.show(id),
    }, label));
    this.element = h('div.card.topic-inspector', { dataset: { topic: topic.name } },
      h('h3', {}, topic.name, h('span.type', {}, this.type || 'unknown type')),
      h('div.subtabs', {}, this.tabButtons),
      h('div.echo-bar', {}, 'received ', this.counter, ' · rate ', this.rateText, this.pauseButton),
      this.body);
    this.show(this.image ? 'image' : 'echo');
    this.subscription = session.subscribe(topic.name, this.type, (batch) => this.onBatch(batch));
    this.timer = setInterval(() => this.renderStats(), 500);
  }

  update(topic) {
    if (topic) this.topic = topic;
  }

  show(tab) {
    this.tab = tab;
    for (const b of this.tabButtons) b.classList.toggle('active', b.dataset.subtab === tab);
    if (this.plot && tab !== 'plot') { this.plot.close(); this.plot = null; }
    if (tab === 'echo') {
      setChildren(this.body, this.canDecode ? this.echoList : this.noTypes());
      this.renderEcho();
    } else if (tab === 'rate') {
      setChildren(this.body, this.statsGrid);
      this.renderStats();
    } else if (tab === 'plot') {
      if (!this.canDecode) { setChildren(this.body, this.noTypes()); return; }
      this.plot = new Plot(this.registry, this.type);
      setChildren(this.body, this.plot.element);
    } else if (tab === 'image') {
      this.imageView = this.imageView || new ImageView(this.image === 'compressed');
      setChildren(this.body, this.imageView.element);
    } else if (tab === 'publish') {
      if (!this.canDecode) { setChildren(this.body, this.noTypes()); return; }
      this.publishPanel = this.publishPanel || new PublishPanel(this.session, this.topic.name, this.type);
      setChildren(this.body, this.publishPanel.element);
    }
  }

  noTypes() {
    return h('div.note', {}, `Messages of ${this.type || 'this topic'} cannot be decoded: no type description `
      + 'of that type is in the install space. Build its interface package with colcon build --wasm.');
  }

  togglePause() {
    this.paused = !this.paused;
    this.pauseButton.textContent = this.paused ? 'Resume' : 'Pause';
  }

  onBatch(batch) {
    for (const m of batch) this.stats.add(m.time, m.bytes.length);
    this.received += batch.length;
    if (this.paused) return;
    this.pending.push(...batch.slice(-(this.tab === 'plot' ? batch.length : ECHO_KEEP)));
    if (this.pending.length > 20000) this.pending.splice(0, this.pending.length - 20000);
    if (!this.scheduled) {
      this.scheduled = true;
      requestAnimationFrame(() => this.flush());
    }
  }

  decode(m) {
    try {
      return this.registry.decode(this.type, m.bytes);
    } catch (e) {
      this.decodeError = e.message;
      return null;
    }
  }

  flush() {
    this.scheduled = false;
    const batch = this.pending.splice(0);
    this.counter.textContent = String(this.received);
    if (!this.canDecode || batch.length === 0) return;
    if (this.tab === 'plot' && this.plot) {
      const values = [];
      const times = [];
      for (const m of batch) {
        const v = this.decode(m);
        if (v) { values.push(v); times.push(m.time); }
      }
      this.plot.add(values, times);
    } else if (this.tab === 'image' && this.imageView) {
      const v = this.decode(batch[batch.length - 1]);
      if (v) this.imageView.show(v);
    } else if (this.tab === 'echo') {
      for (const m of batch.slice(-ECHO_KEEP)) {
        const v = this.decode(m);
        if (v) this.echoItems.push({ seq: m.seq ?? this.received, time: m.time, value: v, size: m.bytes.length });
      }
      if (this.echoItems.length > ECHO_KEEP) this.echoItems.splice(0, this.echoItems.length - ECHO_KEEP);
      this.renderEcho();
    }
  }

  renderEcho() {
    if (this.tab !== 'echo' || !this.canDecode) return;
    if (this.echoItems.length === 0) {
      setChildren(this.echoList, h('div.empty', { style: { padding: '8px' } },
        this.decodeError ? `decoding failed: ${this.decodeError}` : 'Waiting for messages…'));
      return;
    }
    setChildren(this.echoList, this.echoItems.slice().reverse().map((item) => h('div.echo-msg', {},
      h('div.meta', {}, `#${item.seq} · ${item.size} bytes`),
      h('pre.yaml', {}, formatYaml(item.value, { maxArray: 32 })))));
  }

  renderStats() {
    const s = this.stats.summary(performance.now());
    const stale = s && s.sinceLastMs > Math.max(2000, 3000 / s.rate);
    this.rateText.textContent = s && !stale ? `${s.rate.toFixed(s.rate < 10 ? 2 : 1)} Hz` : '–';
    if (this.tab !== 'rate') return;
    const cell = (value, label) => h('div.stat', {}, h('div.value', {}, value), h('div.label', {}, label));
    setChildren(this.statsGrid, s ? [
      cell(`${s.rate.toFixed(2)} Hz`, 'average rate'),
      cell(`${(s.min * 1000).toFixed(2)} ms`, 'min interval'),
      cell(`${(s.max * 1000).toFixed(2)} ms`, 'max interval'),
      cell(`${(s.std * 1000).toFixed(2)} ms`, 'std dev'),
      cell(formatBandwidth(s.bytesPerSecond), 'bandwidth'),
      cell(`${s.meanBytes.toFixed(0)} B`, 'mean size'),
      cell(String(s.window), 'window (messages)'),
      cell(stale ? `${(s.sinceLastMs / 1000).toFixed(1)} s ago` : 'live', 'last message'),
    ] : h('div.empty', {}, 'Waiting for two messages…'));
  }

  close() {
    clearInterval(this.timer);
    if (this.publishPanel) this.publishPanel.close();
    if (this.plot) this.plot.close();
    if (this.subscription) this.subscription.close();
  }
}

/** Publish a message once, or at a rate, from fields or YAML. */
export class PublishPanel {
  constructor(session, topic, type) {
    this.session = session;
    this.form = new MessageForm(session.registry, type);
    this.rate = h('input', { type: 'number', min: '0.1', step: 'any', value: '1', 'aria-label': 'rate in Hz' });
    this.status = h('div.note');
    this.timer = null;
    this.sent = 0;
    this.publisher = null;
    this.onceButton = h('button.primary', { onclick: () => this.once() }, 'Publish once');
    this.rateButton = h('button', { onclick: () => this.toggleRate() }, 'Publish at rate');
    this.element = h('div.publish', { dataset: { publish: topic } }, this.form.element,
      h('div.actions-row', {}, this.onceButton, this.rateButton, this.rate, h('span.note', {}, 'Hz')),
      this.status);
    this.topic = topic;
    this.type = type;
  }

  close() {
    if (this.timer) this.toggleRate();
    if (this.publisher) this.publisher.close();
  }

  ensurePublisher() {
    if (!this.publisher) this.publisher = this.session.publisher(this.topic, this.type);
    return this.publisher;
  }

  async once() {
    let bytes;
    try { bytes = this.form.encode(); } catch (e) { return; }
    try {
      await this.ensurePublisher().publish(bytes);
      this.sent++;
      this.status.textContent = `published ${this.sent} message${this.sent === 1 ? '' : 's'} on ${this.topic}`;
    } catch (e) {
      this.status.textContent = '';
      this.form.error.textContent = `publishing failed: ${e.message}`;
    }
  }

  toggleRate() {
    if (this.timer) {
      clearInterval(this.timer);
      this.timer = null;
      this.rateButton.textContent = 'Publish at rate';
      return;
    }
    const hz = Number(this.rate.value);
    if (!(hz > 0)) { this.form.error.textContent = 'enter a rate above 0 Hz'; return; }
    let bytes;
    try { bytes = this.form.encode(); } catch (e) { return; }
    this.rateButton.textContent = 'Stop';
    this.timer = setInterval(() => {
      this.ensurePublisher().publish(bytes).then(() => {
        this.sent++;
        this.status.textContent = `published ${this.sent} messages at ${hz} Hz`;
      }, (e) => {
        if (this.timer) this.toggleRate();
        this.form.error.textContent = `publishing failed: ${e.message}`;
      });
    }, 1000 / hz);
  }
}
