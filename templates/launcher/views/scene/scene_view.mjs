// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The 3D tab: rviz's job in the page. A fixed frame, TF from /tf and
// /tf_static, displays (RobotModel, TF, LaserScan, PointCloud2, Marker and
// MarkerArray, Map, Path, Odometry, Pose, PoseArray), the TF tree with each
// transform's age, .rviz files (opened by hand or by ?rviz=package://...),
// and rviz's "2D Pose Estimate" and "2D Goal Pose" tools. three.js is loaded
// the first time the tab opens (or a robot description needs it), so the
// page starts as fast without it. The display set is kept per install space.

import { h, setChildren } from '../../dom.mjs';
import { TfBuffer } from './tf_buffer.mjs';
import { TopicFeed } from './topic_feed.mjs';
import { siteUrl } from '../../site_url.mjs';
import { DisplayList } from './display_list.mjs';
import { readRviz } from './rviz_file.mjs';
import { PoseTool, POSE_TOOLS } from './pose_tool.mjs';

const DEFAULT_DISPLAYS = [
  { kind: 'RobotModel', options: {} },
  { kind: 'TF', options: {} },
];
const TF_TYPE = 'tf2_msgs/msg/TFMessage';

export class SceneView {
  constructor(session, workspace) {
    this.title = '3D';
    this.session = session;
    this.storageKey = `colcon-wasm:3d:${workspace.install_base}`;
    this.tf = new TfBuffer();
    this.fixedFrame = 'base_link';
    this.displays = [];
    this.scene = null;
    this.loading = null;
    this.unsupported = [];
    this.problem = null;
    this.list = new DisplayList({
      topicsOf: (types) => session.graph.topics.filter((t) => t.types.some((x) => types.includes(x))).map((t) => t.name),
      onChange: () => this.save(),
      onRemove: (d) => this.removeDisplay(d),
    });
    this.frameSelect = h('select#fixed-frame', { onchange: (e) => this.setFixedFrame(e.target.value) });
    this.frameInput = h('input.mono', { placeholder: 'frame id', onchange: (e) => this.setFixedFrame(e.target.value.trim()) });
    this.addSelect = h('select', { onchange: (e) => { if (e.target.value) this.addDisplay(e.target.value, {}); e.target.value = ''; } },
      h('option', { value: '' }, 'Add display…'));
    this.rvizInput = h('input', { type: 'file', accept: '.rviz,.yaml', hidden: true,
      onchange: (e) => { const f = e.target.files[0]; if (f) f.text().then((t) => this.openRviz(t, f.name)); e.target.value = ''; } });
    this.notes = h('div.scene-notes');
    this.treeBody = h('tbody');
    this.canvasHost = h('div.scene-canvas-host');
    this.overlay = h('div.scene-overlay', {}, 'The 3D view loads when this tab opens.');
    this.toolbar = h('div.scene-toolbar', {},
      POSE_TOOLS.map((tool) => h('button', { dataset: { tool: tool.id }, title: tool.help, onclick: () => this.arm(tool) }, tool.label)),
      h('button', { onclick: () => this.scene && this.scene.setView(this.view || { distance: 6, yaw: 0.785, pitch: 0.6, focal: [0, 0, 0] }) }, 'Reset view'),
      h('span.spacer'),
      this.foldButton = h('button#scene-fold', { onclick: () => this.foldSide(!this.element.classList.contains('side-folded')) }, ''),
      this.toolNote = h('span.tool-note'));
    this.element = h('section.view.scene-view', { dataset: { view: '3d' } },
      h('div.scene-side', {},
        h('div.card', {}, h('h3', {}, 'Global options'),
          h('label.setting', {}, 'Fixed frame', this.frameSelect),
          h('label.setting', {}, 'or', this.frameInput)),
        h('div.card', {}, h('h3', {}, 'Displays', h('span.spacer'),
          h('button', { onclick: () => this.rvizInput.click(), title: 'open an rviz2 configuration' }, 'Open .rviz'), this.rvizInput),
        this.list.element, this.addSelect, this.notes),
        h('div.card', {}, h('h3', {}, 'TF tree'),
          h('table.list.tf-tree', {}, h('thead', {}, h('tr', {}, h('th', {}, 'Frame'), h('th', {}, 'Parent'), h('th.num', {}, 'Age'))), this.treeBody))),
      h('div.scene-main', {}, this.toolbar, h('div.scene-stage', {}, this.canvasHost, this.overlay)));
    this.tfFeeds = [
      new TopicFeed(session, '/tf', TF_TYPE, (values) => this.addTf(values, false)),
      new TopicFeed(session, '/tf_static', TF_TYPE, (values) => this.addTf(values, true)),
    ];
    this.restore(workspace);
    let folded = false;
    try { folded = localStorage.getItem(`${this.storageKey}:side`) === 'folded'; } catch { /* private mode */ }
    this.foldSide(folded, false);
    setInterval(() => this.tick(), 500);
  }

  /**
   * Fold the column of options, displays and TF tree away, for a wider view
   * (a 1024 px window), or bring it back; kept per install space.
   */
  foldSide(folded, keep = true) {
    this.element.classList.toggle('side-folded', folded);
    this.foldButton.textContent = folded ? '▸ Displays' : '◂ Fold displays';
    this.foldButton.title = folded ? 'show the options, the displays and the TF tree' : 'give the 3D view the whole width';
    if (keep) {
      try { localStorage.setItem(`${this.storageKey}:side`, folded ? 'folded' : 'open'); } catch { /* private mode */ }
    }
  }

  /** The tab was opened: load three.js and the displays (once). */
  shown() {
    this.load().catch(() => {});
    if (this.scene) this.scene.resize();
  }

  load() {
    if (!this.loading) {
      this.loading = (async () => {
        this.overlay.textContent = 'Loading three.js…';
        const [{ Scene3d }, { DISPLAYS }] = await Promise.all([import('./scene_3d.mjs'), import('./displays/index.mjs')]);
        this.DISPLAYS = DISPLAYS;
        setChildren(this.addSelect, h('option', { value: '' }, 'Add display…'),
          Object.keys(DISPLAYS).map((k) => h('option', { value: k }, k)));
        this.scene = new Scene3d(this.canvasHost);
        this.scene.beforeRender.push(() => { for (const d of this.displays) d.update(); });
        if (this.background) this.scene.renderer.setClearColor(this.background);
        if (this.grid) this.scene.setGrid(this.grid);
        if (this.view) this.scene.setView(this.view);
        this.ctx = { THREE: this.scene.THREE, root: this.scene.root, tf: this.tf, session: this.session,
          requestRender: () => this.scene.requestRender(), fixedFrame: () => this.fixedFrame };
        for (const spec of this.pending || []) this.createDisplay(spec.kind, spec.options);
        this.pending = null;
        this.poseTool = new PoseTool(this, (text) => { this.toolNote.textContent = text; });
        this.overlay.hidden = true;
        this.list.setDisplays(this.displays);
        this.element.dataset.ready = 'true';
        this.scene.requestRender();
      })();
      this.loading.catch((e) => {
        this.overlay.hidden = false;
        this.overlay.textContent = `The 3D view could not start: ${e.message}`;
        this.overlay.classList.add('error');
        console.error('3D view', e);
      });
    }
    return this.loading;
  }

  addTf(values, isStatic) {
    for (const v of values) this.tf.add(v, isStatic);
    if (!this.frameChosen && !this.tf.has(this.fixedFrame)) {
      // like rviz with its default: the first tree's root when the frame is unknown
      const rows = this.tf.tree();
      if (rows.length) this.fixedFrame = rows[0].frame;
    }
    if (this.scene) this.scene.requestRender();
  }

  setFixedFrame(frame) {
    if (!frame) return;
    this.fixedFrame = frame;
    this.frameChosen = true;
    this.frameInput.value = '';
    this.save();
    this.renderFrames();
    if (this.scene) this.scene.requestRender();
  }

  createDisplay(kind, options) {
    const cls = this.DISPLAYS[kind];
    if (!cls) return null;
    let name = options.name || kind;
    for (let i = 2; this.displays.some((d) => d.name === name); i++) name = `${options.name || kind} ${i}`;
    const display = new cls(this.ctx, { ...options, name });
    this.displays.push(display);
    return display;
  }

  /** Add a display (before three.js is loaded, it is created when it is). */
  addDisplay(kind, options) {
    if (!this.scene) {
      (this.pending ||= []).push({ kind, options });
      return;
    }
    this.createDisplay(kind, options);
    this.list.setDisplays(this.displays);
    this.save();
    this.scene.requestRender();
  }

  removeDisplay(display) {
    display.dispose();
    this.displays = this.displays.filter((d) => d !== display);
    this.list.setDisplays(this.displays);
    this.save();
    this.scene.requestRender();
  }

  /** Replace the displays, fixed frame and view with an .rviz file's. */
  async openRviz(text, source) {
    let config;
    try {
      config = readRviz(text);
    } catch (e) {
      setChildren(this.notes, h('div.status.error', {}, `${source}: ${e.message}`));
      return null;
    }
    await this.load();
    for (const d of this.displays) d.dispose();
    this.displays = [];
    for (const d of config.displays) this.createDisplay(d.kind, d.options);
    this.fixedFrame = config.fixedFrame;
    this.frameChosen = true;
    this.background = config.background;
    if (config.background) this.scene.renderer.setClearColor(config.background);
    this.grid = config.grid;
    this.scene.setGrid(config.grid || { visible: true });
    this.view = config.view;
    if (config.view) this.scene.setView(config.view);
    this.unsupported = config.unsupported;
    setChildren(this.notes, h('div.note', {}, `from ${source}`),
      config.unsupported.length ? h('div.status.warn.unsupported', {},
        `Not shown (no such display here): ${config.unsupported.map((u) => `${u.name} (${u.cls})`).join(', ')}`) : null);
    this.list.setDisplays(this.displays);
    this.renderFrames();
    this.save();
    this.scene.requestRender();
    return config;
  }

  /** Open an .rviz file of the install space: package://PKG/PATH or a site URL. */
  async openRvizUrl(uri) {
    const url = uri.startsWith('package://') ? siteUrl(`package/${uri.slice('package://'.length)}`) : uri;
    const response = await fetch(url);
    if (!response.ok) {
      setChildren(this.notes, h('div.status.error', {}, `${uri}: ${response.status} ${(await response.text()).slice(0, 200)}`));
      return null;
    }
    return this.openRviz(await response.text(), uri);
  }

  arm(tool) {
    if (!this.poseTool) return;
    this.poseTool.arm(tool);
    for (const b of this.toolbar.querySelectorAll('[data-tool]')) b.classList.toggle('active', b.dataset.tool === tool.id && this.poseTool.tool === tool);
  }

  renderFrames() {
    const frames = this.tf.frameIds();
    if (!frames.includes(this.fixedFrame)) frames.unshift(this.fixedFrame);
    const key = frames.join('\n');
    if (key !== this.frameKey || this.frameSelect.value !== this.fixedFrame) {
      this.frameKey = key;
      setChildren(this.frameSelect, frames.map((f) => h('option', { value: f, selected: f === this.fixedFrame }, f)));
    }
    setChildren(this.treeBody, this.tf.tree().map((row) => h('tr', { dataset: { frame: row.frame } },
      h('td.name', { style: { paddingLeft: `${4 + row.depth * 12}px` } }, row.frame),
      h('td.type', {}, row.parent || ''),
      h('td.num', {}, row.age === null ? '' : row.isStatic ? 'static' : `${row.age.toFixed(1)} s`))));
  }

  tick() {
    if (this.setCount) this.setCount(this.displays.length);
    if (this.element.hidden) return;
    this.renderFrames();
    this.list.refreshStatus();
    // moving frames age: redraw now and then for displays that depend on them
    if (this.scene) this.scene.requestRender();
  }

  save() {
    if (!this.scene) return;
    const state = {
      fixedFrame: this.frameChosen ? this.fixedFrame : null,
      displays: this.displays.map((d) => ({ kind: d.constructor.kind, options: {
        name: d.name, topic: d.topic, color: d.color, size: d.size, visible: d.visible, colorMode: d.colorMode } })),
    };
    try { localStorage.setItem(this.storageKey, JSON.stringify(state)); } catch { /* private mode */ }
  }

  restore() {
    let state = null;
    try { state = JSON.parse(localStorage.getItem(this.storageKey) || 'null'); } catch { state = null; }
    this.pending = state && Array.isArray(state.displays) ? state.displays : DEFAULT_DISPLAYS;
    if (state && state.fixedFrame) { this.fixedFrame = state.fixedFrame; this.frameChosen = true; }
  }
}
