# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Golden CDR vectors from the real Fast CDR library.

``tests/data/cdr/*.json`` hold test values of the ``cdr_test_msgs`` types
and their CDR bytes.  This module writes a C++ program that serialises the
values exactly the way ``rosidl_typesupport_fastrtps_cpp`` (Humble,
``msg__type_support.cpp.em``) drives Fast CDR 1.x, compiles it against the
system's Fast CDR (Debian: ``libfastcdr-dev``) and reads the bytes back.

    python3 tests/cdr_fastcdr.py --write    # refresh the hex of every vector

Vector values list every field.  64-bit integers are decimal strings,
non-finite floats the strings ``NaN``/``Infinity``/``-Infinity``, wstrings
plain strings (UTF-16 code units go on the wire).  Padding bytes are zero
(Fast CDR skips over them; this program hands it a zeroed buffer).
"""

import argparse
import json
import os
from pathlib import Path
import shutil
import subprocess
import sys
import tempfile

HERE = Path(__file__).resolve().parent
DATA = HERE / 'data' / 'cdr'
PACKAGE_DIR = DATA / 'cdr_test_msgs'

CPP_TYPES = {
    'bool': 'bool', 'byte': 'uint8_t', 'char': 'uint8_t',
    'float32': 'float', 'float64': 'double',
    'int8': 'int8_t', 'uint8': 'uint8_t', 'int16': 'int16_t', 'uint16': 'uint16_t',
    'int32': 'int32_t', 'uint32': 'uint32_t', 'int64': 'int64_t', 'uint64': 'uint64_t',
    'string': 'std::string', 'wstring': 'std::u16string',
}


def load_types():
    """Describe the cdr_test_msgs package with colcon_wasm.typedesc."""
    sys.path.insert(0, str(HERE.parent))
    from colcon_wasm import typedesc
    return typedesc.describe_package(PACKAGE_DIR, 'cdr_test_msgs')


def load_vectors():
    """Return ``{file name: document}`` of every vector file."""
    return {p.name: json.loads(p.read_text(encoding='utf-8'))
            for p in sorted(DATA.glob('*.json'))}


def _struct(name):
    return name.replace('/', '__')


def _is_nested(type_name):
    return '/' in type_name


def _ordered(messages):
    """Message names, dependencies first."""
    done = []

    def visit(name):
        if name in done:
            return
        for field in messages[name]['fields']:
            if _is_nested(field['type']):
                visit(field['type'])
        done.append(name)
    for name in sorted(messages):
        visit(name)
    return done


def _member_type(field):
    base = _struct(field['type']) if _is_nested(field['type']) else CPP_TYPES[field['type']]
    if 'array_size' in field:
        return f"std::array<{base}, {field['array_size']}>"
    if field.get('sequence'):
        return f'std::vector<{base}>'
    return base


def _serialize_member(field):
    """Return the statements of msg__type_support.cpp.em (Humble) for one member."""
    m = 'm.' + field['name']
    t = field['type']
    nested = _is_nested(t)
    wide = t == 'wstring'
    basic = t in CPP_TYPES and t not in ('string', 'wstring')
    out = []
    if 'array_size' in field:
        if not (nested or wide):
            out.append(f'cdr << {m};')
        else:
            out.append(f"for (size_t i = 0; i < {field['array_size']}; i++) {{")
            if nested:
                out.append(f'  ser({m}[i], cdr);')
            else:
                out.append(f'  std::wstring wstr; u16_to_w({m}[i], wstr); cdr << wstr;')
            out.append('}')
    elif field.get('sequence'):
        bounded = 'sequence_bound' in field
        if not (nested or wide) and not bounded:
            out.append(f'cdr << {m};')
        else:
            out.append(f'size_t size = {m}.size();')
            if bounded:
                out.append(f"if (size > {field['sequence_bound']}) "
                           'throw std::runtime_error("bound");')
            out.append('cdr << static_cast<uint32_t>(size);')
            if basic and t != 'bool':
                out.append(f'if (size > 0) cdr.serializeArray(&({m}[0]), size);')
            else:
                out.append('for (size_t i = 0; i < size; i++) {')
                if t == 'bool':
                    out.append(f'  cdr << ({m}[i] ? true : false);')
                elif wide:
                    out.append(
                        f'  std::wstring wstr; u16_to_w({m}[i], wstr); cdr << wstr;')
                elif nested:
                    out.append(f'  ser({m}[i], cdr);')
                else:
                    out.append(f'  cdr << {m}[i];')
                out.append('}')
    elif t == 'bool':
        out.append(f'cdr << ({m} ? true : false);')
    elif wide:
        out.append(f'std::wstring wstr; u16_to_w({m}, wstr); cdr << wstr;')
    elif nested:
        out.append(f'ser({m}, cdr);')
    else:
        out.append(f'cdr << {m};')
    return ['  {'] + ['    ' + line for line in out] + ['  }']


def _literal(type_name, value):
    if type_name == 'bool':
        return 'true' if value else 'false'
    if type_name in ('float32', 'float64'):
        ctype = CPP_TYPES[type_name]
        if value in ('NaN', 'Infinity', '-Infinity'):
            limit = 'quiet_NaN()' if value == 'NaN' else 'infinity()'
            sign = '-' if value == '-Infinity' else ''
            return f'{sign}std::numeric_limits<{ctype}>::{limit}'
        return f'static_cast<{ctype}>({float(value).hex()})'
    if type_name == 'string':
        data = value.encode('utf-8')
        if not data:
            return 'std::string()'
        return f"std::string({{{', '.join(('char({})'.format(b) for b in data))}}})"
    if type_name == 'wstring':
        units = value.encode('utf-16-le')
        codes = [units[i] | units[i + 1] << 8 for i in range(0, len(units), 2)]
        chars = ', '.join(f'char16_t({c})' for c in codes)
        return f'std::u16string({{{chars}}})' if codes else 'std::u16string()'
    number = int(value)
    if type_name == 'int64' and number == -2 ** 63:
        return 'std::numeric_limits<int64_t>::min()'
    suffix = 'ULL' if type_name.startswith('u') or type_name in ('byte', 'char') else 'LL'
    return f'static_cast<{CPP_TYPES[type_name]}>({number}{suffix})'


def _assign(messages, type_name, value, target, where):
    description = messages[type_name]
    names = [f['name'] for f in description['fields']]
    missing = [n for n in names if n not in value]
    extra = [k for k in value if k not in names]
    if missing or extra:
        raise ValueError(f'{where}: a vector of {type_name} must list every field (missing '
                         f'{missing}, unknown {extra})'
                         )
    out = []
    for field in description['fields']:
        v = value[field['name']]
        lhs = f"{target}.{field['name']}"
        items = None
        if 'array_size' in field:
            if len(v) != field['array_size']:
                raise ValueError(f"{where}: {lhs} needs {field['array_size']} elements")
            items = v
        elif field.get('sequence'):
            out.append(f'{lhs}.resize({len(v)});')
            items = v
        if items is None:
            if _is_nested(field['type']):
                out += _assign(messages, field['type'], v, lhs, where)
            else:
                out.append(f"{lhs} = {_literal(field['type'], v)};")
            continue
        for i, item in enumerate(items):
            element = f'{lhs}[{i}]'
            if _is_nested(field['type']):
                out += _assign(messages, field['type'], item, element, where)
            else:
                out.append(f"{element} = {_literal(field['type'], item)};")
    return out


def generate_program(types, cases):
    """
    Write the C++ source that prints ``name hex`` for each case.

    :param types: the types.json document of cdr_test_msgs
    :param cases: ``[(name, type, value)]``
    """
    messages = types['messages']
    lines = [
        '// Generated by tests/cdr_fastcdr.py: serialises test values the way',
        '// rosidl_typesupport_fastrtps_cpp (Humble) drives Fast CDR.',
        '#include <fastcdr/Cdr.h>',
        '#include <fastcdr/FastBuffer.h>',
        '#include <array>', '#include <cstdint>', '#include <cstdio>', '#include <limits>',
        '#include <stdexcept>', '#include <string>', '#include <vector>',
        'using eprosima::fastcdr::Cdr;',
        'using eprosima::fastcdr::FastBuffer;',
        'static void u16_to_w(const std::u16string & u16, std::wstring & w) {',
        '  w.resize(u16.size());',
        '  for (size_t i = 0; i < u16.size(); ++i) w[i] = static_cast<wchar_t>(u16[i]);',
        '}',
    ]
    for name in _ordered(messages):
        lines.append(f'struct {_struct(name)} {{')
        for field in messages[name]['fields']:
            lines.append(f"  {_member_type(field)} {field['name']}{{}};")
        lines.append('};')
        lines.append(f'static void ser(const {_struct(name)} & m, Cdr & cdr) {{')
        for field in messages[name]['fields']:
            lines += _serialize_member(field)
        lines.append('}')
    lines.append('template<typename T> static void emit(const char * name, const T & m) {')
    lines.append('  std::vector<char> raw(1 << 20, 0);')
    lines.append('  FastBuffer buffer(raw.data(), raw.size());')
    lines.append('  Cdr cdr(buffer, Cdr::DEFAULT_ENDIAN, Cdr::DDS_CDR);')
    lines.append('  cdr.serialize_encapsulation();')
    lines.append('  ser(m, cdr);')
    lines.append('  printf("%s ", name);')
    lines.append('  for (size_t i = 0; i < cdr.getSerializedDataLength(); ++i) '
                 'printf("%02x", static_cast<unsigned char>(raw[i]));')
    lines.append('  printf("\\n");')
    lines.append('}')
    lines.append('int main() {')
    for name, type_name, value in cases:
        lines.append('  {')
        lines.append(f'    {_struct(type_name)} m{{}};')
        lines += ['    ' + s for s in _assign(messages, type_name, value, 'm', name)]
        lines.append(f'    emit("{name}", m);')
        lines.append('  }')
    lines.append('  return 0;')
    lines.append('}')
    return '\n'.join(lines) + '\n'


def compiler():
    """Return the C++ compiler, or None when g++ or Fast CDR is missing."""
    cxx = shutil.which(os.environ.get('CXX', 'g++'))
    headers = Path('/usr/include/fastcdr/Cdr.h')
    if cxx is None or not headers.is_file():
        return None
    return cxx


def serialize_with_fastcdr(types, cases, workdir):
    """Compile and run the program; return ``{case name: hex}``."""
    cxx = compiler()
    if cxx is None:
        raise RuntimeError('needs g++ and Fast CDR (apt-get install g++ libfastcdr-dev)')
    source = Path(workdir) / 'fastcdr_vectors.cpp'
    binary = Path(workdir) / 'fastcdr_vectors'
    source.write_text(generate_program(types, cases), encoding='utf-8')
    subprocess.run([cxx, '-std=c++17', '-O0', str(source), '-o', str(binary), '-lfastcdr'],
                   check=True, capture_output=True, text=True)
    output = subprocess.run([str(binary)], check=True, capture_output=True, text=True).stdout
    result = {}
    for line in output.splitlines():
        name, _, hex_bytes = line.partition(' ')
        result[name] = hex_bytes
    return result


def all_cases(vector_files):
    """Flatten the vector files to ``[(name, type, value)]``."""
    return [(case['name'], case['type'], case['value'])
            for document in vector_files.values() for case in document['vectors']]


def main(argv=None):
    """Refresh the hex of every golden vector from Fast CDR."""
    parser = argparse.ArgumentParser(description=main.__doc__)
    parser.add_argument('--write', action='store_true',
                        help='write the hex into tests/data/cdr/*.json')
    args = parser.parse_args(argv)
    types = load_types()
    files = load_vectors()
    with tempfile.TemporaryDirectory() as workdir:
        hexes = serialize_with_fastcdr(types, all_cases(files), workdir)
    changed = 0
    for file_name, document in files.items():
        for case in document['vectors']:
            if case.get('hex') != hexes[case['name']]:
                changed += 1
                print(f"{file_name}: {case['name']}: {hexes[case['name']]}")
                case['hex'] = hexes[case['name']]
        if args.write:
            (DATA / file_name).write_text(
                json.dumps(document, indent=1, ensure_ascii=False) + '\n', encoding='utf-8')
    written = ', written' if args.write and changed else ''
    print(f'{changed} vector(s) differ from Fast CDR{written}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
