# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The glue fragment engine: ordered, placed, idempotent."""

from colcon_wasm.glue import Fragment
from colcon_wasm.glue import GlueError
from colcon_wasm.glue import inject
from colcon_wasm.glue import load_fragments
import pytest

CONTEXT = {'package': 'p', 'executable': 'e', 'pthread': True,
           'debug': False, 'emscripten_version': '3.1.6'}


def _fragment(folder, name, header, body):
    path = folder / name
    path.write_text(header + '\n' + body)
    return path


def test_shipped_fragments_load_in_order():
    names = [f.name for f in load_fragments()]
    assert names[:3] == ['00-node-fetch', '10-startup', '20-log-exit']
    fetch = load_fragments()[0]
    assert fetch.targets == ('js', 'worker') and fetch.at == 'head'


def test_placement_and_idempotence(tmp_path):
    _fragment(tmp_path, '10-a.j2', '{# glue targets=js at=head #}',
              '// head {{ executable }}\n')
    _fragment(tmp_path, '20-b.j2', '{# glue targets=js,worker at=tail #}',
              '// tail {{ target }}\n')
    _fragment(tmp_path, '30-c.j2',
              '{# glue targets=js at=before:run(); #}', '// before run\n')
    fragments = load_fragments([tmp_path])
    glue = 'var Module={};run();'
    once = inject(glue, fragments, target='js', context=CONTEXT,
                  file_name='e.js')
    assert once.index('// head e') < once.index('var Module')
    assert once.index('// before run') < once.index('run();')
    assert once.rstrip().endswith('/*colcon-wasm:end 20-b*/')
    twice = inject(once, fragments, target='js', context=CONTEXT,
                   file_name='e.js')
    assert twice == once
    worker = inject('"use strict";self.onmessage=1;', fragments,
                    target='worker', context=CONTEXT, file_name='e.worker.js')
    assert '// tail worker' in worker and '// head' not in worker
    assert worker.startswith('"use strict";\nself.onmessage=1;')
    assert inject(worker, fragments, target='worker', context=CONTEXT,
                  file_name='e.worker.js') == worker


def test_missing_anchor(tmp_path):
    _fragment(tmp_path, '10-x.j2', '{# glue targets=js at=before:nope( #}',
              '//\n')
    with pytest.raises(GlueError, match=r"anchor 'nope\(' not found in "
                       r"'e.js' \(Emscripten 3.1.6\)"):
        inject('run();', load_fragments([tmp_path]), target='js',
               context=CONTEXT, file_name='e.js')


def test_bad_header(tmp_path):
    path = _fragment(tmp_path, '10-x.j2', '// no header', '')
    with pytest.raises(GlueError, match='line 1: expected a header'):
        Fragment(path)
    path = _fragment(tmp_path, '11-y.j2', '{# glue targets=html at=head #}',
                     '')
    with pytest.raises(GlueError, match="unknown target 'html'"):
        Fragment(path)


def test_undefined_variable_is_an_error(tmp_path):
    _fragment(tmp_path, '10-x.j2', '{# glue targets=js at=head #}',
              '{{ nope }}\n')
    with pytest.raises(GlueError, match='cannot render'):
        inject('', load_fragments([tmp_path]), target='js', context=CONTEXT,
               file_name='e.js')
