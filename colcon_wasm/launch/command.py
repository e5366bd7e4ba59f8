# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""What ``colcon-wasm run`` and ``colcon-wasm launch`` do, behind their CLI modules."""

from pathlib import Path
import sys

from colcon_wasm.launch import LaunchError
from colcon_wasm.launch import load_launch_file
from colcon_wasm.launch import plan_items
from colcon_wasm.launch import split_launch_arguments
from colcon_wasm.launch.foxglove import schema_file
from colcon_wasm.launch.install_space import InstallSpace
from colcon_wasm.launch.install_space import InstallSpaceError
from colcon_wasm.launch.python_launch import HostLaunch
from colcon_wasm.launch.python_launch import runs_on_host_launch
from colcon_wasm.launch.runner import DEFAULT_LOAD_TIMEOUT
from colcon_wasm.launch.runner import find_launch_file
from colcon_wasm.launch.runner import host_plan
from colcon_wasm.launch.runner import LAUNCH_FILE_SUFFIXES
from colcon_wasm.launch.runner import run_host
from colcon_wasm.launch.zenoh import resolve_gateway_module


def make_plan(values, install_base, *, show_args=False):
    """
    Make a plan from the positional arguments of ``launch``.

    ``FILE [name:=value ...]``, ``PKG FILE [name:=value ...]`` (a launch file
    in the package's share folder) or ``PKG/EXE [PKG/EXE ...]``. A launch
    file that Humble's launch runs (``python_launch.runs_on_host_launch``)
    gives a ``HostLaunch`` (with ``show_args``, it prints the file's
    arguments instead of running it).

    :raises LaunchError: for arguments that are none of these
    """
    others, arguments = split_launch_arguments(values)
    if not others:
        raise LaunchError('name a launch file or PKG/EXE items, e.g. '
                          'colcon-wasm launch demo_nodes/talker demo_nodes/listener')
    install_space = InstallSpace(install_base) if Path(install_base).is_dir() else None
    first = Path(others[0])
    if len(others) == 1 and (first.is_file() or first.name.endswith(LAUNCH_FILE_SUFFIXES)) \
            and not _names_an_executable(install_space, others[0]):
        if not first.is_file():
            raise LaunchError(f"launch file '{first}' does not exist")
        if runs_on_host_launch(first, install_space):
            return HostLaunch(first, arguments, show_args=show_args)
        return load_launch_file(first, arguments, install_space=install_space)
    if len(others) == 2 and '/' not in others[0] and \
            others[1].endswith(LAUNCH_FILE_SUFFIXES):
        if install_space is None:
            raise LaunchError(f"no install space at '{install_base}': run 'colcon build --wasm' "
                              'first, or '
                              'pass --install-base DIR')
        path = find_launch_file(install_space, others[0], others[1])
        if runs_on_host_launch(path, install_space):
            return HostLaunch(path, arguments, show_args=show_args)
        return load_launch_file(path, arguments, install_space=install_space)
    if arguments:
        given = ', '.join(f'{k}:={v}' for k, v in arguments.items())
        raise LaunchError(f'launch arguments ({given}) need a launch file')
    return plan_items(others)


def _names_an_executable(install_space, value):
    """Check if ``PKG/EXE`` names an executable (e.g. a Python script ``pkg/talker.py``)."""
    package, _, executable = value.partition('/')
    if install_space is None or not executable or '/' in executable or Path(value).is_file():
        return False
    try:
        install_space.executable(package, executable)
    except InstallSpaceError:  # not one: then it is a launch file's path
        return False
    return True


def _add_python_nodes(description, python, install_space, bases):
    from colcon_wasm.launch.install_view import ament_prefixes
    from colcon_wasm.launch.install_view import view_bases
    from colcon_wasm.launch.python_nodes import python_processes
    bases = view_bases(install_space) if bases is None else [Path(b) for b in bases]
    processes = description['processes']
    processes += python_processes(python, ament_prefixes(bases), first_index=len(processes) + 1)


def _add_pyodide_if_installed(description, pyodide):
    """Give the host Pyodide's folder when there is one: the launch may start Python nodes."""
    from colcon_wasm.launch.python_nodes import find_pyodide
    try:
        description['pyodide'] = str(find_pyodide(pyodide))
    except LaunchError:
        pass  # a Python node the launch starts then fails, saying how to get Pyodide


def _run_python_launch(launch, description, install_space, bundled, *, command, duration,
                       print_plan, bags, out, err):
    """Run a Python launch file beside the Node host (or print it), as ``execute`` runs a plan."""
    if print_plan or launch.show_args:
        return launch.describe(command=command, out=out)
    from colcon_wasm.record.session import bag_session
    from colcon_wasm.server import find_runtime
    from colcon_wasm.server import runtime_entry
    from colcon_wasm.server import ServeError
    try:
        runtime_dir, _ = find_runtime(install_space, bundled)
        runtime = runtime_dir / runtime_entry(runtime_dir)
        fds = [description['control']['ready_fd']]
        with schema_file(description, install_space), \
                bag_session(bags, install_space, err) as session:

            def alongside(host, register):
                return launch.run(host, register, command=command, duration=duration)
            if session is None:
                return run_host(description, runtime, bundled, pass_fds=fds, alongside=alongside)
            description.update(session.host_plan)
            status = run_host(description, runtime, bundled, pass_fds=[*session.fds, *fds],
                              started=session.host_started, alongside=alongside)
            return session.finish(status)
    except (LaunchError, ServeError) as e:
        print(f'{command}: {e}', file=err)
        return 1


def execute(plan, *, install_base, duration=None, echo=(), print_plan=False, command,
            out=None, err=None, stdin=False, load_timeout=DEFAULT_LOAD_TIMEOUT,
            bases=None, bridges=None, python=(), pyodide=None, bags=None):
    """
    Resolve a plan against the install space and run it in Node.js (or print it).

    With ``stdin`` the one process of the plan reads this process' standard input.
    ``load_timeout`` (seconds) bounds each wait of a composable node load.
    ``bases``: the install bases the processes see (default: the install space's
    base and underlays), highest priority first; see ``install_view``.
    ``bridges``: the rosbridge server and client entries of the plan
    (``colcon_wasm.launch.rosbridge.bridge_plan``) and the Foxglove server's
    (``colcon_wasm.launch.foxglove.foxglove_plan``).
    ``python``: Python scripts run as nodes next to the plan's processes, with
    the Pyodide folder ``pyodide`` (default: ``find_pyodide``'s lookup).
    ``bags``: what to record and play (``colcon_wasm.record.session.bag_plan``).

    :returns: the exit status (1 for bad input, else the Node host's)
    """
    out = out or sys.stdout
    err = err or sys.stderr
    from colcon_wasm import resources
    bundled = resources.path('packages') / 'wasm_js' / 'src'
    python_launch = plan if isinstance(plan, HostLaunch) else None
    launch_duration = duration
    if python_launch:
        plan = python_launch.plan
        duration = None  # the launch gets SIGINT at the end of the duration, as Ctrl-C
    try:
        install_space = InstallSpace(install_base)
        description = host_plan(plan, install_space, duration=duration, echo=echo,
                                stdin=stdin, load_timeout=load_timeout, bases=bases)
        description.update(bridges or {}, command=command)
        resolve_gateway_module(description, install_space)
        if python:
            _add_python_nodes(description, python, install_space, bases)
            # run's one process reads standard input, a Python node too (input(), a console)
            description['stdin'] = bool(stdin) and len(description['processes']) == 1
        if not print_plan and any(p.get('python') for p in description['processes']):
            # scripts of --python, and entry points of Python packages
            from colcon_wasm.launch.python_nodes import find_pyodide
            description['pyodide'] = str(find_pyodide(pyodide))
        if python_launch:
            python_launch.prepare(description, install_space, bases,
                                  runtime_python=bundled / 'python')
            _add_pyodide_if_installed(description, pyodide)
    except (LaunchError, InstallSpaceError) as e:
        print(f'{command}: {e}', file=err)
        return 1
    if python_launch:
        try:
            return _run_python_launch(python_launch, description, install_space, bundled,
                                      command=command, duration=launch_duration,
                                      print_plan=print_plan, bags=bags, out=out, err=err)
        finally:
            python_launch.cleanup()
    if print_plan:
        for process in description['processes']:
            args = ' '.join(process['args'])
            print(f"[{process['label']}] {process['js']} {args}".rstrip(), file=out)
        for load in plan.loads:
            for node in load.nodes:
                print(f'[load_node {load.container_name}] {node.describe()}',
                      file=out)
        return 0
    from colcon_wasm.server import find_runtime
    from colcon_wasm.server import runtime_entry
    from colcon_wasm.server import ServeError
    try:
        runtime_dir, _ = find_runtime(install_space, bundled)
        from colcon_wasm.record.session import bag_session
        with schema_file(description, install_space), \
                bag_session(bags, install_space, err) as session:
            if session is None:
                return run_host(description, runtime_dir / runtime_entry(runtime_dir), bundled)
            description.update(session.host_plan)
            status = run_host(description, runtime_dir / runtime_entry(runtime_dir), bundled,
                              pass_fds=session.fds, started=session.host_started)
            return session.finish(status)
    except (LaunchError, ServeError) as e:
        print(f'{command}: {e}', file=err)
        return 1
