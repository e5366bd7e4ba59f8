# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The ``assets`` capability of ``serve --foxglove``.

``fetchAsset`` of a ``package://PKG/PATH`` URI (the meshes and textures a
URDF names) is answered with the file from that package's share folder in
the install space, as foxglove_bridge resolves them through the ament
index and as the Node.js server of ``run``/``launch --foxglove`` does
(packages/wasm_js/src/bridges/foxglove/assets.mjs), with the same rules
and error texts: only the file kinds of foxglove_bridge's default
``asset_uri_allowlist``, nothing outside the package's share folder (links
resolved), at most 64 MiB.
"""

import os
from pathlib import Path
import re
import struct
from urllib.parse import unquote

from colcon_wasm.error import ColconWasmError

"""foxglove_bridge's default asset_uri_allowlist (the file kinds a scene needs)."""
ASSET_URI_ALLOWLIST = re.compile(
    r'^package://(?:[-\w%]+/)*[-\w%.]+\.(?:dae|fbx|glb|gltf|jpeg|jpg|mtl|obj|png|stl|tif|tiff|'
    r'urdf|webp|xacro)$', re.IGNORECASE | re.ASCII)
"""The largest asset sent (a WebSocket message holds it whole)."""
MAX_ASSET_BYTES = 64 * 1024 * 1024

_FETCH_ASSET_RESPONSE = 0x04
_HEAD = struct.Struct('<BIBI')


class AssetError(ColconWasmError):
    """An asset that cannot be served: the text says why and what to do."""


class Assets:
    """The share folders of an install space's packages, as ``package://`` serves them."""

    def __init__(self, shares):
        """
        Serve from ``shares``.

        :param shares: ``{package: share folder}``
        """
        self.shares = {name: Path(folder) for name, folder in shares.items()}

    @classmethod
    def of_install(cls, install_space):
        """Serve the share folder of every package of an install space."""
        return cls(install_space.share_folders())

    @property
    def available(self):
        """Whether there is a package to serve assets from."""
        return bool(self.shares)

    def fetch(self, uri):
        """
        Read the file a ``package://`` URI names.

        :returns: its bytes
        :raises AssetError: naming the URI and why it is not served
        """
        if not isinstance(uri, str) or not uri:
            raise AssetError("fetchAsset needs a 'uri' string, e.g. "
                             'package://my_robot/meshes/base.stl')
        if not uri.startswith('package://'):
            raise AssetError(f'fetchAsset {uri}: only package:// URIs are served '
                             '(package://PKG/PATH, from the install space)')
        if not ASSET_URI_ALLOWLIST.match(uri):
            raise AssetError(
                f"fetchAsset {uri}: not an allowed asset (foxglove_bridge's asset_uri_allowlist: "
                'package://PKG/PATH ending in .dae, .fbx, .glb, .gltf, .jpeg, .jpg, .mtl, .obj, '
                '.png, .stl, .tif, .tiff, .urdf, .webp or .xacro)')
        package, _, relative = unquote(uri[len('package://'):]).partition('/')
        share = self.shares.get(package)
        if share is None:
            raise AssetError(f"fetchAsset {uri}: package '{package}' is not in the install "
                             'space: build it with colcon build --wasm')
        try:
            root = share.resolve(strict=True)
            real = (share / relative).resolve(strict=True)
        except OSError:
            raise AssetError(f'fetchAsset {uri}: no file {relative} in the share folder of '
                             f"'{package}' ({share})") from None
        if real != root and root not in real.parents:
            raise AssetError(f'fetchAsset {uri}: the path leaves the share folder of '
                             f"'{package}'")
        if not real.is_file():
            raise AssetError(f"fetchAsset {uri}: {relative} in '{package}' is not a file")
        size = os.stat(real).st_size
        if size > MAX_ASSET_BYTES:
            raise AssetError(f'fetchAsset {uri}: the file is {size} bytes, more than the '
                             f'{MAX_ASSET_BYTES} served')
        return real.read_bytes()


def fetch_asset_response(request_id, error, data=b''):
    """
    Encode a FETCH_ASSET_RESPONSE: the file's bytes, or status 1 and the error text.

    :param request_id: the request's ``requestId``
    :param error: the error text, or None
    :param data: the file's bytes (when no error)
    """
    text = (error or '').encode('utf-8')
    return _HEAD.pack(_FETCH_ASSET_RESPONSE, request_id, 1 if error else 0, len(text)) + text + (
        b'' if error else bytes(data))
