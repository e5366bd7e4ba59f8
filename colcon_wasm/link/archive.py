# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Read the members of a static archive (the `ar` format emar writes)."""

import os

from colcon_wasm.error import ColconWasmError

MAGIC = b'!<arch>\n'
HEADER_SIZE = 60


class ArchiveError(ColconWasmError):
    """An archive that cannot be read."""


def read_members(path):
    """
    List the object members of an archive, in archive order.

    GNU and BSD long names are resolved; the symbol tables (`/`, `//`,
    `__.SYMDEF`) are not members.

    :param str path: the archive
    :returns: a list of (name, offset, size) with the offset of the data
    :raises ArchiveError: when the file is not an archive
    """
    with open(path, 'rb') as handle:
        data = handle.read()
    if not data.startswith(MAGIC):
        raise ArchiveError(f"'{path}' is not an ar archive")
    members = []
    long_names = b''
    position = len(MAGIC)
    while position + HEADER_SIZE <= len(data):
        header = data[position:position + HEADER_SIZE]
        if header[58:60] != b'`\n':
            raise ArchiveError(
                f"'{path}': bad member header at offset {position}")
        raw_name = header[0:16].decode('utf-8', 'replace').rstrip(' ')
        try:
            size = int(header[48:58].decode().strip())
        except ValueError as e:
            raise ArchiveError(
                f"'{path}': bad member size at offset {position}") from e
        start = position + HEADER_SIZE
        total = size
        name = raw_name
        offset = start
        if raw_name == '//':
            long_names = data[start:start + size]
            name = None
        elif raw_name in ('/', '/SYM64/') or raw_name.startswith('__.SYMDEF'):
            name = None
        elif raw_name.startswith('/') and raw_name[1:].isdigit():
            index = int(raw_name[1:])
            end = long_names.find(b'\n', index)
            name = long_names[index:end if end >= 0 else None].decode(
                'utf-8', 'replace').rstrip('/')
        elif raw_name.startswith('#1/') and raw_name[3:].isdigit():
            # BSD: the name is stored at the start of the data
            length = int(raw_name[3:])
            name = data[start:start + length].decode(
                'utf-8', 'replace').rstrip('\0')
            offset = start + length
            size -= length
        else:
            name = raw_name.rstrip('/')
        if name is not None:
            members.append((name, offset, size))
        position = start + total + (total % 2)
    return members


def extract_member(path, index, destination):
    """
    Write the `index`-th object member of an archive to a file.

    :param str path: the archive
    :param int index: the member's position among :func:`read_members`
    :param str destination: the file to write (replaced atomically)
    """
    name, offset, size = read_members(path)[index]
    with open(path, 'rb') as handle:
        handle.seek(offset)
        data = handle.read(size)
    staging = f'{destination}.{os.getpid()}'
    with open(staging, 'wb') as handle:
        handle.write(data)
    os.replace(staging, destination)
