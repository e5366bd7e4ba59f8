# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Read XML and YAML launch files into Entities that remember their lines.

Both front ends give the same shape, as ``launch.frontend.Entity`` does:
an entity has a kind (``node``, ``arg`` ...), attributes, lists of
sub-entities by name (``remap``, ``param``) and children (``group``).
"""

from xml.parsers import expat

from colcon_wasm.launch.errors import LaunchError
import yaml


class Entity:
    """One tag of a launch file (XML element or YAML mapping)."""

    def __init__(self, kind, *, source, line, attributes=None, lists=None, children=None):
        """
        Create an entity.

        :param kind: the tag, e.g. ``'node'``
        :param source: the launch file
        :param line: the line of the tag
        :param attributes: ``{name: (value, line)}``
        :param lists: ``{name: [Entity]}`` for nested tags such as remap
        :param children: the child entities of a group or launch, or None
        """
        self.kind = kind
        self.source = source
        self.line = line
        self.attributes = attributes or {}
        self.lists = lists or {}
        self.children_list = children
        self.frontend = 'yaml' if str(source).lower().endswith(('.yaml', '.yml')) else 'xml'
        self._read = set()

    @property
    def where(self):
        """Return ``(file, line)`` of the tag."""
        return (self.source, self.line)

    def where_of(self, name):
        """Return ``(file, line)`` of an attribute (the tag's line if unknown)."""
        if name in self.attributes:
            return (self.source, self.attributes[name][1] or self.line)
        return self.where

    def get(self, name, *, optional=True):
        """Return an attribute's value, or None when absent and optional."""
        self._read.add(name)
        if name in self.attributes:
            return self.attributes[name][0]
        if not optional:
            raise LaunchError(
                f"<{self.kind}> needs the attribute '{name}'", *self.where)
        return None

    def get_list(self, name):
        """Return the nested entities of a name (XML child tags, YAML list)."""
        self._read.add(name)
        return self.lists.get(name, [])

    def children(self):
        """Return the child entities."""
        self._read.add('children')
        return self.children_list or []

    def check_complete(self, ignored=()):
        """Raise for attributes or nested tags nobody read (typos, unsupported)."""
        unread = [n for n in list(self.attributes) + list(self.lists)
                  if n not in self._read and n not in ignored]
        if not unread and self.children_list and 'children' not in self._read:
            child = self.children_list[0]
            raise LaunchError(
                f'unexpected tag <{child.kind}> inside <{self.kind}>: it is misspelled or not '
                'supported by '
                'colcon-wasm launch', *child.where)
        if unread:
            name = unread[0]
            kind = 'tag' if name in self.lists else 'attribute'
            raise LaunchError(
                f"unexpected {kind} '{name}' in <{self.kind}>: it is misspelled or not supported "
                'by '
                'colcon-wasm launch', *self.where_of(name))


# --------------------------------------------------------------------- XML

# Tags whose child tags are sub-entities of the tag, not actions.
_XML_LISTS = {
    'node': ('remap', 'param', 'env'),
    'node_container': ('remap', 'param', 'env', 'composable_node'),
    'composable_node': ('remap', 'param', 'extra_arg'),
    'load_composable_node': ('composable_node',),
    'param': ('param',),
    'include': ('arg',),
    'arg': ('choice',),
}


def read_xml(path):
    """Read an XML launch file; return the root ``<launch>`` Entity."""
    stack = []
    root = []
    parser = expat.ParserCreate()

    def start(tag, attributes):
        line = parser.CurrentLineNumber
        entity = Entity(tag, source=path, line=line,
                        attributes={k: (v, line) for k, v in attributes.items()})
        if stack:
            parent = stack[-1]
            if tag in _XML_LISTS.get(parent.kind, ()):
                parent.lists.setdefault(tag, []).append(entity)
            else:
                if parent.children_list is None:
                    parent.children_list = []
                parent.children_list.append(entity)
        else:
            root.append(entity)
        stack.append(entity)

    def end(tag):
        stack.pop()

    parser.StartElementHandler = start
    parser.EndElementHandler = end
    try:
        with open(path, 'rb') as f:
            parser.ParseFile(f)
    except expat.ExpatError as e:
        raise LaunchError(f'not valid XML: {expat.ErrorString(e.code)}',
                          path, e.lineno) from None
    except OSError as e:
        raise LaunchError(f'cannot read the launch file: {e.strerror}', path) from None
    entity = root[0]
    if entity.kind != 'launch':
        raise LaunchError(f'the root tag is <{entity.kind}>, expected <launch>',
                          *entity.where)
    return entity


# -------------------------------------------------------------------- YAML

def _yaml_entity(kind, node, loader, path):
    line = node.start_mark.line + 1
    if isinstance(node, yaml.SequenceNode):
        return Entity(kind, source=path, line=line,
                      children=[_yaml_single_key(item, loader, path) for item in node.value])
    if not isinstance(node, yaml.MappingNode):
        raise LaunchError(
            f"'{kind}' must be a mapping of attributes or a list of entities",
            path, line)
    entity = Entity(kind, source=path, line=line)
    for key_node, value_node in node.value:
        key = loader.construct_object(key_node)
        value_line = value_node.start_mark.line + 1
        if key == 'children' and isinstance(value_node, yaml.SequenceNode):
            entity.children_list = [
                _yaml_single_key(item, loader, path) for item in value_node.value]
        elif isinstance(value_node, yaml.SequenceNode) and value_node.value and all(
                isinstance(item, yaml.MappingNode) for item in value_node.value):
            entity.lists[key] = [_yaml_entity(key, item, loader, path)
                                 for item in value_node.value]
        else:
            entity.attributes[key] = (loader.construct_object(value_node, deep=True),
                                      value_line)
    return entity


def _yaml_single_key(node, loader, path):
    line = node.start_mark.line + 1
    if not isinstance(node, yaml.MappingNode) or len(node.value) != 1:
        raise LaunchError(
            'each entry must be a mapping with one key, the entity type '
            '(e.g. "- node: {pkg: ..., exec: ...}")', path, line)
    key_node, value_node = node.value[0]
    return _yaml_entity(loader.construct_object(key_node), value_node, loader, path)


def read_yaml(path):
    """Read a YAML launch file; return the root ``launch`` Entity."""
    try:
        with open(path, 'r', encoding='utf-8') as f:
            text = f.read()
    except OSError as e:
        raise LaunchError(f'cannot read the launch file: {e.strerror}', path) from None
    except UnicodeDecodeError as e:
        raise LaunchError(f'not UTF-8 text: {e.reason} at byte {e.start}', path) from None
    try:
        loader = yaml.SafeLoader(text)
    except yaml.YAMLError as e:
        # a character YAML does not allow (the reader checks them first)
        raise LaunchError(f'not valid YAML: {e}', path) from None
    try:
        node = loader.get_single_node()
        if not isinstance(node, yaml.MappingNode) or len(node.value) != 1 or \
                loader.construct_object(node.value[0][0]) != 'launch':
            raise LaunchError(
                "a YAML launch file has one top-level key 'launch' with a list of entities",
                path, node.start_mark.line + 1 if node is not None else None)
        return _yaml_entity('launch', node.value[0][1], loader, path)
    except yaml.MarkedYAMLError as e:
        line = e.problem_mark.line + 1 if e.problem_mark else None
        raise LaunchError(f'not valid YAML: {e.problem}', path, line) from None
    finally:
        loader.dispose()
