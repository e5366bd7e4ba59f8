// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// rviz's Marker and MarkerArray displays: visualization_msgs markers kept by
// (namespace, id), every marker type, ADD/MODIFY, DELETE and DELETEALL, and
// lifetimes. Each marker sits in its own frame, placed by TF at each frame.

import * as THREE from 'three';
import { Display, applyPose } from '../display.mjs';
import { poseOf } from '../tf_buffer.mjs';
import { loadMesh } from '../mesh_loader.mjs';

export const MARKER_TYPES = ['ARROW', 'CUBE', 'SPHERE', 'CYLINDER', 'LINE_STRIP', 'LINE_LIST',
  'CUBE_LIST', 'SPHERE_LIST', 'POINTS', 'TEXT_VIEW_FACING', 'MESH_RESOURCE', 'TRIANGLE_LIST'];
const ADD = 0; const DELETE = 2; const DELETEALL = 3;

function material(c, options = {}) {
  const color = new THREE.Color(c.r, c.g, c.b);
  const transparent = c.a < 1;
  return options.line
    ? new THREE.LineBasicMaterial({ color, transparent, opacity: c.a })
    : new THREE.MeshPhongMaterial({ color, transparent, opacity: c.a, side: THREE.DoubleSide });
}

function vertexColors(m, count) {
  if (!m.colors || m.colors.length !== count) return null;
  const out = new Float32Array(count * 3);
  m.colors.forEach((c, i) => { out[i * 3] = c.r; out[i * 3 + 1] = c.g; out[i * 3 + 2] = c.b; });
  return out;
}

function positions(points) {
  const out = new Float32Array(points.length * 3);
  points.forEach((p, i) => { out[i * 3] = p.x; out[i * 3 + 1] = p.y; out[i * 3 + 2] = p.z; });
  return out;
}

function textSprite(text, height, c) {
  const canvas = document.createElement('canvas');
  const ctx = canvas.getContext('2d');
  const font = 48;
  ctx.font = `${font}px sans-serif`;
  canvas.width = Math.max(8, Math.ceil(ctx.measureText(text).width) + 8);
  canvas.height = font + 16;
  ctx.font = `${font}px sans-serif`;
  ctx.fillStyle = `rgba(${c.r * 255}, ${c.g * 255}, ${c.b * 255}, ${c.a})`;
  ctx.textBaseline = 'middle';
  ctx.fillText(text, 4, canvas.height / 2);
  const sprite = new THREE.Sprite(new THREE.SpriteMaterial({ map: new THREE.CanvasTexture(canvas), transparent: true }));
  sprite.scale.set(height * canvas.width / canvas.height, height, 1);
  return sprite;
}

/** Build the three.js object of one marker (in its own pose), or throw naming what is wrong. */
export function markerObject(m, onMesh) {
  const s = m.scale;
  const type = MARKER_TYPES[m.type];
  if (!type) throw new Error(`marker type ${m.type} is not one of visualization_msgs' types`);
  switch (type) {
    case 'CUBE': {
      const mesh = new THREE.Mesh(new THREE.BoxGeometry(1, 1, 1), material(m.color));
      mesh.scale.set(s.x, s.y, s.z);
      return mesh;
    }
    case 'SPHERE': {
      const mesh = new THREE.Mesh(new THREE.SphereGeometry(0.5, 24, 16), material(m.color));
      mesh.scale.set(s.x, s.y, s.z);
      return mesh;
    }
    case 'CYLINDER': {
      const geometry = new THREE.CylinderGeometry(0.5, 0.5, 1, 24);
      geometry.rotateX(Math.PI / 2); // ROS cylinders stand on z, three.js' on y
      const mesh = new THREE.Mesh(geometry, material(m.color));
      mesh.scale.set(s.x, s.y, s.z);
      return mesh;
    }
    case 'ARROW': {
      if (m.points && m.points.length >= 2) {
        const [a, b] = m.points;
        const dir = new THREE.Vector3(b.x - a.x, b.y - a.y, b.z - a.z);
        const length = dir.length();
        const arrow = new THREE.ArrowHelper(dir.normalize(), new THREE.Vector3(a.x, a.y, a.z), length,
          new THREE.Color(m.color.r, m.color.g, m.color.b), s.z || length * 0.3, s.y || length * 0.2);
        return arrow;
      }
      const arrow = new THREE.ArrowHelper(new THREE.Vector3(1, 0, 0), new THREE.Vector3(0, 0, 0), s.x,
        new THREE.Color(m.color.r, m.color.g, m.color.b), s.x * 0.23, Math.max(s.y, s.z) * 2);
      return arrow;
    }
    case 'LINE_STRIP':
    case 'LINE_LIST': {
      const geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.BufferAttribute(positions(m.points), 3));
      const colors = vertexColors(m, m.points.length);
      const mat = material(m.color, { line: true });
      if (colors) { geometry.setAttribute('color', new THREE.BufferAttribute(colors, 3)); mat.vertexColors = true; mat.color.set(0xffffff); }
      return type === 'LINE_STRIP' ? new THREE.Line(geometry, mat) : new THREE.LineSegments(geometry, mat);
    }
    case 'POINTS': {
      const geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.BufferAttribute(positions(m.points), 3));
      const colors = vertexColors(m, m.points.length);
      const mat = new THREE.PointsMaterial({ size: s.x || 0.05, color: new THREE.Color(m.color.r, m.color.g, m.color.b) });
      if (colors) { geometry.setAttribute('color', new THREE.BufferAttribute(colors, 3)); mat.vertexColors = true; mat.color.set(0xffffff); }
      return new THREE.Points(geometry, mat);
    }
    case 'CUBE_LIST':
    case 'SPHERE_LIST': {
      const geometry = type === 'CUBE_LIST' ? new THREE.BoxGeometry(s.x, s.y, s.z) : new THREE.SphereGeometry(0.5, 12, 8).scale(s.x, s.y, s.z);
      const mesh = new THREE.InstancedMesh(geometry, material(m.color), Math.max(1, m.points.length));
      const matrix = new THREE.Matrix4();
      const colors = vertexColors(m, m.points.length);
      m.points.forEach((p, i) => {
        mesh.setMatrixAt(i, matrix.makeTranslation(p.x, p.y, p.z));
        if (colors) mesh.setColorAt(i, new THREE.Color(colors[i * 3], colors[i * 3 + 1], colors[i * 3 + 2]));
      });
      mesh.count = m.points.length;
      return mesh;
    }
    case 'TRIANGLE_LIST': {
      const geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.BufferAttribute(positions(m.points), 3));
      geometry.computeVertexNormals();
      const mat = material(m.color);
      const colors = vertexColors(m, m.points.length);
      if (colors) { geometry.setAttribute('color', new THREE.BufferAttribute(colors, 3)); mat.vertexColors = true; mat.color.set(0xffffff); }
      const mesh = new THREE.Mesh(geometry, mat);
      mesh.scale.set(s.x || 1, s.y || 1, s.z || 1);
      return mesh;
    }
    case 'TEXT_VIEW_FACING':
      return textSprite(m.text || '', s.z || 0.1, m.color);
    case 'MESH_RESOURCE': {
      const holder = new THREE.Group();
      holder.scale.set(s.x || 1, s.y || 1, s.z || 1);
      const mat = m.mesh_use_embedded_materials && m.color.a === 0 ? null : material(m.color);
      loadMesh(m.mesh_resource, mat).then((obj) => { holder.add(obj); onMesh(null); }, (e) => onMesh(e));
      return holder;
    }
    default:
      throw new Error(`marker type ${type}`);
  }
}

export class MarkerDisplay extends Display {
  static kind = 'Marker';
  static defaultTopic = '/visualization_marker';
  static types = ['visualization_msgs/msg/Marker', 'visualization_msgs/msg/MarkerArray'];

  constructor(ctx, options) {
    super(ctx, options);
    // "ns/id" -> {object, frameId, expires, ns}
    this.markers = new Map();
    this.errors = new Map();
    this.listen(MarkerDisplay.types);
  }

  get settings() { return ['topic']; }

  onMessages(values) {
    for (const v of values) {
      for (const m of v.markers || [v]) this.apply(m);
    }
  }

  remove(key) {
    const entry = this.markers.get(key);
    if (!entry) return;
    this.group.remove(entry.object);
    entry.object.traverse((o) => { if (o.geometry) o.geometry.dispose(); });
    this.markers.delete(key);
  }

  apply(m) {
    const key = `${m.ns}/${m.id}`;
    if (m.action === DELETEALL) {
      // rviz2 (Humble): DELETEALL removes every marker of the display, whatever its namespace
      for (const k of [...this.markers.keys()]) this.remove(k);
      this.errors.clear();
      return;
    }
    if (m.action === DELETE) { this.remove(key); this.errors.delete(key); return; }
    if (m.action !== ADD && m.action !== 1) return;
    this.remove(key);
    let object;
    try {
      object = markerObject(m, (e) => {
        if (e) this.errors.set(key, e.message);
        this.ctx.requestRender();
      });
    } catch (e) {
      this.errors.set(key, `${key}: ${e.message}`);
      return;
    }
    this.errors.delete(key);
    const holder = new THREE.Group();
    const inner = new THREE.Group();
    applyPose(inner, poseOf(m.pose));
    inner.add(object);
    holder.add(inner);
    this.group.add(holder);
    const life = m.lifetime ? m.lifetime.sec + m.lifetime.nanosec * 1e-9 : 0;
    this.markers.set(key, { object: holder, frameId: m.header.frame_id, ns: m.ns,
      expires: life > 0 ? performance.now() + life * 1000 : Infinity });
  }

  update() {
    this.frameError = null;
    const now = performance.now();
    let soonest = Infinity;
    for (const [key, entry] of this.markers) {
      if (entry.expires <= now) { this.remove(key); continue; }
      soonest = Math.min(soonest, entry.expires);
      this.place(entry.object, entry.frameId);
    }
    // a marker with a lifetime goes when it ends, even if nothing else draws a frame
    if (soonest < Infinity && !this.expiryTimer) {
      this.expiryTimer = setTimeout(() => { this.expiryTimer = null; this.ctx.requestRender(); }, Math.max(10, soonest - now));
    }
  }

  namespaces() {
    const counts = {};
    for (const entry of this.markers.values()) counts[entry.ns] = (counts[entry.ns] || 0) + 1;
    return counts;
  }

  status() {
    if (this.errors.size) return { level: 'error', text: [...this.errors.values()][0] };
    const s = super.status();
    if (s.level !== 'ok') return s;
    const ns = Object.entries(this.namespaces()).map(([n, c]) => `${n || '(no ns)'}: ${c}`).join(', ');
    return { level: 'ok', text: `${this.markers.size} markers${ns ? ` (${ns})` : ''}` };
  }
}
