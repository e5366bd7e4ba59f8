# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Spell-check the Python code as a test (colcon-core's test/test_spell_check.py)."""

from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
WORDS = Path(__file__).parent / 'spell_check.words'


def source_files():
    """List the Python files checked: the package, the tests and the scripts."""
    files = list((REPO / 'colcon_wasm').glob('**/*.py'))
    files += [p for p in (REPO / 'tests').glob('**/*.py') if 'node_modules' not in p.parts]
    files += list((REPO / 'scripts').glob('*.py'))
    return sorted(files)


@pytest.fixture(scope='module')
def known_words():
    return WORDS.read_text().splitlines()


def test_spell_check(known_words):
    from scspell import Report
    from scspell import SCSPELL_BUILTIN_DICT
    from scspell import spell_check

    report = Report(known_words)
    spell_check(
        [str(p) for p in source_files()], base_dicts=[SCSPELL_BUILTIN_DICT],
        report_only=report, additional_extensions=[('', 'Python')])

    unknown = sorted(report.unknown_words)
    assert not unknown, \
        f'{len(unknown)} unknown words (fix the spelling, or add them to ' \
        f"'{WORDS.relative_to(REPO)}'): " + ', '.join(unknown)

    unused = sorted(set(known_words) - report.found_known_words)
    assert not unused, \
        f"{len(unused)} words of '{WORDS.relative_to(REPO)}' are not used: " + ', '.join(unused)


def test_spell_check_word_list_order(known_words):
    assert known_words == sorted(known_words), \
        f"'{WORDS.relative_to(REPO)}' should be sorted alphabetically"


def test_spell_check_word_list_duplicates(known_words):
    assert len(known_words) == len(set(known_words)), \
        f"'{WORDS.relative_to(REPO)}' should not contain duplicates"
