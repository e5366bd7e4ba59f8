// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// A drag handle above the log dock: drag it up to give the logs more room,
// down to give the view (the 3D canvas, the plot) more. Double-click folds
// the dock to its minimum. The height is kept per install space.

import { h } from '../dom.mjs';

const MIN = 90;

/** The handle element for a dock; the dock's height is restored at once. */
export function dockSplitter(dock, storageKey) {
  const apply = (px) => {
    const max = Math.max(MIN, window.innerHeight - 220);
    const height = Math.min(max, Math.max(MIN, Math.round(px)));
    dock.style.height = `${height}px`;
    return height;
  };
  const saved = Number(localStorage.getItem(storageKey));
  if (saved > 0) apply(saved);
  const handle = h('div.dock-splitter', { title: 'drag to resize the log dock; double-click to fold it', role: 'separator', 'aria-orientation': 'horizontal' });
  handle.addEventListener('pointerdown', (e) => {
    e.preventDefault();
    handle.setPointerCapture(e.pointerId);
    const startY = e.clientY;
    const startHeight = dock.getBoundingClientRect().height;
    const move = (ev) => { apply(startHeight + (startY - ev.clientY)); };
    const up = () => {
      handle.removeEventListener('pointermove', move);
      handle.removeEventListener('pointerup', up);
      try { localStorage.setItem(storageKey, String(Math.round(dock.getBoundingClientRect().height))); } catch { /* private mode */ }
    };
    handle.addEventListener('pointermove', move);
    handle.addEventListener('pointerup', up);
  });
  handle.addEventListener('dblclick', () => {
    const height = apply(dock.getBoundingClientRect().height > MIN + 4 ? MIN : window.innerHeight * 0.34);
    try { localStorage.setItem(storageKey, String(height)); } catch { /* private mode */ }
  });
  return handle;
}
