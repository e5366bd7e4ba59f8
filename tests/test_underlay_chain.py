# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""An overlay of an overlay: the underlays' own underlays come with them (build and run)."""

import json

from colcon_wasm.launch.install_space import InstallSpace
from colcon_wasm.underlay import find_underlays
from colcon_wasm.underlay import MARKER


def _base(path, underlays, pthread=True):
    path.mkdir(parents=True)
    (path / MARKER).write_text(json.dumps({
        'schema': 1, 'colcon_wasm': '0.1.0', 'pthread': pthread,
        'underlays': [str(u) for u in underlays]}))
    return path


def test_a_build_on_an_overlay_stands_on_its_chain(tmp_path):
    core = _base(tmp_path / 'core', [])
    corpus = _base(tmp_path / 'corpus', [core])
    mine = _base(tmp_path / 'mine', [corpus])
    found = find_underlays(option_paths=[str(mine)], environ={},
                           install_base=str(tmp_path / 'ws' / 'install_wasm'), pthread=True)
    # highest priority first: what was named, then what it stands on
    assert [u.base for u in found] == [mine, corpus, core]
    assert found[2].source == f"an underlay of '{corpus}'"


def test_an_install_space_sees_the_whole_chain_and_skips_a_moved_one(tmp_path):
    core = _base(tmp_path / 'core', [])
    corpus = _base(tmp_path / 'corpus', [core, tmp_path / 'gone'])
    overlay = _base(tmp_path / 'overlay', [corpus])
    space = InstallSpace(overlay, environ={})
    assert space.underlays == [corpus, core]
