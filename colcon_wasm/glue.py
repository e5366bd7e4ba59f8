# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Inject JavaScript fragments into Emscripten's glue files.

A fragment is a Jinja template in `templates/glue/` named `NN-name.j2`;
fragments are applied in file name order. Its first line says which glue
files it goes into and where::

    {# glue targets=js,worker at=head #}

* `targets`: `js` (the executable's `<exe>.js`) and/or `worker` (the
  pthread bootstrap `<exe>.worker.js`, present with `-pthread`);
* `at`: `head` (before the glue, after a leading `"use strict";`), `tail`
  (after it) or `before:TEXT`
  (right before the first occurrence of TEXT; an error if TEXT is absent).

Each injected block is wrapped in `/*colcon-wasm:begin NAME*/` and
`/*colcon-wasm:end NAME*/` markers. Injecting again first removes the blocks
of an earlier run, so running twice gives the same file.
"""

from pathlib import Path
import re

from colcon_wasm import resources
from colcon_wasm.error import ColconWasmError
import jinja2

TARGETS = ('js', 'worker')

_HEADER = re.compile(
    r'^\{#-?\s*glue\s+targets=(?P<targets>[a-z,]+)\s+'
    r'at=(?P<at>head|tail|before:.+?)\s*-?#\}\s*$')

_BLOCK = re.compile(
    r'/\*colcon-wasm:begin (?P<name>[^*]+)\*/.*?'
    r'/\*colcon-wasm:end (?P=name)\*/\n?', re.DOTALL)


class GlueError(ColconWasmError):
    """A fragment is malformed or cannot be placed."""


class Fragment:
    """One glue fragment template."""

    def __init__(self, path):
        """
        Read a fragment file and its header.

        :param pathlib.Path path: the `.j2` file
        :raises GlueError: for a missing or malformed header
        """
        self.path = Path(path)
        self.name = self.path.stem
        text = self.path.read_text()
        first, _, body = text.partition('\n')
        match = _HEADER.match(first.strip())
        if not match:
            raise GlueError(
                f"glue fragment '{self.path}' line 1: expected a header like "
                "'{# glue targets=js,worker at=head #}', got "
                f'{first.strip()!r}')
        self.targets = tuple(match.group('targets').split(','))
        for target in self.targets:
            if target not in TARGETS:
                raise GlueError(
                    f"glue fragment '{self.path}' line 1: unknown target "
                    f"'{target}', expected one of: " + ', '.join(TARGETS))
        self.at = match.group('at')
        self.body = body

    def render(self, context):
        """Render the fragment with the executable's context."""
        environment = jinja2.Environment(
            undefined=jinja2.StrictUndefined, keep_trailing_newline=True,
            autoescape=False)
        try:
            return environment.from_string(self.body).render(**context)
        except jinja2.TemplateError as e:
            raise GlueError(
                f"glue fragment '{self.path}': cannot render: {e}") from e


def load_fragments(folders=None):
    """
    Load the glue fragments in application order.

    :param folders: folders to read `*.j2` from (default: the shipped
      `templates/glue/`); fragments are ordered by file name over all folders
    :returns: list of :class:`Fragment`
    """
    if folders is None:
        folders = [resources.path('templates') / 'glue']
    paths = []
    for folder in folders:
        paths += sorted(Path(folder).glob('*.j2'))
    return [Fragment(p) for p in sorted(paths, key=lambda p: p.name)]


def strip_injections(text):
    """Remove every block injected by an earlier run."""
    return _BLOCK.sub('', text)


def inject(text, fragments, *, target, context, file_name):
    """
    Inject fragments into one glue file's text.

    :param str text: the glue
    :param fragments: the :class:`Fragment` list, in order
    :param str target: `js` or `worker`
    :param dict context: template variables
    :param str file_name: for messages
    :returns: the new text
    :raises GlueError: when a `before:` anchor is not in the glue
    """
    text = strip_injections(text)
    heads = []
    tails = []
    for fragment in fragments:
        if target not in fragment.targets:
            continue
        block = (f'/*colcon-wasm:begin {fragment.name}*/\n'
                 + fragment.render(dict(context, target=target)).strip('\n')
                 + f'\n/*colcon-wasm:end {fragment.name}*/\n')
        if fragment.at == 'head':
            heads.append(block)
        elif fragment.at == 'tail':
            tails.append(block)
        else:
            anchor = fragment.at[len('before:'):]
            position = text.find(anchor)
            if position < 0:
                raise GlueError(
                    f"glue fragment '{fragment.path.name}': anchor "
                    f"{anchor!r} not found in '{file_name}' (Emscripten "
                    f"{context.get('emscripten_version')}); update the "
                    "fragment's 'at=before:' text")
            text = text[:position] + block + text[position:]
    if tails and not text.endswith('\n'):
        text += '\n'
    # keep a "use strict" directive first (the pthread worker.js has one)
    prologue = ''
    for directive in ('"use strict";', "'use strict';"):
        if text.startswith(directive):
            prologue = directive + '\n'
            text = text[len(directive):].lstrip('\n')
    return prologue + ''.join(heads) + text + ''.join(tails)


def inject_file(path, fragments, *, target, context):
    """
    Inject fragments into a glue file in place (idempotent).

    :returns: True when the file changed
    """
    path = Path(path)
    text = path.read_text()
    new_text = inject(text, fragments, target=target, context=context,
                      file_name=path.name)
    if new_text == text:
        return False
    path.write_text(new_text)
    return True
