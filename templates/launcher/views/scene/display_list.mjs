// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The 3D view's display list, as rviz's Displays panel: per display a
// checkbox, its name and kind, its status (errors in red), and its settings
// (topic, colour, size, colour transformer) when opened. Plain DOM; the
// displays themselves live in the loaded scene.

import { h, setChildren } from '../../dom.mjs';

const COLOR_MODES = ['RGB8', 'Intensity', 'AxisColor', 'FlatColor'];

export class DisplayList {
  /**
   * @param hooks {topicsOf(types) -> names, onChange(), onRemove(display)}
   */
  constructor(hooks) {
    this.hooks = hooks;
    this.displays = [];
    this.open = new Set();
    this.element = h('div.display-list');
  }

  setDisplays(displays) {
    this.displays = displays;
    this.render();
  }

  field(display, name) {
    const change = (value) => { display.set(name, value); this.hooks.onChange(); };
    if (name === 'topic') {
      const id = `topics-${display.name.replace(/\W/g, '_')}`;
      const options = this.hooks.topicsOf(display.constructor.types || []);
      return h('label.setting', {}, 'Topic',
        h('input.mono', { value: display.topic || '', list: id, dataset: { setting: 'topic' },
          onchange: (e) => change(e.target.value.trim()) }),
        h('datalist', { id }, options.map((t) => h('option', { value: t }))));
    }
    if (name === 'color') {
      return h('label.setting', {}, 'Colour',
        h('input', { type: 'color', value: display.color, onchange: (e) => change(e.target.value) }));
    }
    if (name === 'size') {
      return h('label.setting', {}, 'Size (m)',
        h('input', { type: 'number', step: '0.01', min: '0', value: String(display.size),
          onchange: (e) => change(e.target.value) }));
    }
    if (name === 'colorMode') {
      return h('label.setting', {}, 'Colour by',
        h('select', { onchange: (e) => change(e.target.value) },
          COLOR_MODES.map((m) => h('option', { value: m, selected: m === display.colorMode }, m))));
    }
    return null;
  }

  /** Refresh the status lines only (called a few times a second). */
  refreshStatus() {
    for (const row of this.element.querySelectorAll('.display')) {
      const display = this.displays[Number(row.dataset.index)];
      if (!display) continue;
      const s = display.status();
      const line = row.querySelector('.status');
      line.textContent = s.text;
      line.className = `status ${s.level}`;
      row.dataset.level = s.level;
    }
  }

  render() {
    setChildren(this.element, this.displays.map((display, index) => {
      const s = display.status();
      const opened = this.open.has(display);
      return h(`div.display${opened ? '.open' : ''}`, { dataset: { index: String(index), kind: display.constructor.kind, level: s.level } },
        h('div.row', {},
          h('input', { type: 'checkbox', checked: display.visible, title: 'shown',
            onchange: (e) => { display.setVisible(e.target.checked); this.hooks.onChange(); } }),
          h('button.link.name', { title: 'settings', onclick: () => {
            if (opened) this.open.delete(display); else this.open.add(display);
            this.render();
          } }, display.name),
          h('span.kind', {}, display.constructor.kind),
          h('button.icon', { title: `remove ${display.name}`, onclick: () => this.hooks.onRemove(display) }, '×')),
        h(`div.status.${s.level}`, {}, s.text),
        opened ? h('div.settings', {}, display.settings.map((f) => this.field(display, f))) : null);
    }));
  }
}
