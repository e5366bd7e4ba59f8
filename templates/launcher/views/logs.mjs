// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The log dock: one pane per process (and one for all), severity colours,
// and a crash report when a process dies. Lines are appended once per frame.

import { h, setChildren } from '../dom.mjs';

const MAX_LINES = 2000;

export class LogsDock {
  constructor(session) {
    this.session = session;
    this.current = 'all';
    this.pending = [];
    this.scheduled = false;
    this.follow = h('input', { type: 'checkbox', checked: true });
    this.tabs = h('div.logtabs');
    this.pane = h('div.logpane', { role: 'log', 'aria-live': 'off' });
    this.element = h('section.logs', {}, this.tabs, this.pane);
    session.on('processes', () => this.renderTabs());
    session.on('log', (proc, entry) => {
      if (this.current === 'all' || this.current === proc.id) {
        this.pending.push([proc, entry]);
        this.schedule();
      }
    });
    this.renderTabs();
    this.renderPane();
  }

  select(id) {
    this.current = id;
    this.renderTabs();
    this.renderPane();
  }

  renderTabs() {
    const procs = [...this.session.processes.values()];
    if (this.current !== 'all' && !this.session.processes.has(this.current)) this.current = 'all';
    const tab = (id, label, state) => h(`button${this.current === id ? '.active' : ''}`, {
      dataset: { log: id === 'all' ? 'all' : label }, onclick: () => this.select(id),
    }, state ? h(`span.status-dot.${state}`) : null, label);
    setChildren(this.tabs,
      tab('all', 'all output'),
      procs.map((p) => tab(p.id, p.label, p.state)),
      h('span.spacer'),
      h('label', {}, this.follow, 'follow'),
      h('button.link', { onclick: () => this.clearCurrent() }, 'clear'));
  }

  clearCurrent() {
    for (const p of this.session.processes.values()) {
      if (this.current === 'all' || this.current === p.id) p.log.length = 0;
    }
    this.renderPane();
  }

  entries() {
    if (this.current !== 'all') {
      const p = this.session.processes.get(this.current);
      return p ? p.log.map((e) => [p, e]) : [];
    }
    const all = [];
    for (const p of this.session.processes.values()) for (const e of p.log) all.push([p, e]);
    all.sort((a, b) => a[1].seq - b[1].seq);
    return all.slice(-MAX_LINES);
  }

  renderPane() {
    this.pending = [];
    const lines = this.entries();
    setChildren(this.pane, lines.length ? lines.map(([p, e]) => this.line(p, e))
      : h('div.empty', {}, this.current === 'all' ? 'The output of every process appears here.'
        : 'No output yet.'));
    this.scroll();
  }

  line(proc, entry) {
    if (entry.crash) {
      return h('div.crash', { dataset: { crash: proc.label, proc: proc.label, seq: entry.seq } },
        h('strong', {}, `✖ ${proc.label} crashed`), entry.text,
        entry.detail ? h('pre', {}, entry.detail) : null);
    }
    return h(`div.logline.${entry.severity}`, { dataset: { proc: proc.label, seq: entry.seq } },
      this.current === 'all' ? h('span.who', {}, `[${proc.label}]`) : null, entry.text);
  }

  schedule() {
    if (this.scheduled) return;
    this.scheduled = true;
    requestAnimationFrame(() => {
      this.scheduled = false;
      const batch = this.pending.splice(0);
      if (batch.length === 0) return;
      const empty = this.pane.querySelector('.empty');
      if (empty) empty.remove();
      const frag = document.createDocumentFragment();
      for (const [p, e] of batch.slice(-MAX_LINES)) frag.append(this.line(p, e));
      this.pane.append(frag);
      while (this.pane.childElementCount > MAX_LINES) this.pane.firstElementChild.remove();
      this.scroll();
    });
  }

  scroll() {
    if (this.follow.checked) this.pane.scrollTop = this.pane.scrollHeight;
  }
}
