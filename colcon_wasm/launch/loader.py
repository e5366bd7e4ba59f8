# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Turn the entities of an XML or YAML launch file into a LaunchPlan.

Supported, with the semantics of launch/launch_ros (Humble): ``arg`` (with
``default``, ``description``, ``choice``), ``let``, ``node`` (``pkg``,
``exec``, ``name``, ``namespace``, ``args``, ``ros_args``, ``exec_name``,
``remap``, ``param`` with ``value``/nested ``param``/``from``, ``env``),
``group`` (``scoped``), ``push-ros-namespace``, ``include`` of XML/YAML
files with ``arg``, ``node_container`` (a ``node`` with ``composable_node``
children) and ``load_composable_node`` (``target``, ``composable_node``), and
``if``/``unless`` on each of them.  Anything else is an error that names the
file and line, never silently skipped.

Over 500 lines on purpose: one walker of launch's entity kinds, each a short
method on ``Loader``; splitting them would spread one grammar over modules.
"""

from pathlib import Path
import shlex

from colcon_wasm.launch.composable import ComposableNode
from colcon_wasm.launch.composable import extra_argument_value
from colcon_wasm.launch.composable import file_parameters
from colcon_wasm.launch.composable import LoadComposableNodes
from colcon_wasm.launch.errors import LaunchError
from colcon_wasm.launch.frontends import read_xml
from colcon_wasm.launch.frontends import read_yaml
from colcon_wasm.launch.launch_plan import absolute_namespace
from colcon_wasm.launch.launch_plan import LaunchPlan
from colcon_wasm.launch.launch_plan import NodeProcess
from colcon_wasm.launch.launch_plan import validate_node_name
from colcon_wasm.launch.launch_plan import yaml_value
from colcon_wasm.launch.substitutions import condition
from colcon_wasm.launch.substitutions import Context
from colcon_wasm.launch.substitutions import evaluate
from colcon_wasm.launch.substitutions import parse_template
from colcon_wasm.launch.substitutions import substitute
import yaml

# Attributes of <node> that only change how `ros2 launch` shows output.
_IGNORED_NODE_ATTRIBUTES = ('output', 'emulate_tty', 'sigterm_timeout', 'sigkill_timeout')
_NAMESPACE_KEY = 'ros_namespace'


def read_launch_file(path):
    """Read an XML or YAML launch file by its suffix; return the root Entity."""
    path = Path(path)
    suffix = path.name.lower()
    if suffix.endswith('.py'):
        raise LaunchError(
            "Python launch files are not read here: Humble's launch runs them "
            "('colcon-wasm launch FILE.launch.py', colcon_wasm/launch/python_launch/); this "
            'reader takes XML (.launch.xml) and YAML (.launch.yaml) launch files', path)
    if suffix.endswith('.xml'):
        return read_xml(path)
    if suffix.endswith(('.yaml', '.yml')):
        return read_yaml(path)
    raise LaunchError(
        'unknown launch file type: use a .launch.xml or .launch.yaml file', path)


class Loader:
    """Walk launch entities and collect NodeProcesses."""

    def __init__(self, install_space=None, environ=None, *, listing=False):
        """
        Create a loader; ``install_space`` resolves ``$(find-pkg-share)``.

        :param listing: collect the declared arguments (``declared``) only: a
          required one that is not given reads as empty, and no choice is checked
        """
        self.install_space = install_space
        self.environ = environ
        self.listing = listing
        self.processes = []
        self.loads = []
        self.include_stack = []
        self.declared = []

    def _find_package(self, name, where):
        if self.install_space is None:
            raise LaunchError(
                f'$(find-pkg-share {name}) needs an install space (--install-base)',
                *where)
        try:
            return self.install_space.find_package_prefix(name)
        except Exception as e:  # InstallSpaceError, with the list of packages
            raise LaunchError(str(e), *where) from None

    def load(self, path, arguments):
        """Load a launch file with ``name:=value`` arguments; return a LaunchPlan."""
        context = Context(configurations=arguments, launch_file=Path(path),
                          find_package=self._find_package, environ=self.environ)
        self._file(Path(path), context)
        for load in self.loads:
            if not load.containers:  # a load_composable_node: its container, if launched here
                load.containers = [p for p in self.processes
                                   if p.node_name == load.container_name]
        return LaunchPlan(self.processes, arguments, self.loads)

    def _file(self, path, context):
        resolved = path.resolve()
        if resolved in self.include_stack:
            chain = ' -> '.join(str(p) for p in self.include_stack + [resolved])
            raise LaunchError('launch files include each other in a loop: ' + chain, path)
        self.include_stack.append(resolved)
        try:
            root = read_launch_file(path)
            children = root.children()
            root.check_complete(ignored=('version',))
            self._actions(children, context)
        finally:
            self.include_stack.pop()

    def _actions(self, entities, context):
        for entity in entities:
            if not self._condition(entity, context):
                continue
            handler = {
                'arg': self._arg,
                'let': self._let,
                'node': self._node,
                'group': self._group,
                'push-ros-namespace': self._push_namespace,
                'push_ros_namespace': self._push_namespace,
                'include': self._include,
                'node_container': self._node_container,
                'load_composable_node': self._load_composable_node,
            }.get(entity.kind)
            if handler is None:
                raise LaunchError(
                    f'<{entity.kind}> is not supported by colcon-wasm launch (supported: arg, '
                    'let, node, '
                    'group, push-ros-namespace, include, node_container, '
                    'load_composable_node)', *entity.where)
            handler(entity, context)

    def _condition(self, entity, context):
        result = True
        for key, wanted in (('if', True), ('unless', False)):
            value = entity.get(key)
            if value is not None:
                result = result and condition(value, context, entity.where_of(key)) == wanted
        return result

    def _text(self, entity, name, context, *, optional=True):
        value = entity.get(name, optional=optional)
        if value is None:
            return None
        return substitute(value, context, entity.where_of(name))

    # ---------------------------------------------------------------- actions

    def _arg(self, entity, context):
        name = self._text(entity, 'name', context, optional=False)
        default = self._text(entity, 'default', context)
        description = entity.get('description') or ''
        choices = [self._text(c, 'value', context, optional=False)
                   for c in entity.get_list('choice')]
        for choice in entity.get_list('choice'):
            choice.check_complete()
        entity.check_complete()
        if all(a['name'] != name for a in self.declared):
            self.declared.append({'name': name, 'default': default,
                                  'description': description,
                                  'choices': choices, 'conditional': False})
        if self.listing:
            context.configurations.setdefault(name, '' if default is None else default)
            return
        if name not in context.configurations:
            if default is None:
                raise LaunchError(
                    f"launch argument '{name}' is required: pass {name}:=VALUE",
                    *entity.where)
            context.configurations[name] = default
        value = context.configurations[name]
        if choices and value not in choices:
            raise LaunchError(
                f"launch argument '{name}' is {value!r}, but must be one of: "
                f"{', '.join(choices)}", *entity.where)

    def _let(self, entity, context):
        name = self._text(entity, 'name', context, optional=False)
        context.configurations[name] = self._text(entity, 'value', context, optional=False)
        entity.check_complete()

    def _group(self, entity, context):
        scoped = entity.get('scoped')
        scoped = True if scoped is None else condition(scoped, context, entity.where_of('scoped'))
        children = entity.children()
        entity.check_complete()
        if scoped:
            inner = context.child()
            inner.configurations = dict(context.configurations)
        else:
            inner = context
        self._actions(children, inner)

    def _push_namespace(self, entity, context):
        namespace = self._text(entity, 'namespace', context, optional=False)
        entity.check_complete()
        context.configurations[_NAMESPACE_KEY] = absolute_namespace(
            context.configurations.get(_NAMESPACE_KEY), namespace)

    def _include(self, entity, context):
        file_text = self._text(entity, 'file', context, optional=False)
        path = Path(file_text)
        if not path.is_absolute() and context.launch_file is not None:
            path = Path(context.launch_file).parent / path
        if not path.is_file():
            raise LaunchError(f'included launch file {path} does not exist',
                              *entity.where_of('file'))
        inner = context.child(launch_file=path)
        inner.configurations = dict(context.configurations)
        for arg in entity.get_list('arg'):
            name = self._text(arg, 'name', context, optional=False)
            inner.configurations[name] = self._text(arg, 'value', context, optional=False)
            arg.check_complete()
        entity.check_complete()
        self._file(path, inner)

    def _node(self, entity, context):
        package = self._text(entity, 'pkg', context, optional=False)
        executable = self._text(entity, 'exec', context, optional=False)
        name = self._text(entity, 'name', context)
        namespace = absolute_namespace(
            context.configurations.get(_NAMESPACE_KEY), self._text(entity, 'namespace', context))
        arguments = self._command_line(entity, 'args', context)
        ros_arguments = self._command_line(entity, 'ros_args', context)
        exec_name = self._text(entity, 'exec_name', context)
        for key in ('respawn', 'launch-prefix', 'launch_prefix', 'cwd'):
            if entity.get(key) is not None:
                raise LaunchError(
                    f"the <{entity.kind}> attribute '{key}' is not supported by colcon-wasm "
                    'launch', *entity.where_of(key))
        remappings = []
        for remap in entity.get_list('remap'):
            remappings.append((self._text(remap, 'from', context, optional=False),
                               self._text(remap, 'to', context, optional=False)))
            remap.check_complete()
        parameters = []
        for param in entity.get_list('param'):
            parameters += self._parameters(param, context, name, prefix='')
        env = {}
        for variable in entity.get_list('env'):
            env[self._text(variable, 'name', context, optional=False)] = self._text(
                variable, 'value', context, optional=False)
            variable.check_complete()
        entity.check_complete(ignored=_IGNORED_NODE_ATTRIBUTES)
        process = NodeProcess(
            package, executable, name=name, namespace=namespace, arguments=arguments,
            ros_arguments=ros_arguments, remappings=remappings, parameters=parameters,
            env=env, exec_name=exec_name, where=entity.where)
        self.processes.append(process)
        return process

    # ------------------------------------------------------ composable nodes

    def _node_container(self, entity, context):
        """Start a container like a node, then load its composable nodes into it."""
        for key in ('name', 'namespace'):
            if entity.get(key) is None:
                raise LaunchError(
                    f"<node_container> needs the attribute '{key}': the container's full name "
                    '(namespace + name) is where its composable nodes are loaded; write '
                    'namespace="" for the root namespace', *entity.where)
        children = entity.get_list('composable_node')
        process = self._node(entity, context)
        nodes = [self._composable_node(child, context) for child in children
                 if self._condition(child, context)]
        if nodes:
            self.loads.append(LoadComposableNodes(
                process.node_name, nodes, containers=[process], kind=entity.kind,
                where=entity.where))

    def _load_composable_node(self, entity, context):
        """Load composable nodes into a container of this launch, or one running already."""
        target = self._text(entity, 'target', context, optional=False)
        children = entity.get_list('composable_node')
        entity.check_complete()
        if not children:
            raise LaunchError(
                '<load_composable_node> needs at least one <composable_node> (pkg, plugin, '
                'name) to load', *entity.where)
        namespace, _, name = target.strip('/').rpartition('/')
        validate_node_name(name, '/' + namespace, entity.where_of('target'),
                           what=f'target {target!r}: the container')
        nodes = [self._composable_node(child, context) for child in children
                 if self._condition(child, context)]
        if nodes:
            self.loads.append(LoadComposableNodes(target, nodes, where=entity.where))

    def _composable_node(self, entity, context):
        """Evaluate one <composable_node> as launch_ros' get_composable_node_load_request."""
        package = self._text(entity, 'pkg', context, optional=False)
        plugin = self._text(entity, 'plugin', context, optional=False)
        name = self._text(entity, 'name', context, optional=False)
        namespace = absolute_namespace(
            context.configurations.get(_NAMESPACE_KEY), self._text(entity, 'namespace', context))
        validate_node_name(name, namespace, entity.where, what='composable node')
        remappings = []
        for remap in entity.get_list('remap'):
            remappings.append((self._text(remap, 'from', context, optional=False),
                               self._text(remap, 'to', context, optional=False)))
            remap.check_complete()
        parameters = []
        for param in entity.get_list('param'):
            for item in self._parameter_items(param, context, prefix=''):
                if isinstance(item, Path):
                    where = param.where_of('from')
                    parameters += [(n, v, where) for n, v in file_parameters(
                        item, name, namespace, where)]
                else:
                    parameters.append(item)
        extra_arguments = []
        for argument in entity.get_list('extra_arg'):
            arg_name = self._text(argument, 'name', context, optional=False)
            value = argument.get('value', optional=False)
            where = argument.where_of('value')
            if not isinstance(value, str):
                raise LaunchError(
                    f"<extra_arg name='{arg_name}'>: write the value as a string (value: "
                    f"'{yaml_value(value)}'), as "
                    'ros2 launch reads it', *where)
            extra_arguments.append(
                (arg_name, extra_argument_value(substitute(value, context, where), arg_name,
                                                where), where))
            argument.check_complete()
        entity.check_complete()
        return ComposableNode(package, plugin, name, namespace=namespace,
                              remappings=remappings, parameters=parameters,
                              extra_arguments=extra_arguments, where=entity.where)

    def _command_line(self, entity, key, context):
        value = entity.get(key)
        if value is None:
            return []
        where = entity.where_of(key)
        if isinstance(value, list):
            return [substitute(str(v), context, where) for v in value]
        try:
            return shlex.split(substitute(value, context, where))
        except ValueError as e:
            raise LaunchError(f"cannot split '{key}': {e}", *where) from None

    def _parameters(self, param, context, node_name, prefix):
        """Return ``[(name, yaml_text, node_or_None)]`` of one <param>."""
        result = []
        for item in self._parameter_items(param, context, prefix):
            if isinstance(item, Path):
                result += parameters_from_file(item, node_name, param.where_of('from'))
            else:
                result.append((item[0], yaml_value(item[1]), None))  # node-wide -p
        return result

    def _parameter_items(self, param, context, prefix):
        """Return the typed ``(name, value, where)`` of one <param>, or its file's Path."""
        source = param.get('from')
        name = param.get('name')
        where = param.where
        if source is not None:
            if name is not None:
                raise LaunchError("<param> takes either 'name' or 'from', not both", *where)
            param.get('allow_substs')
            param.check_complete()
            path = Path(substitute(source, context, param.where_of('from')))
            if not path.is_absolute() and context.launch_file is not None:
                path = Path(context.launch_file).parent / path
            return [path]
        if name is None:
            raise LaunchError("<param> needs 'name' (with 'value' or nested <param>) or "
                              "'from'", *where)
        full = prefix + substitute(name, context, param.where_of('name'))
        value = param.get('value')
        separator = param.get('value-sep')
        nested = param.get_list('param')
        value_type = param.get('type')
        param.check_complete()
        if value is not None and nested:
            raise LaunchError(f"<param name='{full}'> has both a value and nested "
                              '<param>s', *where)
        if nested:
            result = []
            for child in nested:
                result += self._parameter_items(child, context, full + '.')
            return result
        if value is None:
            raise LaunchError(f"<param name='{full}'> needs a 'value'", *where)
        typed = parameter_value(value, value_type, separator, context,
                                param.where_of('value'), full,
                                typed_text=param.frontend == 'xml')
        return [(full, typed, param.where_of('value'))]


_TYPES = {'str': str, 'int': int, 'float': float, 'bool': bool}


def _load_yaml(text):
    """Load a scalar or list as YAML (launch's convert_as_yaml); keep bad YAML as text."""
    if not text:
        return text
    try:
        return yaml.safe_load(text)
    except yaml.YAMLError:
        return text


def _coerce(text, scalar_type, context, where, typed_text):
    """
    Coerce one string as launch's coerce_to_type does, then substitute.

    XML attributes are text that launch first reads as YAML (``typed_text``);
    YAML values are typed already.  A string that holds a substitution is read
    as YAML once substituted, as launch_ros evaluates parameter values.
    """
    if not typed_text:
        loaded = text
    elif scalar_type in (None, bool):
        loaded = _load_yaml(text)
    elif scalar_type in (int, float):
        try:
            loaded = scalar_type(text)
        except ValueError:
            loaded = text
    else:
        loaded = text
    if not isinstance(loaded, str):
        return loaded
    parts = parse_template(loaded, where)
    result = evaluate(parts, context, where)
    if scalar_type is str or all(isinstance(p, str) for p in parts):
        return result
    return _load_yaml(result) if scalar_type in (None, bool) else _coerce_number(
        result, scalar_type)


def _coerce_number(text, number_type):
    try:
        return number_type(text)
    except ValueError:
        return text


def parameter_value(value, value_type, separator, context, where, name, *, typed_text=True):
    """
    Compute a parameter's value the way launch_ros does for XML and YAML.

    :param value: the attribute (a string in XML; any YAML value in YAML)
    :param value_type: the ``type`` attribute: str, int, float, bool, yaml,
      list_of_str, list_of_int, list_of_float, list_of_bool, or None
    :param separator: the ``value-sep`` attribute (XML lists), or None
    :param typed_text: True for XML attributes (text read as YAML first),
      False for YAML launch files (values typed by YAML already)
    :raises LaunchError: when the value does not have the type
    """
    is_list = False
    scalar_type = None
    if value_type not in (None, 'yaml'):
        base = value_type[len('list_of_'):] if value_type.startswith('list_of_') else value_type
        if base not in _TYPES:
            raise LaunchError(
                f"parameter '{name}': type '{value_type}' is not one of str, int, float, bool, "
                'yaml, '
                'list_of_str, list_of_int, list_of_float, list_of_bool', *where)
        is_list = value_type.startswith('list_of_')
        scalar_type = _TYPES[base]
    if separator is not None and isinstance(value, str):
        value = value.split(separator)
    if isinstance(value, list):
        result = [_coerce(v, scalar_type, context, where, typed_text) if isinstance(v, str)
                  else v for v in value]
    elif isinstance(value, str) and is_list:
        result = _load_yaml(substitute(value, context, where))
    elif isinstance(value, str):
        result = _coerce(value, scalar_type, context, where, typed_text)
    else:
        result = value
    if is_list or isinstance(value, list):
        ok = isinstance(result, list) and (scalar_type is None or all(
            isinstance(v, scalar_type) and not (scalar_type is int and isinstance(v, bool))
            for v in result))
    else:
        ok = scalar_type is None or (isinstance(result, scalar_type) and not (
            scalar_type is int and isinstance(result, bool)))
        if scalar_type is float and isinstance(result, int) and not isinstance(result, bool):
            result, ok = float(result), True
    if not ok:
        raise LaunchError(f"parameter '{name}': {value!r} is not a {value_type}", *where)
    return result


def _flatten(prefix, value, out):
    """Append ``(dotted.name, yaml_text)`` for each leaf of a parameter tree."""
    if isinstance(value, dict):
        for key, item in value.items():
            _flatten(f'{prefix}{key}.', item, out)
    else:
        out.append((prefix[:-1], yaml_value(value)))


def _sections(document, path, found):
    """Find the ``ros__parameters`` mappings of a parameters file, with their node path."""
    for key, value in document.items():
        if not isinstance(value, dict):
            continue
        if 'ros__parameters' in value:
            found.append((path + [str(key)], value['ros__parameters']))
        else:
            _sections(value, path + [str(key)], found)


def parameters_from_file(path, node_name, where):
    """
    Read a ROS 2 parameters file into ``-p`` arguments.

    Sections ``/**`` apply to every node; a section named after a node (or
    ``/ns/node``, ``/**/node``) is passed as ``-p node:name:=value``, which rcl
    applies to that node only.
    """
    try:
        with open(path, 'r', encoding='utf-8') as f:
            document = yaml.safe_load(f)
    except OSError as e:
        raise LaunchError(f'cannot read the parameters file {path}: {e.strerror}',
                          *where) from None
    except UnicodeDecodeError as e:
        raise LaunchError(f'the parameters file {path} is not UTF-8 text: {e.reason} at byte '
                          f'{e.start}', *where) from None
    except yaml.YAMLError as e:
        raise LaunchError(f'the parameters file {path} is not valid YAML: {e}',
                          *where) from None
    sections = []
    if isinstance(document, dict):
        _sections(document, [], sections)
    if not sections:
        raise LaunchError(f'the parameters file {path} has no node section with '
                          "'ros__parameters' (e.g. talker: {ros__parameters: {rate: 5}})",
                          *where)
    result = []
    for node_path, parameters in sections:
        last = node_path[-1].strip('/')
        target = None if last in ('**', '*') else last.split('/')[-1]
        flat = []
        _flatten('', parameters or {}, flat)
        result += [(name, value, target) for name, value in flat]
    return result


def load_launch_file(path, arguments=None, *, install_space=None, environ=None):
    """
    Load an XML or YAML launch file into a LaunchPlan.

    :param path: the launch file
    :param arguments: ``{name: value}`` from ``name:=value`` on the command line
    :param install_space: an InstallSpace, for ``$(find-pkg-share ...)``
    :raises LaunchError: naming the file and line of the problem
    """
    return Loader(install_space, environ).load(Path(path), dict(arguments or {}))


def declared_arguments(path, *, install_space=None, environ=None):
    """
    Return the arguments an XML or YAML launch file declares (its includes' too).

    Each is ``{name, default, description, choices, conditional}``; ``default``
    is None for a required one.

    :raises LaunchError: naming the file and line of the problem
    """
    loader = Loader(install_space, environ, listing=True)
    loader.load(Path(path), {})
    return loader.declared
