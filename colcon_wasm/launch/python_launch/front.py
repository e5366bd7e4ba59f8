# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The host process of a Python launch file: ``ros2 launch``, with Humble's own ``launch``.

``colcon-wasm launch`` runs this module with the launcher's Python, the
install's module folders on ``PYTHONPATH`` and ``AMENT_PREFIX_PATH`` naming
the launch's host prefix (``host_prefix.py``). It does what ros2launch's
``launch_a_launch_file`` does: a ``LaunchService`` that includes the file
through ``IncludeLaunchDescription``, with the ``name:=value`` arguments.
launch, launch_ros, launch_xml and launch_yaml are the install's, unmodified.

Two things happen first, so that launch_ros imports on the build host:
``rclpy`` is colcon-wasm's (``packages/wasm_js/src/python/rclpy``), and
interface modules (``lifecycle_msgs.msg``, ...) are made from the install's
type descriptions, as they are for Python nodes. The node launch_ros makes
for LoadComposableNodes and LifecycleNode is on the launch's bus: rclpy's
bus functions go over the launch's socket (``rclpy/_host_link.py``).

Usage (by ``colcon_wasm.launch.python_launch``)::

    python3 -m colcon_wasm.launch.python_launch.front OPTIONS_JSON
"""

import json
import logging
import re
import sys
import traceback

from colcon_wasm.error import ColconWasmError

#: what to build when launch is missing (the Humble packages ros2 launch runs on)
LAUNCH_PACKAGES = ('launch', 'launch_ros', 'launch_xml', 'launch_yaml')


class FrontError(ColconWasmError):
    """A launch file or its arguments that cannot be launched; the text says why."""


def prepare_interfaces(types_files):
    """Make the install's interface modules importable (colcon-wasm's rclpy finder)."""
    from rclpy import _messages
    for path in types_files:
        try:
            with open(path, encoding='utf-8') as f:
                _messages.load_descriptions(f.read())
        except OSError as e:
            print(f'[WARNING] [launch]: cannot read the type descriptions {path}: {e}',
                  file=sys.stderr)
    _messages.install_finder()


def import_launch():
    """
    Import launch and launch_ros, or say which package is missing and how to build it.

    :raises FrontError: when the install space lacks them
    """
    try:
        import launch  # noqa: F401
        import launch.launch_description_sources  # noqa: F401
        import launch_ros.actions  # noqa: F401
    except ImportError as e:
        missing = getattr(e, 'name', None) or str(e)
        raise FrontError(
            "Python launch files run with Humble's launch and launch_ros, but importing them "
            f"failed ({e}): build them into the install space with 'colcon build --wasm "
            f"--packages-up-to {' '.join(LAUNCH_PACKAGES)}' (ros2/launch and ros2/launch_ros; "
            f'missing: {missing})') from None


def _load_trace(path):
    """Format the exception being handled, from the launch file's frames on."""
    kind, value, tb = sys.exc_info()
    frames = traceback.extract_tb(tb)
    at = next((i for i, f in enumerate(frames) if f.filename == str(path)), 0)
    lines = traceback.format_list(frames[at:]) + traceback.format_exception_only(kind, value)
    return 'Traceback (most recent call last):\n' + ''.join(lines)


def load_description(path):
    """
    Load a launch file with launch's own loader (any of Python, XML, YAML).

    :raises FrontError: with the traceback from the file's frames, when loading raises
    """
    from launch.launch_description_sources import get_launch_description_from_any_launch_file
    from launch.launch_description_sources import get_launch_description_from_python_launch_file
    # a Python file directly: launch's any-file loader would hide its exception behind a
    # list of what each frontend made of it
    load = get_launch_description_from_python_launch_file if str(path).endswith('.py') \
        else get_launch_description_from_any_launch_file
    try:
        return load(str(path))
    except Exception:
        raise FrontError(f'{path}: loading the launch file failed:\n{_load_trace(path)}') \
            from None


def arguments_text(description):
    """Describe a description's arguments as ``ros2 launch --show-args`` prints them."""
    lines = ["Arguments (pass arguments as '<name>:=<value>'):"]
    arguments = description.get_launch_arguments()
    conditional = False
    for argument in arguments:
        text = f"\n    '{argument.name}':"
        if argument._conditionally_included:
            conditional = True
            text += '*'
        text += f'\n        {argument.description}'
        if argument.default_value is not None:
            default = ' + '.join(token.describe() for token in argument.default_value)
            text += f'\n        (default: {default})'
        lines.append(text)
    if arguments:
        if conditional:
            lines.append('\n* argument(s) which are only used if specific conditions occur')
    else:
        lines.append('\n  No arguments.')
    return '\n'.join(lines)


def arguments_list(description):
    """
    Describe a description's arguments for the page's form (``serve``'s ``/launch``).

    Each is ``{name, default, description, choices, conditional}``; ``default``
    is launch's description of the default (None: required).
    """
    listed = []
    for argument in description.get_launch_arguments():
        default = None
        if argument.default_value is not None:
            default = ' + '.join(token.describe() for token in argument.default_value)
            # a plain text default reads as the text, not as its quoted description
            if all(type(t).__name__ == 'TextSubstitution' for t in argument.default_value):
                default = ''.join(t.text for t in argument.default_value)
        listed.append({'name': argument.name, 'default': default,
                       'description': argument.description or '',
                       'choices': list(getattr(argument, 'choices', None) or []),
                       'conditional': bool(argument._conditionally_included)})
    return listed


def parse_arguments(values):
    """Parse ``name:=value`` as ros2launch's ``parse_launch_arguments`` (the last one wins)."""
    parsed = {}
    for value in values:
        count = value.count(':=')
        if count == 0 or value.startswith(':=') or (count == 1 and value.endswith(':=')):
            raise FrontError(
                f"malformed launch argument '{value}', expected format '<name>:=<value>'")
        name, text = value.split(':=', maxsplit=1)
        parsed[name] = text
    return parsed


def check_arguments(path, description, given):
    """
    Refuse arguments the file does not declare, and required ones not given.

    ``ros2 launch`` passes unknown ones on silently; a typo then changes
    nothing. Here they are refused with the file's arguments listed.

    :raises FrontError: naming the argument, with the list of arguments
    """
    declared = {a.name: a for a in description.get_launch_arguments()}
    unknown = [name for name in given if name not in declared]
    if unknown:
        raise FrontError(
            f"{path}: no launch argument named {', '.join(repr(n) for n in unknown)}.\n"
            + arguments_text(description))
    missing = [a for a in declared.values()
               if a.default_value is None and not a._conditionally_included
               and a.name not in given]
    if missing:
        raise FrontError(
            f"{path}: the required launch argument {', '.join(repr(a.name) for a in missing)} "
            'is not given (pass it as name:=value).\n' + arguments_text(description))


#: host programs launch files run with Command/FindExecutable, and the package of each
HOST_TOOL_PACKAGES = {'xacro': 'xacro'}
_NOT_FOUND = re.compile(r"executable '([^']+)' not found on the PATH")


class MissingToolHint(logging.Filter):
    """Add to launch's "not found on the PATH" which package gives the program, and how."""

    def filter(self, record):  # noqa: A003 (logging's name)
        """Append the hint to a record that names a missing executable."""
        match = _NOT_FOUND.search(str(record.msg))
        if match:
            tool = match.group(1)
            package = HOST_TOOL_PACKAGES.get(tool)
            if package:
                hint = (f"'{tool}' comes from the package '{package}': build it into the "
                        f"install space ('colcon build --wasm --packages-up-to {package}'); "
                        'its bin/ programs run on the build host')
            else:
                hint = (f"'{tool}' is looked for in the install's bin/ folders (Python "
                        "programs, run on the build host) and on the host's PATH")
            record.msg = f'{record.msg} ({hint})'
        return True


def run(options):
    """Run (or describe) the launch file of ``options``; return the exit status."""
    import launch
    launch.logging.get_logger('launch').addFilter(MissingToolHint())
    path = options['file']
    given = parse_arguments(options.get('arguments', []))
    description = load_description(path)
    if options.get('show_args'):
        print(json.dumps(arguments_list(description)) if options.get('json')
              else arguments_text(description))
        return 0
    check_arguments(path, description, given)
    if options.get('print'):
        print(launch.LaunchIntrospector().format_launch_description(description))
        return 0
    service = launch.LaunchService(argv=options.get('arguments', []), noninteractive=True)
    # as ros2 launch: the file is included, so that its location and arguments are set
    service.include_launch_description(launch.LaunchDescription([
        launch.actions.IncludeLaunchDescription(
            launch.LaunchDescriptionSource(description, str(path), 'interpreted launch file'),
            launch_arguments=list(given.items())),
    ]))
    return service.run()


def main(argv=None):
    """Run ``front.py OPTIONS_JSON``; errors are one message and exit status 1."""
    argv = sys.argv[1:] if argv is None else argv
    options = json.loads(argv[0])
    try:
        prepare_interfaces(options.get('types', []))
        if options.get('socket'):
            # launch_ros' ROS node (LoadComposableNodes, LifecycleNode): on the launch's bus
            from rclpy import _bus
            _bus.link_on_first_use(options['socket'])
        import_launch()
        return run(options)
    except FrontError as e:
        print(f"{options.get('command', 'colcon-wasm launch')}: {e}", file=sys.stderr)
        return 1


if __name__ == '__main__':
    sys.exit(main())
