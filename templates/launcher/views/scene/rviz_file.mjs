// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// .rviz files (rviz2's YAML configuration): the fixed frame, the background,
// the displays (Group displays flattened) with their topics, colours and
// sizes, and the Orbit view — as the 3D view's settings. A display class it
// cannot show is listed with its name, not dropped.

import { parseYaml } from '../../../wasm_js/page/yaml.mjs';

/** rviz_default_plugins/<Class> -> the 3D view's display kind. */
export const RVIZ_CLASSES = {
  TF: 'TF', RobotModel: 'RobotModel', LaserScan: 'LaserScan', PointCloud2: 'PointCloud2',
  Marker: 'Marker', MarkerArray: 'Marker', Map: 'Map', Path: 'Path', Odometry: 'Odometry',
  Pose: 'Pose', PoseArray: 'PoseArray',
};

function topicOf(value) {
  if (value && typeof value === 'object') return value.Value || null;
  return typeof value === 'string' && value ? value : null;
}

function number(value, fallback) {
  const n = Number(value);
  return Number.isFinite(n) ? n : fallback;
}

/** rviz's colour "r; g; b" (0-255) as '#rrggbb'. */
export function rvizColor(value) {
  if (typeof value !== 'string') return null;
  const parts = value.split(';').map((x) => Number(x.trim()));
  if (parts.length !== 3 || parts.some((x) => !Number.isFinite(x))) return null;
  return `#${parts.map((x) => Math.max(0, Math.min(255, Math.round(x))).toString(16).padStart(2, '0')).join('')}`;
}

function display(entry) {
  const cls = String(entry.Class || '');
  const short = cls.split('/').pop();
  const kind = RVIZ_CLASSES[short];
  const options = {
    name: entry.Name || short,
    visible: entry.Enabled !== false && entry.Value !== false,
    topic: topicOf(entry.Topic) || topicOf(entry['Description Topic']),
  };
  const color = rvizColor(entry.Color);
  if (color) options.color = color;
  const size = entry['Size (m)'] ?? entry['Shaft Length'] ?? entry.Length ?? entry['Marker Scale'];
  if (size !== undefined && kind !== 'RobotModel') options.size = number(size, undefined);
  if (entry['Color Transformer']) options.colorMode = entry['Color Transformer'];
  if (entry.Alpha !== undefined) options.alpha = number(entry.Alpha, 1);
  if (kind === 'Odometry' && entry.Keep !== undefined) options.keep = number(entry.Keep, 100);
  return { cls, kind, options };
}

function collect(list, out) {
  for (const entry of list || []) {
    if (!entry || typeof entry !== 'object') continue;
    const short = String(entry.Class || '').split('/').pop();
    if (short === 'Group') { collect(entry.Displays, out); continue; }
    if (short === 'Grid') {
      out.grid = { cells: number(entry['Plane Cell Count'], 10), size: number(entry['Cell Size'], 1),
        color: rvizColor(entry.Color) || '#a0a0a4', visible: entry.Enabled !== false && entry.Value !== false };
      continue;
    }
    const d = display(entry);
    if (d.kind) out.displays.push(d);
    else out.unsupported.push({ cls: d.cls || '(no Class)', name: d.options.name });
  }
}

/**
 * Read an .rviz file's text.
 * @returns {{fixedFrame, background, grid, view, displays: [{cls, kind, options}], unsupported: [{cls, name}]}}
 * @throws YamlError (with the line) or Error when it is not an rviz configuration
 */
export function readRviz(text) {
  const doc = parseYaml(text);
  const manager = doc && doc['Visualization Manager'];
  if (!manager || typeof manager !== 'object') {
    throw new Error('not an rviz configuration: it has no "Visualization Manager"');
  }
  const out = { displays: [], unsupported: [], grid: null, view: null };
  collect(manager.Displays, out);
  const global = manager['Global Options'] || {};
  out.fixedFrame = global['Fixed Frame'] || 'map';
  out.background = rvizColor(global['Background Color']);
  const current = (manager.Views || {}).Current || {};
  const viewClass = String(current.Class || '').split('/').pop();
  if (viewClass === 'Orbit' || viewClass === 'XYOrbit' || viewClass === 'ThirdPersonFollower') {
    const f = current['Focal Point'] || {};
    out.view = { distance: number(current.Distance, 10), yaw: number(current.Yaw, 0.785),
      pitch: number(current.Pitch, 0.785), focal: [number(f.X, 0), number(f.Y, 0), number(f.Z, 0)] };
  } else if (viewClass) {
    out.unsupported.push({ cls: current.Class, name: 'view' });
  }
  return out;
}
