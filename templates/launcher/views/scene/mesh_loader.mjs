// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Meshes of URDF visuals and MESH_RESOURCE markers: package://PKG/PATH is
// the share folder of PKG, served at /package/PKG/PATH by colcon-wasm serve;
// STL, COLLADA (.dae) and OBJ are read with three.js' own loaders.

import * as THREE from 'three';
import { STLLoader } from 'three/examples/jsm/loaders/STLLoader.js';
import { ColladaLoader } from 'three/examples/jsm/loaders/ColladaLoader.js';
import { OBJLoader } from 'three/examples/jsm/loaders/OBJLoader.js';
import { siteUrl } from '../../site_url.mjs';

/** The URL of a package:// (or file://, or relative) mesh URI. */
export function meshUrl(uri) {
  if (uri.startsWith('package://')) return siteUrl(`package/${uri.slice('package://'.length)}`);
  if (/^[a-z]+:\/\//i.test(uri)) {
    throw new Error(`mesh ${uri}: only package:// URIs are served to the page (package://PKG/PATH, a file of the package's share folder)`);
  }
  return uri;
}

/** Read a mesh: resolves to an Object3D, rejects naming the URI and what failed. */
export function loadMesh(uri, material) {
  let url;
  try { url = meshUrl(uri); } catch (e) { return Promise.reject(e); }
  return loadMeshUrl(url, material, uri);
}

/** Read a mesh from a URL of the site (its extension says the format). */
export function loadMeshUrl(url, material, uri = url) {
  const ext = url.split('?')[0].split('.').pop().toLowerCase();
  return new Promise((resolve, reject) => {
    const fail = (e) => reject(new Error(`mesh ${uri}: ${e && e.message ? e.message : `cannot load ${url}`}`));
    if (ext === 'stl') {
      new STLLoader().load(url, (geometry) => resolve(new THREE.Mesh(geometry, material || new THREE.MeshPhongMaterial({ color: 0xbbbbbb }))), undefined, fail);
    } else if (ext === 'dae') {
      new ColladaLoader().load(url, (dae) => resolve(dae.scene), undefined, fail);
    } else if (ext === 'obj') {
      new OBJLoader().load(url, (obj) => {
        if (material) obj.traverse((o) => { if (o.isMesh) o.material = material; });
        resolve(obj);
      }, undefined, fail);
    } else {
      reject(new Error(`mesh ${uri}: .${ext} files are not read (STL, DAE and OBJ are)`));
    }
  });
}
