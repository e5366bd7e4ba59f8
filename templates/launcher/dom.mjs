// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Small DOM helpers of the launcher page (no framework, no build step).

/**
 * Create an element: h('button.primary', {onclick, title}, 'Run').
 * The tag may carry classes after dots and an id after '#'.
 * Children may be strings, nodes, arrays, or null (skipped).
 */
export function h(spec, attributes = {}, ...children) {
  const [withoutId, id] = spec.split('#');
  const [tag, ...classes] = withoutId.split('.');
  const el = document.createElement(tag || 'div');
  if (id) el.id = id;
  if (classes.length) el.className = classes.join(' ');
  for (const [key, value] of Object.entries(attributes || {})) {
    if (value === undefined || value === null || value === false) continue;
    if (key.startsWith('on') && typeof value === 'function') {
      el.addEventListener(key.slice(2), value);
    } else if (key === 'dataset') {
      Object.assign(el.dataset, value);
    } else if (key === 'style' && typeof value === 'object') {
      Object.assign(el.style, value);
    } else if (key in el && typeof value !== 'string') {
      el[key] = value;
    } else {
      el.setAttribute(key, value === true ? '' : String(value));
    }
  }
  append(el, children);
  return el;
}

function append(el, children) {
  for (const child of children) {
    if (child === null || child === undefined || child === false) continue;
    if (Array.isArray(child)) append(el, child);
    else el.append(child instanceof Node ? child : String(child));
  }
}

/** Replace the children of an element. */
export function setChildren(el, ...children) {
  el.textContent = '';
  append(el, children);
  return el;
}

/** Human-readable byte count. */
export function formatBytes(n) {
  if (!n) return '0 B';
  if (n >= 1 << 20) return `${(n / (1 << 20)).toFixed(1)} MiB`;
  if (n >= 1 << 10) return `${(n / (1 << 10)).toFixed(0)} KiB`;
  return `${n} B`;
}

/** Split a command line like a shell does (quotes, backslashes). */
export function splitArgs(text) {
  const out = [];
  let current = '';
  let quote = null;
  let has = false;
  for (let i = 0; i < text.length; i++) {
    const c = text[i];
    if (quote) {
      if (c === quote) quote = null;
      else if (c === '\\' && quote === '"' && i + 1 < text.length) current += text[++i];
      else current += c;
    } else if (c === '"' || c === "'") {
      quote = c;
      has = true;
    } else if (c === '\\' && i + 1 < text.length) {
      current += text[++i];
      has = true;
    } else if (/\s/.test(c)) {
      if (has || current) out.push(current);
      current = '';
      has = false;
    } else {
      current += c;
    }
  }
  if (quote) throw new Error(`the ${quote === '"' ? 'double' : 'single'} quote is not closed`);
  if (has || current) out.push(current);
  return out;
}

/** Run `fn` at most once per animation frame, with the latest arguments. */
export function perFrame(fn) {
  let scheduled = false;
  let lastArgs = [];
  return (...args) => {
    lastArgs = args;
    if (scheduled) return;
    scheduled = true;
    requestAnimationFrame(() => {
      scheduled = false;
      fn(...lastArgs);
    });
  };
}

/** A short relative time: '3 s', '2 min'. */
export function formatAge(ms) {
  if (ms < 1000) return `${Math.round(ms)} ms`;
  if (ms < 60000) return `${(ms / 1000).toFixed(ms < 10000 ? 1 : 0)} s`;
  return `${Math.round(ms / 60000)} min`;
}

/**
 * A ROS name (or type) as text with `<wbr>` after each `/` and `_` (and the
 * `.` of parameter names), so that a narrow table cell wraps it only there,
 * never inside a word (launcher.css: no word-break in those cells):
 * h('td.name', {}, breakable('/add_two_ints')). Its textContent is the name.
 * A name shorter than `whole` characters gets none: it is not wrapped at all.
 * @param {string} name
 * @param {number} [whole]
 * @returns {Array<string|Node>}
 */
export function breakable(name, whole = 0) {
  const text = String(name);
  if (text.length < whole) return [text];
  const parts = [];
  for (const piece of text.split(/(?<=[/_.])/)) {
    if (parts.length) parts.push(document.createElement('wbr'));
    parts.push(piece);
  }
  return parts;
}

/** How long a name in a table's first column may be and still never wrap. */
export const WHOLE_NAME = 24;
