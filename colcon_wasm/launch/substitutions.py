# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

r"""The ``$(...)`` substitutions of ROS 2 XML and YAML launch files.

Follows the grammar of ``launch/frontend/grammar.lark`` (Humble): text with
``$(name arg arg ...)``, arguments separated by one space, quoted with ``'`` or
``"`` when they contain spaces, substitutions nested anywhere, ``\\`` escaping
the next character.
"""

import math
import os
from pathlib import Path
import secrets

from colcon_wasm.launch.errors import LaunchError


class Substitution:
    """One ``$(name args...)`` of a template; ``args`` are templates too."""

    __slots__ = ('name', 'args')

    def __init__(self, name, args):
        """Keep the substitution name and its argument templates."""
        self.name = name
        self.args = args


def _is_identifier_char(c):
    return c.isalnum() or c in '_-'


class _Parser:
    """Recursive descent over one attribute value."""

    def __init__(self, text, where):
        self.text = text
        self.pos = 0
        self.where = where

    def fail(self, message):
        return LaunchError(f'{message} in {self.text!r}', *self.where)

    def peek(self, n=1):
        return self.text[self.pos:self.pos + n]

    def template(self, stop=''):
        """Parse fragments until end of text or one of ``stop`` (unconsumed)."""
        parts = []
        text = []
        while self.pos < len(self.text):
            c = self.text[self.pos]
            if c in stop:
                break
            if c == '\\' and self.pos + 1 < len(self.text):
                text.append(self.text[self.pos + 1])
                self.pos += 2
                continue
            if self.peek(2) == '$(':
                if text:
                    parts.append(''.join(text))
                    text = []
                parts.append(self.substitution())
                continue
            text.append(c)
            self.pos += 1
        if text:
            parts.append(''.join(text))
        return parts

    def substitution(self):
        start = self.pos
        self.pos += 2
        name_start = self.pos
        while self.pos < len(self.text) and _is_identifier_char(self.text[self.pos]):
            self.pos += 1
        name = self.text[name_start:self.pos]
        if not name:
            raise self.fail(f'a substitution needs a name after "$(" at character {start}')
        args = []
        while True:
            c = self.peek()
            if c == ')':
                self.pos += 1
                return Substitution(name, args)
            if c != ' ':
                raise self.fail(
                    f'substitution $({name} ... is not closed with ")"' if not c
                    else f'unexpected {c!r} in substitution $({name} ...)')
            while self.peek() == ' ':
                self.pos += 1
            if self.peek() == ')':
                continue
            args.append(self.argument())

    def argument(self):
        c = self.peek()
        if c in ('"', "'"):
            self.pos += 1
            parts = self.template(stop=c)
            if self.peek() != c:
                raise self.fail(f'quoted argument is not closed with {c}')
            self.pos += 1
            return parts
        return self.template(stop=' )\'"')


def parse_template(text, where=(None, None)):
    """
    Parse an attribute value into a list of strings and Substitutions.

    :param where: ``(file, line)`` for error messages
    """
    if not isinstance(text, str):
        return [str(text)]
    parser = _Parser(text, where)
    parts = parser.template()
    if parser.pos != len(text):
        raise parser.fail(f'unexpected {text[parser.pos]!r}')
    return parts


class Context:
    """What substitutions see: launch configurations, the file, packages."""

    def __init__(self, *, configurations=None, launch_file=None, find_package=None,
                 environ=None):
        """
        Create a context.

        :param configurations: ``{name: value}`` set by args and lets
        :param launch_file: the launch file being read
        :param find_package: ``callable(name) -> prefix Path`` that raises
          LaunchError for a package that is not in the install space
        :param environ: the environment (defaults to os.environ)
        """
        self.configurations = dict(configurations or {})
        self.launch_file = launch_file
        self.find_package = find_package
        self.environ = os.environ if environ is None else environ
        self.anonymous = {}

    def child(self, *, launch_file=None):
        """Return a context for an included file, sharing configurations."""
        context = Context(configurations=self.configurations,
                          launch_file=launch_file or self.launch_file,
                          find_package=self.find_package, environ=self.environ)
        context.anonymous = self.anonymous
        return context


def _truthy(value, name, where):
    lowered = value.strip().lower()
    if lowered in ('true', '1'):
        return True
    if lowered in ('false', '0'):
        return False
    raise LaunchError(
        f'$({name}) expects true/false or 1/0, got {value!r}', *where)


def _expect(name, args, counts, where):
    if len(args) not in counts:
        expected = ' or '.join(str(c) for c in counts)
        raise LaunchError(
            f'$({name}) takes {expected} argument(s), got {len(args)}', *where)


def evaluate(parts, context, where=(None, None)):
    """Evaluate a parsed template to a string."""
    out = []
    for part in parts:
        if isinstance(part, str):
            out.append(part)
        else:
            out.append(_perform(part, context, where))
    return ''.join(out)


def _perform(sub, context, where):
    name = sub.name
    args = [evaluate(a, context, where) for a in sub.args]
    if name == 'var':
        _expect(name, args, (1,), where)
        if args[0] not in context.configurations:
            known = ', '.join(sorted(context.configurations)) or 'none'
            raise LaunchError(
                f"launch configuration '{args[0]}' is not set: declare it with <arg "
                f'name="{args[0]}" '
                f'default="..."/> or pass {args[0]}:=VALUE (set: {known})', *where)
        return context.configurations[args[0]]
    if name == 'env':
        _expect(name, args, (1, 2), where)
        if args[0] in context.environ:
            return context.environ[args[0]]
        if len(args) == 2:
            return args[1]
        raise LaunchError(
            f"environment variable '{args[0]}' is not set; give a default: $(env {args[0]} "
            'DEFAULT)', *where)
    if name in ('find-pkg-share', 'find-pkg-prefix'):
        _expect(name, args, (1,), where)
        if context.find_package is None:
            raise LaunchError(f'$({name}) needs an install space', *where)
        prefix = context.find_package(args[0], where)
        if name == 'find-pkg-prefix':
            return str(prefix)
        return str(Path(prefix) / 'share' / args[0])
    if name in ('dirname', 'filename'):
        _expect(name, args, (0,), where)
        if context.launch_file is None:
            raise LaunchError(f'$({name}) is only valid in a launch file', *where)
        path = Path(context.launch_file).resolve()
        return str(path.parent if name == 'dirname' else path)
    if name == 'anon':
        _expect(name, args, (1,), where)
        return context.anonymous.setdefault(
            args[0], f'{args[0]}_{secrets.token_hex(4)}')
    if name == 'eval':
        _expect(name, args, (1,), where)
        try:
            return str(eval(args[0], {'__builtins__': {}}, dict(math.__dict__)))
        except Exception as e:  # noqa: B902 the user's expression may raise anything
            raise LaunchError(f'$(eval {args[0]!r}) failed: {e}', *where) from None
    if name == 'not':
        _expect(name, args, (1,), where)
        return str(not _truthy(args[0], name, where)).lower()
    if name in ('and', 'or'):
        _expect(name, args, (2,), where)
        left, right = (_truthy(a, name, where) for a in args)
        return str(left and right if name == 'and' else left or right).lower()
    raise LaunchError(
        f'$({name}) is not supported by colcon-wasm launch (supported: var, env, '
        'find-pkg-share, find-pkg-prefix, dirname, filename, anon, eval, not, and, or)',
        *where)


def substitute(text, context, where=(None, None)):
    """Parse and evaluate an attribute value; non-strings pass through as text."""
    return evaluate(parse_template(text, where), context, where)


def condition(value, context, where):
    """Evaluate an ``if``/``unless`` value to a bool."""
    text = substitute(value, context, where) if isinstance(value, str) else value
    if isinstance(text, bool):
        return text
    lowered = str(text).strip().lower()
    if lowered in ('true', '1'):
        return True
    if lowered in ('false', '0'):
        return False
    raise LaunchError(
        f'a condition must be true/false or 1/0, got {text!r}', *where)
