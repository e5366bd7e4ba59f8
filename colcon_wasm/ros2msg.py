# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Complete message definitions in rosbag2's ``ros2msg`` encoding.

An MCAP file written by rosbag2 (Humble: rosbag2_storage_mcap) stores with
each topic the schema of its type: the type's own ``.msg`` text, then, for
every type it uses (recursively, each once), a line of 80 ``=``, a line
``MSG: <pkg>/<Type>`` and that type's text. Dependencies come depth first,
the dependencies of one definition in sorted order, as rosbag2's
``MessageDefinitionCache::get_full_text`` does. Foxglove's WebSocket
protocol advertises channels with the same text (``schemaEncoding:
ros2msg``), and Foxglove's decoders parse it.

The texts come from the ``definition`` of each message in the
``types.json`` documents of the install (:mod:`colcon_wasm.typedesc`).

    from colcon_wasm.ros2msg import Ros2MsgSchemas
    schemas = Ros2MsgSchemas.from_documents(documents)
    schemas.full_text('sensor_msgs/msg/Image')
"""

import json

from colcon_wasm.error import ColconWasmError

"""The line between two definitions (followed by ``MSG: <pkg>/<Type>``)."""
DELIMITER = '=' * 80

_KINDS = ('msg', 'srv', 'action')


class SchemaError(ColconWasmError):
    """A type whose complete definition cannot be assembled (named in the text)."""


def short_name(type_name):
    """
    Name a type as ``.msg`` files and rosbag2's delimiters do: ``pkg/Type``.

    :param type_name: ``pkg/msg/Type`` (or ``pkg/srv/…``, ``pkg/action/…``)
    """
    parts = type_name.split('/')
    if len(parts) == 3:
        return f'{parts[0]}/{parts[2]}'
    return type_name


class Ros2MsgSchemas:
    """The complete definitions of the messages of some types.json documents."""

    def __init__(self, messages):
        """
        Index message descriptions by their full name.

        :param messages: ``{'pkg/msg/Type': description}`` as types.json holds
          them (each with a ``definition``)
        """
        self._messages = dict(messages)
        self._cache = {}

    @classmethod
    def from_documents(cls, documents):
        """Collect the messages of several types.json documents."""
        messages = {}
        for document in documents:
            messages.update(document.get('messages', {}))
        return cls(messages)

    @classmethod
    def from_files(cls, paths):
        """
        Read types.json files.

        :raises SchemaError: naming a file that cannot be read
        """
        documents = []
        for path in paths:
            try:
                documents.append(json.loads(open(path, encoding='utf-8').read()))
            except (OSError, ValueError) as e:
                raise SchemaError(
                    f"cannot read the type descriptions '{path}': {e}: rebuild its "
                    'package with `colcon build --wasm`') from e
        return cls.from_documents(documents)

    def names(self):
        """List the full names of the message types described."""
        return list(self._messages)

    def resolve(self, name):
        """
        Find the full name of a type named ``pkg/Type`` or ``pkg/msg/Type``.

        :returns: the full name, or None when no document describes it
        """
        if name in self._messages:
            return name
        parts = name.split('/')
        if len(parts) == 2:
            for kind in _KINDS:
                candidate = f'{parts[0]}/{kind}/{parts[1]}'
                if candidate in self._messages:
                    return candidate
        return None

    def _description(self, name, needed_by):
        full = self.resolve(name)
        if full is None:
            where = f" (used by '{needed_by}')" if needed_by else ''
            raise SchemaError(
                f"no type description of '{name}'{where}: build its interface package "
                'with `colcon build --wasm`, or add it to the install chain')
        description = self._messages[full]
        if 'definition' not in description:
            raise SchemaError(
                f"the type description of '{full}' has no definition text (written by an "
                'older colcon-wasm): rebuild its package with `colcon build --wasm`')
        return full, description

    def dependencies(self, name):
        """List the full names of the message types a type's fields use (sorted)."""
        full, description = self._description(name, None)
        used = set()
        for field in description.get('fields', []):
            if field['type'].count('/') == 2:
                used.add(field['type'])
        return sorted(used, key=short_name)

    def full_text(self, name):
        """
        Assemble the complete definition of a type, as rosbag2 writes it.

        :param name: ``pkg/msg/Type`` or ``pkg/Type``
        :raises SchemaError: naming the type (and its user) with no description
        """
        root, _ = self._description(name, None)
        if root in self._cache:
            return self._cache[root]
        parts = []
        seen = {root}

        def append(full, needed_by):
            full, description = self._description(full, needed_by)
            if parts:
                parts.append(f'\n{DELIMITER}\nMSG: {short_name(full)}\n')
            parts.append(description['definition'])
            for dependency in self.dependencies(full):
                if dependency not in seen:
                    seen.add(dependency)
                    append(dependency, full)

        append(root, None)
        text = ''.join(parts)
        self._cache[root] = text
        return text
