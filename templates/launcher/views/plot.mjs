// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// A live line plot of numeric fields over time (canvas, redrawn once per frame).

import { asNumber, getPath, numericPaths } from '../../wasm_js/page/fields.mjs';
import { h, setChildren } from '../dom.mjs';

const COLORS = ['#2f7ed8', '#d0352b', '#1e9e5a', '#c98a06', '#8e44ad', '#16a2b8', '#e67e22', '#34495e'];

export class Plot {
  constructor(registry, type, { windowSeconds = 10 } = {}) {
    this.windowSeconds = windowSeconds;
    this.paths = numericPaths(registry, type);
    this.series = new Map();  // path -> {color, t: [], v: []}
    this.paused = false;
    this.canvas = h('canvas.plot', { width: 800, height: 280 });
    this.fields = h('div.plot-fields');
    this.pauseButton = h('button', { onclick: () => this.togglePause() }, 'Pause');
    this.windowSelect = h('select', { onchange: () => { this.windowSeconds = Number(this.windowSelect.value); } },
      [5, 10, 30, 60].map((s) => h('option', { value: s, selected: s === windowSeconds }, `${s} s`)));
    const initial = this.paths.filter((p) => !/stamp|count|step|seq|time|id$/.test(p)).slice(0, 2);
    (initial.length ? initial : this.paths.slice(0, 1)).forEach((p) => this.enable(p));
    this.renderFields();
    this.element = this.paths.length
      ? h('div.plot', {}, this.fields, h('div.plot-wrap', {}, this.canvas),
        h('div.actions-row', {}, this.pauseButton, h('span.note', {}, 'window'), this.windowSelect))
      : h('div.note', {}, `${type} has no numeric field to plot.`);
    this.draw = this.draw.bind(this);
    this.frame = requestAnimationFrame(this.draw);
  }

  enable(path) {
    const color = COLORS[this.series.size % COLORS.length];
    this.series.set(path, { color, t: [], v: [] });
  }

  renderFields() {
    setChildren(this.fields, this.paths.map((path) => {
      const s = this.series.get(path);
      const box = h('input', {
        type: 'checkbox', checked: Boolean(s), dataset: { path },
        onchange: () => {
          if (box.checked) this.enable(path); else this.series.delete(path);
          this.renderFields();
        },
      });
      return h('label', {}, box, s ? h('span.swatch', { style: { background: s.color } }) : null, path);
    }));
  }

  togglePause() {
    this.paused = !this.paused;
    this.pauseButton.textContent = this.paused ? 'Resume' : 'Pause';
  }

  /** Add decoded messages received at times (ms, performance.now()). */
  add(values, times) {
    if (this.paused) return;
    for (const [path, s] of this.series) {
      for (let i = 0; i < values.length; i++) {
        s.t.push(times[i]);
        s.v.push(asNumber(getPath(values[i], path)));
      }
    }
  }

  draw() {
    this.frame = requestAnimationFrame(this.draw);
    if (!this.canvas.isConnected || this.paused) return;
    const ratio = window.devicePixelRatio || 1;
    const cw = this.canvas.clientWidth;
    const chh = this.canvas.clientHeight;
    if (this.canvas.width !== Math.round(cw * ratio)) {
      this.canvas.width = Math.round(cw * ratio);
      this.canvas.height = Math.round(chh * ratio);
    }
    const ctx = this.canvas.getContext('2d');
    ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
    ctx.clearRect(0, 0, cw, chh);
    const now = performance.now();
    const start = now - this.windowSeconds * 1000;
    let lo = Infinity;
    let hi = -Infinity;
    for (const s of this.series.values()) {
      let cut = 0;
      while (cut < s.t.length && s.t[cut] < start) cut++;
      if (cut > 0) { s.t.splice(0, cut); s.v.splice(0, cut); }
      for (const v of s.v) if (Number.isFinite(v)) { if (v < lo) lo = v; if (v > hi) hi = v; }
    }
    if (!(hi >= lo)) { lo = -1; hi = 1; }
    if (hi === lo) { hi += 1; lo -= 1; }
    const pad = (hi - lo) * 0.08;
    lo -= pad; hi += pad;
    const left = 52; const right = 8; const top = 8; const bottom = 22;
    const w = cw - left - right; const hh = chh - top - bottom;
    const x = (t) => left + ((t - start) / (this.windowSeconds * 1000)) * w;
    const y = (v) => top + (1 - (v - lo) / (hi - lo)) * hh;
    ctx.font = '11px system-ui, sans-serif';
    ctx.fillStyle = '#6b7486';
    ctx.strokeStyle = '#eef0f4';
    ctx.lineWidth = 1;
    const step = niceStep((hi - lo) / 4);
    for (let v = Math.ceil(lo / step) * step; v <= hi; v += step) {
      const value = Math.abs(v) < step / 1e6 ? 0 : v;  // no -6.8e-10 for zero
      const yy = Math.round(y(value)) + 0.5;
      ctx.beginPath(); ctx.moveTo(left, yy); ctx.lineTo(left + w, yy); ctx.stroke();
      ctx.fillText(tickLabel(value, step), 4, yy + 4);
    }
    for (let s = 0; s <= this.windowSeconds; s += this.windowSeconds <= 10 ? 1 : 5) {
      const xx = Math.round(x(start + s * 1000)) + 0.5;
      const label = timeLabel(this.windowSeconds - s);
      // the last label ends at the right edge, the others are centred on their tick
      const width = ctx.measureText(label).width;
      ctx.fillText(label, s === this.windowSeconds ? cw - right - width : xx - width / 2, chh - 6);
    }
    for (const s of this.series.values()) {
      ctx.strokeStyle = s.color;
      ctx.lineWidth = 1.6;
      ctx.beginPath();
      let pen = false;
      for (let i = 0; i < s.t.length; i++) {
        if (!Number.isFinite(s.v[i])) { pen = false; continue; }
        const px = x(s.t[i]); const py = y(s.v[i]);
        if (pen) ctx.lineTo(px, py); else ctx.moveTo(px, py);
        pen = true;
      }
      ctx.stroke();
    }
  }

  close() {
    cancelAnimationFrame(this.frame);
  }
}

/**
 * A grid step of 1, 2 or 5 times a power of ten, close to `raw`.
 * @param {number} raw
 * @returns {number}
 */
export function niceStep(raw) {
  if (!(raw > 0) || !Number.isFinite(raw)) return 1;
  const power = 10 ** Math.floor(Math.log10(raw));
  const f = raw / power;
  return (f < 1.5 ? 1 : f < 3.5 ? 2 : f < 7.5 ? 5 : 10) * power;
}

/**
 * The x axis label of a time `secondsAgo` before now: '-5s', and '0s' (never
 * '-0s') for now.
 * @param {number} secondsAgo
 * @returns {string}
 */
export function timeLabel(secondsAgo) {
  const whole = Math.round(secondsAgo);
  return whole === 0 ? '0s' : `${-whole}s`;
}

/**
 * A tick label with as many decimals as the step needs.
 * @param {number} v
 * @param {number} step
 * @returns {string}
 */
export function tickLabel(v, step) {
  if (v === 0) return '0';
  if (Math.abs(v) >= 1e5 || Math.abs(v) < 1e-4) {
    const digits = Math.min(12, Math.max(1, Math.ceil(Math.log10(Math.abs(v) / step))));
    return v.toExponential(digits);
  }
  return v.toFixed(Math.min(12, Math.max(0, -Math.floor(Math.log10(step)))));
}
