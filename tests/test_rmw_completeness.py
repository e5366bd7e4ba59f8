# Copyright 2026 The colcon-wasm authors
# Licensed under the Apache License, Version 2.0

"""
Every function Humble's rmw headers declare is defined, with real results.

The declarations are parsed from the snapshot's rmw headers; the definitions
are the symbols of the built static libraries (librmw for the functions rmw
implements itself, librmw_wasm_cpp for the rest), read with emnm/llvm-nm.
Only message loans, network flow endpoints and content filters may answer
RMW_RET_UNSUPPORTED, each with an error string that says why.
"""

import re
import shutil
import subprocess

from humble_build import humble_snapshot
from humble_build import REPO
from humble_build import unpacked_source
import pytest
from rclcpp_build import rclcpp_build

SOURCES = REPO / 'packages' / 'rmw_wasm_cpp' / 'src'

"""The functions issue 5 allows to be unsupported (loans, network flows, content filters)."""
MAY_BE_UNSUPPORTED = {
    'rmw_borrow_loaned_message', 'rmw_return_loaned_message_from_publisher',
    'rmw_publish_loaned_message', 'rmw_take_loaned_message',
    'rmw_take_loaned_message_with_info', 'rmw_return_loaned_message_from_subscription',
    'rmw_publisher_get_network_flow_endpoints', 'rmw_subscription_get_network_flow_endpoints',
    'rmw_subscription_set_content_filter', 'rmw_subscription_get_content_filter',
}


@pytest.fixture(scope='module')
def build():
    """Get the (cached) Humble build up to rclcpp."""
    return rclcpp_build()


def declared_functions():
    """Map each function declared by rmw's public headers to its header."""
    if not (humble_snapshot() / 'src.tar.xz').is_file():
        pytest.skip(f'Humble snapshot not found at {humble_snapshot()} (set COLCON_WASM_HUMBLE)')
    include = unpacked_source() / 'ros2' / 'rmw' / 'rmw' / 'include' / 'rmw'
    assert include.is_dir(), f'rmw headers not found at {include}'
    functions = {}
    for header in sorted(include.rglob('*.h')):
        text = re.sub(r'/\*.*?\*/', '', header.read_text(), flags=re.S)
        text = re.sub(r'//[^\n]*', '', text)
        for match in re.finditer(r'\bRMW_PUBLIC\b([^;{]*?)\b(rmw_\w+)\s*\(', text, flags=re.S):
            functions[match.group(2)] = header.relative_to(include).as_posix()
    return functions


def nm_tool():
    """Find an nm that reads wasm objects (Emscripten's emnm, else llvm-nm)."""
    for name in ('emnm', 'llvm-nm', 'llvm-nm-14'):
        found = shutil.which(name)
        if found:
            return found
    pytest.fail('neither emnm nor llvm-nm found: install emscripten (apt) or LLVM')


def defined_symbols(archive):
    """Get the names of the functions an archive defines."""
    assert archive.is_file(), f'{archive} not built'
    completed = subprocess.run(
        [nm_tool(), '--defined-only', str(archive)], capture_output=True, text=True, check=True)
    return {line.split()[-1] for line in completed.stdout.splitlines()
            if len(line.split()) == 3 and line.split()[1] in 'TW'}


def test_headers_declare_the_humble_rmw_api():
    functions = declared_functions()
    # a sanity check of the parser on well-known names, from several headers
    for name in ('rmw_init', 'rmw_create_node', 'rmw_wait', 'rmw_take_event',
                 'rmw_feature_supported', 'rmw_get_publishers_info_by_topic',
                 'rmw_qos_profile_check_compatible', 'rmw_get_zero_initialized_context'):
        assert name in functions, name
    assert len(functions) > 150


def test_every_declared_function_is_defined(build):
    rmw_library = defined_symbols(build.install / 'rmw' / 'lib' / 'librmw.a')
    ours = defined_symbols(build.install / 'rmw_wasm_cpp' / 'lib' / 'librmw_wasm_cpp.a')
    missing = {name: header for name, header in declared_functions().items()
               if name not in rmw_library and name not in ours}
    assert not missing, 'declared by rmw but defined nowhere:\n' + '\n'.join(
        f'  {name} ({header})' for name, header in sorted(missing.items()))
    both = sorted(n for n in declared_functions() if n in rmw_library and n in ours)
    assert not both, f'defined twice (rmw and rmw_wasm_cpp): {both}'
    implemented = {n for n in declared_functions() if n in ours}
    assert len(implemented) >= 89, sorted(implemented)


def _function_bodies(text):
    """Yield (name, body) of the rmw_* functions defined in a C++ source."""
    for match in re.finditer(r'\n\w[\w\s\*]*?\b(rmw_\w+)\(([^;{]*?)\)\n\{', text):
        start = match.end()
        depth, index = 1, start
        while depth:
            depth += {'{': 1, '}': -1}.get(text[index], 0)
            index += 1
        yield match.group(1), text[start:index]


def test_only_loans_flows_and_filters_are_unsupported():
    unsupported = {}
    for source in sorted(SOURCES.rglob('*.cpp')):
        for name, body in _function_bodies(source.read_text()):
            if 'RMW_RET_UNSUPPORTED' in body:
                unsupported[name] = body
    assert set(unsupported) == MAY_BE_UNSUPPORTED
    for name, body in unsupported.items():
        assert 'RMW_SET_ERROR_MSG' in body, f'{name} returns UNSUPPORTED without saying why'
    reasons = (SOURCES / 'rmw_unsupported.cpp').read_text()
    for reason in ('does not loan messages', 'no network flow endpoints',
                   'does not filter content'):
        assert reason in reasons


def test_rmw_wait_sleeps_in_the_core():
    """rmw_wait hands the whole wait to the core's wait set (Atomics.wait), no loop."""
    wait = (SOURCES / 'detail' / 'rmw_wait_set_data.cpp').read_text()
    body = wait[wait.index('WaitSetData::wait('):]
    assert body.count('wait_set_->wait(') == 1
    assert not re.search(r'\b(while|sleep|usleep|nanosleep|sleep_for)\b', body)
