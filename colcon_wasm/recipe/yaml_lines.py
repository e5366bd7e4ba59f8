# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""A YAML loader that remembers the line of every key and list item."""

import yaml


class LineDict(dict):
    """A mapping that knows the line of each of its keys (1-based)."""

    line = None

    def __init__(self, *args, **kwargs):  # noqa: D107
        super().__init__(*args, **kwargs)
        self.key_lines = {}

    def line_of(self, key):
        """Get the line of a key, or of the mapping when unknown."""
        return self.key_lines.get(key, self.line)


class LineList(list):
    """A sequence that knows the line of each item (1-based)."""

    line = None

    def __init__(self, *args, **kwargs):  # noqa: D107
        super().__init__(*args, **kwargs)
        self.item_lines = []

    def line_of(self, index):
        """Get the line of an item, or of the sequence when unknown."""
        if 0 <= index < len(self.item_lines):
            return self.item_lines[index]
        return self.line


class _LineLoader(yaml.SafeLoader):
    """SafeLoader producing :class:`LineDict` and :class:`LineList`."""


def _construct_mapping(loader, node):
    loader.flatten_mapping(node)
    result = LineDict()
    result.line = node.start_mark.line + 1
    for key_node, value_node in node.value:
        key = loader.construct_object(key_node, deep=True)
        if key in result:
            raise yaml.constructor.ConstructorError(
                None, None, f"duplicate key '{key}'", key_node.start_mark)
        result[key] = loader.construct_object(value_node, deep=True)
        result.key_lines[key] = key_node.start_mark.line + 1
    return result


def _construct_sequence(loader, node):
    result = LineList()
    result.line = node.start_mark.line + 1
    for item_node in node.value:
        result.append(loader.construct_object(item_node, deep=True))
        result.item_lines.append(item_node.start_mark.line + 1)
    return result


_LineLoader.add_constructor(
    yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, _construct_mapping)
_LineLoader.add_constructor(
    yaml.resolver.BaseResolver.DEFAULT_SEQUENCE_TAG, _construct_sequence)


def load(text):
    """
    Parse YAML text keeping line numbers.

    :param str text: the YAML document
    :returns: the data (mappings as :class:`LineDict`, sequences as
      :class:`LineList`)
    :raises yaml.YAMLError: on a syntax error (its mark has the line)
    """
    return yaml.load(text, Loader=_LineLoader)  # noqa: S506 (SafeLoader)
