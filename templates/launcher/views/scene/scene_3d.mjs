// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The 3D view's canvas: a three.js scene in ROS axes (x forward, y left,
// z up), a grid, orbit/pan/zoom (three's OrbitControls), and rendering on
// demand — a frame is drawn only when a display or the camera changed, so
// an idle view costs nothing. It is loaded the first time the 3D tab opens,
// with three.js itself (served from /vendor/, see colcon_wasm/vendor.py).

import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';

/** ROS (x, y, z) -> three.js (x, z, -y): the root group turns z up. */
export function rosToThree(v) {
  return new THREE.Vector3(v[0], v[2], -v[1]);
}

/** The WebGL renderer's name when it draws on the CPU (SwiftShader, llvmpipe), else null. */
export function softwareRenderer() {
  try {
    const gl = document.createElement('canvas').getContext('webgl2');
    if (!gl) return null;
    const info = gl.getExtension('WEBGL_debug_renderer_info');
    const name = info ? gl.getParameter(info.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER);
    gl.getExtension('WEBGL_lose_context')?.loseContext();
    return /swiftshader|llvmpipe|software/i.test(String(name)) ? String(name) : null;
  } catch {
    return null;
  }
}

export class Scene3d {
  constructor(host) {
    this.THREE = THREE;
    this.host = host;
    this.software = softwareRenderer();
    // multisampling costs a software renderer (SwiftShader) most of its frame time
    this.renderer = new THREE.WebGLRenderer({ antialias: !this.software });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
    this.renderer.setClearColor(0x30343c);
    this.canvas = this.renderer.domElement;
    this.canvas.className = 'scene-canvas';
    host.append(this.canvas);
    this.scene = new THREE.Scene();
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x444444, 1.6));
    const sun = new THREE.DirectionalLight(0xffffff, 1.4);
    sun.position.set(5, 10, 7);
    this.scene.add(sun);
    // the fixed frame: every display's objects live under it, in ROS axes
    this.root = new THREE.Group();
    this.root.rotation.x = -Math.PI / 2;
    this.scene.add(this.root);
    this.grid = new THREE.GridHelper(10, 10, 0xa0a4ac, 0x5c6068);
    this.scene.add(this.grid);
    this.camera = new THREE.PerspectiveCamera(50, 1, 0.01, 1000);
    this.controls = new OrbitControls(this.camera, this.canvas);
    this.controls.addEventListener('change', () => this.requestRender());
    this.setView({ distance: 6, yaw: 0.785, pitch: 0.6, focal: [0, 0, 0] });
    this.beforeRender = [];
    this.frames = 0;
    this.pending = false;
    this.resizeObserver = new ResizeObserver(() => this.resize());
    this.resizeObserver.observe(host);
    this.resize();
  }

  /** rviz's Orbit view: distance, yaw and pitch (radians) about a focal point (ROS axes). */
  setView({ distance, yaw, pitch, focal }) {
    const f = rosToThree(focal);
    const offset = [distance * Math.cos(pitch) * Math.cos(yaw),
      distance * Math.cos(pitch) * Math.sin(yaw), distance * Math.sin(pitch)];
    this.camera.position.copy(f.clone().add(rosToThree(offset)));
    this.controls.target.copy(f);
    this.controls.update();
    this.requestRender();
  }

  /** rviz's Grid display: cell count, cell size and colour. */
  setGrid({ cells = 10, size = 1, color = 0xa0a4ac, visible = true } = {}) {
    this.scene.remove(this.grid);
    this.grid.geometry.dispose();
    this.grid = new THREE.GridHelper(cells * size, cells, color, color);
    this.grid.material.opacity = 0.6;
    this.grid.material.transparent = true;
    this.grid.visible = visible;
    this.scene.add(this.grid);
    this.requestRender();
  }

  resize() {
    const width = Math.max(1, this.host.clientWidth);
    const height = Math.max(1, this.host.clientHeight);
    this.renderer.setSize(width, height, false);
    this.canvas.style.width = `${width}px`;
    this.canvas.style.height = `${height}px`;
    this.camera.aspect = width / height;
    this.camera.updateProjectionMatrix();
    this.requestRender();
  }

  /** Draw one frame soon (once, however often it is asked). */
  requestRender() {
    if (this.pending) return;
    this.pending = true;
    requestAnimationFrame(() => {
      this.pending = false;
      for (const fn of this.beforeRender) fn();
      this.renderer.render(this.scene, this.camera);
      this.frames++;
    });
  }

  /** The ROS point (fixed frame) under a canvas pixel on the z = 0 plane, or null. */
  groundPoint(clientX, clientY) {
    const rect = this.canvas.getBoundingClientRect();
    const ndc = new THREE.Vector2(((clientX - rect.left) / rect.width) * 2 - 1,
      -((clientY - rect.top) / rect.height) * 2 + 1);
    const ray = new THREE.Raycaster();
    ray.setFromCamera(ndc, this.camera);
    const hit = new THREE.Vector3();
    if (!ray.ray.intersectPlane(new THREE.Plane(new THREE.Vector3(0, 1, 0), 0), hit)) return null;
    return [hit.x, -hit.z, 0];
  }

  dispose() {
    this.resizeObserver.disconnect();
    this.controls.dispose();
    this.renderer.dispose();
  }
}
