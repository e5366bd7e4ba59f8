// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The log dock: one pane per process (and one for all), severity colours,
// and a crash report when a process dies. Lines are appended once per frame;
// in "all output" they are in the order they were logged (log_order.mjs).

import { h, setChildren } from '../dom.mjs';
import { insertionIndex, logStamp, mergeByStamp } from './log_order.mjs';

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
    // the selected process' standard input, like its terminal
    this.stdinInput = h('input', {
      type: 'text', autocomplete: 'off', spellcheck: false, 'aria-label': 'standard input',
    });
    this.stdinRow = h('form.stdin', { onsubmit: (e) => this.sendLine(e) },
      h('span.prompt', {}, 'stdin ›'), this.stdinInput,
      h('button', { type: 'submit', title: 'Send the line (Enter)' }, 'Send'),
      h('button', { type: 'button', title: 'End of file (Ctrl-D)', onclick: () => this.endOfFile() }, 'EOF'));
    this.stdinInput.addEventListener('keydown', (e) => {
      if (e.key === 'd' && e.ctrlKey) {
        e.preventDefault();
        this.endOfFile();
      }
    });
    this.element = h('section.logs', {}, this.tabs, this.pane, this.stdinRow);
    session.on('processes', () => {
      this.renderTabs();
      this.renderStdin();
    });
    session.on('log', (proc, entry) => {
      if (this.current === 'all' || this.current === proc.id) {
        this.pending.push([proc, entry]);
        this.schedule();
      }
    });
    this.renderTabs();
    this.renderPane();
    this.renderStdin();
  }

  select(id) {
    this.current = id;
    this.renderTabs();
    this.renderPane();
    this.renderStdin();
  }

  /** Show the stdin line for a running process' tab only. */
  renderStdin() {
    const p = this.current === 'all' ? null : this.session.processes.get(this.current);
    const running = !!p && p.state === 'running' && !p.noStdin;
    this.stdinRow.hidden = !running;
    if (running) this.stdinInput.placeholder = `type a line for ${p.label}, Enter to send`;
  }

  sendLine(event) {
    event.preventDefault();
    if (this.current === 'all') return;
    const line = this.stdinInput.value;
    this.stdinInput.value = '';
    this.session.sendStdin(this.current, line).catch(() => this.renderStdin());
  }

  endOfFile() {
    if (this.current !== 'all') this.session.closeStdin(this.current);
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
    // the last MAX_LINES of each process hold the last MAX_LINES of all
    const lists = [...this.session.processes.values()].map((p) => p.log.slice(-MAX_LINES).map((e) => [p, e]));
    return mergeByStamp(lists, ([, e]) => logStamp(e), ([, e]) => e.seq).slice(-MAX_LINES);
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
    const el = entry.crash
      ? h('div.crash', { dataset: { crash: proc.label, proc: proc.label, seq: entry.seq } },
        h('strong', {}, `✖ ${proc.label} crashed`), entry.text,
        entry.detail ? h('pre', {}, entry.detail) : null)
      : h(`div.logline.${entry.severity}`, { dataset: { proc: proc.label, seq: entry.seq } },
        this.current === 'all' ? h('span.who', {}, `[${proc.label}]`) : null, entry.text);
    el.logOrder = { stamp: logStamp(entry), proc: proc.id };
    return el;
  }

  /** Add a line where it belongs: at the end, or in "all output" before the later-logged lines of others. */
  place(el) {
    const lines = this.pane.children;
    const at = this.current === 'all'
      ? insertionIndex(lines.length, (i) => lines[i].logOrder, el.logOrder) : lines.length;
    this.pane.insertBefore(el, lines[at] || null);
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
      for (const [p, e] of batch.slice(-MAX_LINES)) this.place(this.line(p, e));
      while (this.pane.childElementCount > MAX_LINES) this.pane.firstElementChild.remove();
      this.scroll();
    });
  }

  scroll() {
    if (this.follow.checked) this.pane.scrollTop = this.pane.scrollHeight;
  }
}
