// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The `assets` capability of the Foxglove server: `fetchAsset` of a
 * `package://PKG/PATH` URI (the meshes and textures a URDF names) answered
 * with the file from that package's share folder in the install space,
 * as foxglove_bridge resolves them through the ament index. As there, only
 * the file kinds of foxglove_bridge's default `asset_uri_allowlist` are
 * served, and nothing outside the package's share folder.
 *
 * @module bridges/foxglove/assets
 */

import { readFile, realpath, stat } from 'node:fs/promises';
import path from 'node:path';

/** foxglove_bridge's default asset_uri_allowlist (the file kinds a scene needs). */
export const ASSET_URI_ALLOWLIST = /^package:\/\/(?:[-\w%]+\/)*[-\w%.]+\.(?:dae|fbx|glb|gltf|jpeg|jpg|mtl|obj|png|stl|tif|tiff|urdf|webp|xacro)$/i;
/** The largest asset sent (a WebSocket message holds it whole). */
export const MAX_ASSET_BYTES = 64 * 1024 * 1024;

/** An asset that cannot be served: the message says why and what to do. */
export class AssetError extends Error {
  constructor(message) {
    super(message);
    this.name = 'AssetError';
  }
}

export class Assets {
  /** @param {Object<string, string>} shares package name -> its share folder in the install space */
  constructor(shares) {
    this.shares = new Map(Object.entries(shares || {}));
  }

  /** True when there is a package to serve assets from. */
  get available() {
    return this.shares.size > 0;
  }

  /**
   * Read the file a `package://` URI names.
   * @param {string} uri
   * @returns {Promise<Uint8Array>}
   * @throws {AssetError}
   */
  async fetch(uri) {
    if (typeof uri !== 'string' || !uri) throw new AssetError("fetchAsset needs a 'uri' string, e.g. package://my_robot/meshes/base.stl");
    if (!uri.startsWith('package://')) {
      throw new AssetError(`fetchAsset ${uri}: only package:// URIs are served (package://PKG/PATH, from the install space)`);
    }
    if (!ASSET_URI_ALLOWLIST.test(uri)) {
      throw new AssetError(`fetchAsset ${uri}: not an allowed asset (foxglove_bridge's asset_uri_allowlist: `
        + 'package://PKG/PATH ending in .dae, .fbx, .glb, .gltf, .jpeg, .jpg, .mtl, .obj, .png, .stl, .tif, .tiff, .urdf, .webp or .xacro)');
    }
    const rest = decodeURIComponent(uri.slice('package://'.length));
    const slash = rest.indexOf('/');
    const pkg = rest.slice(0, slash);
    const share = this.shares.get(pkg);
    if (!share) {
      throw new AssetError(`fetchAsset ${uri}: package '${pkg}' is not in the install space: build it with colcon build --wasm`);
    }
    const relative = rest.slice(slash + 1);
    const file = path.resolve(share, relative);
    let real;
    try {
      const root = await realpath(share);
      real = await realpath(file);
      if (real !== root && !real.startsWith(root + path.sep)) {
        throw new AssetError(`fetchAsset ${uri}: the path leaves the share folder of '${pkg}'`);
      }
    } catch (e) {
      if (e instanceof AssetError) throw e;
      throw new AssetError(`fetchAsset ${uri}: no file ${relative} in the share folder of '${pkg}' (${share})`);
    }
    const info = await stat(real);
    if (!info.isFile()) throw new AssetError(`fetchAsset ${uri}: ${relative} in '${pkg}' is not a file`);
    if (info.size > MAX_ASSET_BYTES) {
      throw new AssetError(`fetchAsset ${uri}: the file is ${info.size} bytes, more than the ${MAX_ASSET_BYTES} served`);
    }
    return new Uint8Array(await readFile(real));
  }
}
