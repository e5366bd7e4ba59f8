// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// What tests/test_page_graph.py reads of the page's Graph tab, evaluated in
// the page by a page_session.mjs `until` step (its value, true, ends the step).

window.graphProbe = {
  svg: () => document.querySelector('section[data-view=graph] svg.graph'),
  labels(kind) {
    const svg = this.svg();
    return svg && [...svg.querySelectorAll(`.graph-vertex.${kind} text`)].map((t) => t.textContent).sort().join(',');
  },
  edges() {
    const svg = this.svg();
    return svg ? svg.querySelectorAll('path.graph-edge').length : null;
  },
  edgeLabels() {
    const svg = this.svg();
    return svg && [...svg.querySelectorAll('.graph-edge-label')].map((t) => t.textContent).join(',');
  },
  /** The first namespace frame and the vertices inside it. */
  group() {
    const svg = this.svg();
    const frame = svg && svg.querySelector('rect.graph-group');
    if (!frame) return null;
    const f = frame.getBBox();
    const inside = [...svg.querySelectorAll('.graph-vertex')].filter((v) => {
      const b = v.getBBox();
      return b.x >= f.x && b.y >= f.y && b.x + b.width <= f.x + f.width && b.y + b.height <= f.y + f.height;
    });
    return { name: frame.dataset.group, inside: inside.map((v) => v.dataset.id).sort() };
  },
  /** Click (or double-click) the vertex with this data-id. */
  press(id, type = 'click') {
    const vertex = [...this.svg().querySelectorAll('.graph-vertex')].find((v) => v.dataset.id === id);
    if (!vertex) return null;
    vertex.dispatchEvent(new MouseEvent(type, { bubbles: true }));
    return true;
  },
  inspector() {
    const panel = document.querySelector('.graph-inspector');
    return panel && !panel.hidden && panel.textContent;
  },
  option(name) {
    document.querySelector(`[data-option=${name}]`).click();
    return true;
  },
  widths() {
    return { w: document.documentElement.scrollWidth, inner: innerWidth, svg: this.svg().getBoundingClientRect().width };
  },
};
true;
