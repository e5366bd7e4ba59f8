// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The processes started from this page: state, stop, and their logs on click.

import { h, setChildren } from '../dom.mjs';

const STATE_TEXT = {
  starting: 'starting', running: 'running', exited: 'exited', crashed: 'crashed', stopped: 'stopped',
};

export class ProcessesView {
  constructor(session) {
    this.session = session;
    this.onSelect = null;
    this.selected = null;
    this.count = h('span.count', {}, '0');
    this.list = h('div.processes');
    this.clear = h('button.link', { onclick: () => session.forgetFinished(), title: 'Remove finished processes' }, 'clear');
    this.element = h('section', {}, h('h2', {}, 'Processes', this.count, h('span', { style: { flex: 1 } }), this.clear), this.list);
    session.on('processes', () => this.render());
    this.render();
  }

  render() {
    const procs = [...this.session.processes.values()];
    this.count.textContent = String(procs.length);
    if (procs.length === 0) {
      setChildren(this.list, h('div.empty', {}, 'Nothing running. Press ▶ Run next to an executable.'));
      return;
    }
    setChildren(this.list, procs.map((p) => {
      const live = p.state === 'starting' || p.state === 'running';
      const detail = p.state === 'crashed' ? 'crashed' : (p.state === 'exited' ? `exit ${p.exit?.code ?? ''}` : STATE_TEXT[p.state]);
      return h(`div.proc${this.selected === p.id ? '.selected' : ''}`, {
        dataset: { proc: p.label, state: p.state },
        title: `${p.pkg}/${p.exe} ${p.args.join(' ')}`,
        onclick: () => this.select(p.id),
      },
      h(`span.status-dot.${p.state}`),
      h('span.label', {}, p.label),
      h('span.state', {}, detail),
      live ? h('button.stop', {
        onclick: (e) => { e.stopPropagation(); this.session.stopProcess(p.id); },
        title: `Stop ${p.label}`,
      }, '■ Stop') : null);
    }));
  }

  select(id) {
    this.selected = id;
    this.render();
    if (this.onSelect) this.onSelect(id);
  }
}
