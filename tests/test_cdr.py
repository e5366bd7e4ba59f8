# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""CDR in JS (packages/wasm_js/src/cdr.mjs) against golden Fast CDR bytes."""

import json
from pathlib import Path
import shutil
import subprocess
import sys

sys.path.insert(0, str(Path(__file__).resolve().parent))

import cdr_fastcdr  # noqa: E402, I100
import pytest  # noqa: E402, I100, I202

REPO = Path(__file__).resolve().parents[1]


@pytest.fixture(scope='module')
def types_json(tmp_path_factory):
    """Return the types.json of cdr_test_msgs, as typedesc writes it."""
    path = tmp_path_factory.mktemp('cdr') / 'types.json'
    path.write_text(json.dumps(cdr_fastcdr.load_types()), encoding='utf-8')
    return path


def test_cdr_mjs_matches_the_golden_vectors(types_json):
    node = shutil.which('node')
    assert node, 'Node.js 20 is needed (apt-get install nodejs)'
    result = subprocess.run(
        [node, '--test', '--test-reporter=tap', str(REPO / 'tests' / 'js' / 'test_cdr.mjs')],
        env={'CDR_TYPES': str(types_json), 'PATH': '/usr/bin:/bin'},
        capture_output=True, text=True, timeout=120)
    failures = [line for line in result.stdout.splitlines() if line.startswith('not ok')]
    assert result.returncode == 0, '\n'.join(failures) + '\n' + result.stdout[-6000:] + \
        result.stderr[-2000:]
    assert '# fail 0' in result.stdout
    # every vector was exercised both ways
    vectors = cdr_fastcdr.all_cases(cdr_fastcdr.load_vectors())
    assert result.stdout.count('ok ') >= 2 * len(vectors)


def test_golden_vectors_are_what_fast_cdr_writes(tmp_path):
    """Regenerate each vector with the real Fast CDR library and compare."""
    if cdr_fastcdr.compiler() is None:
        pytest.skip('g++ and Fast CDR headers are needed (apt-get install g++ libfastcdr-dev)')
    files = cdr_fastcdr.load_vectors()
    produced = cdr_fastcdr.serialize_with_fastcdr(
        cdr_fastcdr.load_types(), cdr_fastcdr.all_cases(files), tmp_path)
    stored = {case['name']: case['hex']
              for document in files.values() for case in document['vectors']}
    assert produced == stored


def test_vector_names_are_unique_and_types_exist():
    types = cdr_fastcdr.load_types()
    cases = cdr_fastcdr.all_cases(cdr_fastcdr.load_vectors())
    names = [name for name, _, _ in cases]
    assert len(names) == len(set(names))
    assert all(type_name in types['messages'] for _, type_name, _ in cases)
