# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Python nodes: spin threads, spin_once, and the arguments of ``--python`` scripts.

Against the C++ demo nodes (tests/demo_build.py), with the npm package
``pyodide`` of tests/js. Every script ends by itself; ``--duration`` and
the subprocess timeout only bound a run that would not.
"""

import re

from launch_until import finished
from test_pyodide_nodes import colcon_wasm
from test_pyodide_nodes import DATA
from test_pyodide_nodes import install  # noqa: F401 (the fixture)


def lines_of(out, label):
    """Return the lines of one process (``[label] ...``), without the prefix."""
    prefix = f'[{label}] '
    return [line[len(prefix):] for line in out.splitlines() if line.startswith(prefix)]


def test_a_spin_thread_runs_while_the_main_thread_sleeps_and_waits(install):  # noqa: F811
    code, out = colcon_wasm(
        'launch', '--install-base', install, '--duration', 60,
        '--python', DATA / 'thread_talker.py', 'demo_nodes/talker', 'demo_nodes/listener',
        until=lambda out: finished('thread_talker-3')(out) and re.search(
            r'\[listener-2\] .*I heard: \[Hello from the main thread: \d+\]', out))
    mine = lines_of(out, 'thread_talker-3')
    assert any('spin thread started: alive=True' in line for line in mine), out[-6000:]
    # the C++ talker heard by the spin thread's callback while the main loop sleeps ...
    heard = [i for i, line in enumerate(mine) if re.search(
        r'\[py_thread_talker\]: heard while the main thread sleeps: \[Hello World: \d+\]', line)]
    done = [i for i, line in enumerate(mine) if 'main loop done: published' in line]
    assert len(heard) >= 3 and done and heard[2] < done[0], out[-6000:]
    # ... and the main thread's messages heard by the C++ listener
    assert re.search(r'\[listener-2\] .*I heard: \[Hello from the main thread: \d+\]', out), \
        out[-6000:]
    # Event.wait set by a callback; after shutdown the spin ends and join returns
    assert any('Event.wait returned True' in line for line in mine), out[-6000:]
    assert any('after shutdown and join: alive=False' in line for line in mine), out[-6000:]
    assert '[INFO] [thread_talker-3]: process has finished cleanly' in out, out[-6000:]
    assert code == 0, out[-3000:]


def test_spin_threads_of_executors_serve_the_main_threads_calls(install):  # noqa: F811
    code, out = colcon_wasm(
        'launch', '--install-base', install, '--duration', 60,
        '--python', DATA / 'thread_executor.py', 'demo_nodes/add_two_ints_server',
        until=finished('thread_executor-2'))
    mine = lines_of(out, 'thread_executor-2')
    text = '\n'.join(mine)
    # a future the spin thread completes while the main thread sleeps; a synchronous call
    assert '[py_thread_client]: call_async while sleeping: 2 + 3 = 5' in text, out[-6000:]
    assert '[py_thread_client]: call: 40 + 2 = 42' in text, out[-6000:]
    # a second spin thread (spin_until_future_complete), joined: it ends with its future
    assert ('[py_thread_client]: spin_until_future_complete thread: 100 + 23 = 123, '
            'alive=False') in text, out[-6000:]
    assert re.search(r'\[add_two_ints_server-1\] .*Incoming request: a: 100 b: 23', out), \
        out[-6000:]
    # the thread is no daemon: it spins on after main returned, until the timer shuts down
    returned = next(i for i, line in enumerate(mine) if 'main returns' in line)
    ticks = [i for i, line in enumerate(mine) if re.search(r'timer tick \d$', line)]
    assert len(ticks) == 3 and ticks[0] > returned, out[-6000:]
    assert '[INFO] [thread_executor-2]: process has finished cleanly' in out, out[-6000:]
    assert code == 0, out[-3000:]


def test_a_thread_that_does_not_spin_and_a_spin_threads_exception(install):  # noqa: F811
    code, out = colcon_wasm(
        'launch', '--install-base', install, '--duration', 60,
        '--python', DATA / 'thread_errors.py', 'demo_nodes/talker',
        until=finished('thread_errors-2'))
    text = '\n'.join(lines_of(out, 'thread_errors-2'))
    assert ("a thread of print: can't start new thread 'Thread-1 (print)' with the target "
            "<built-in function print>: Pyodide starts no threads; colcon-wasm's rclpy runs a "
            'thread whose target spins: rclpy.spin, rclpy.spin_until_future_complete, or an '
            "executor's spin or spin_until_future_complete") in text, out[-6000:]
    assert ('Event.wait() with no spin thread: threading.Condition.wait() (Event.wait(), '
            'Queue.get(), ...) without a timeout would wait forever') in text, out[-6000:]
    # printed as Python prints a thread's exception; the thread ends, the program goes on
    start = text.index('Exception in thread spinner:')
    assert f'File "{DATA / "thread_errors.py"}", line 24, in explode' in text[start:], \
        out[-6000:]
    assert re.search(r'ValueError: the callback gives up on \[Hello World: \d+\]', text[start:]), \
        out[-6000:]
    assert 'the main thread goes on: spin thread alive=False' in text[start:], out[-6000:]
    assert '[INFO] [thread_errors-2]: process has finished cleanly' in out, out[-6000:]


def test_spin_once_runs_one_callback_per_call_in_the_order_of_rclpy(install):  # noqa: F811
    code, out = colcon_wasm(
        'launch', '--install-base', install, '--duration', 60,
        '--python', DATA / 'spin_once_order.py', DATA / 'fast_talker.launch.xml',
        until=finished('spin_once_order-2'))
    text = '\n'.join(lines_of(out, 'spin_once_order-2'))
    # one wait found all four ready: timers, then subscriptions, then guard conditions
    assert "after 1 spin_once: ['timer']" in text, out[-6000:]
    assert "after 2 spin_once: ['timer', 'A']" in text, out[-6000:]
    assert "after 3 spin_once: ['timer', 'A', 'B']" in text, out[-6000:]
    assert "after 4 spin_once: ['timer', 'A', 'B', 'guard']" in text, out[-6000:]
    # one message of each subscription per wait: the next messages at the next wait
    assert "the next wait: ['A', 'B']" in text, out[-6000:]
    assert '[INFO] [spin_once_order-2]: process has finished cleanly' in out, out[-6000:]


def test_arguments_of_python_scripts_act_as_for_entry_points(install):  # noqa: F811
    script = DATA / 'args_talker.py'
    # one quoted value: the script, then its arguments (launch and run)
    code, out = colcon_wasm(
        'launch', '--install-base', install, '--duration', 60, '--python',
        f'{script} --count 3 --ros-args -p greeting:=Greetings -r talk:=chatter '
        '-r __node:=renamed',
        'demo_nodes/listener',
        until=lambda out: finished('args_talker-2')(out) and all(
            re.search(rf'\[listener-1\] .*I heard: \[Greetings {i}\]', out) for i in (1, 2, 3)))
    assert '[renamed]: /renamed on /chatter: count=3 greeting=Greetings' in out, out[-6000:]
    for i in (1, 2, 3):
        assert re.search(rf'\[listener-1\] .*I heard: \[Greetings {i}\]', out), out[-6000:]
    assert '[INFO] [args_talker-2]: process has finished cleanly' in out, out[-6000:]
    # run: the words after -- go to the script; so do --ros-args and what follows
    code, out = colcon_wasm('run', '--install-base', install, '--duration', 60,
                            '--python', script, '--', '--count', '2', '--ros-args',
                            '-p', 'greeting:=Hi')
    assert '[py_args_talker]: /py_args_talker on /talk: count=2 greeting=Hi' in out, \
        out[-4000:]
    assert code == 0, out[-4000:]
    code, out = colcon_wasm('run', '--install-base', install, '--duration', 60,
                            '--python', script, '--ros-args', '-p', 'greeting:=Bye',
                            '-r', 'talk:=news')
    assert '[py_args_talker]: /py_args_talker on /news: count=1 greeting=Bye' in out, \
        out[-4000:]
    assert code == 0, out[-4000:]


def test_python_script_arguments_in_the_plan_and_bad_ones(install):  # noqa: F811
    script = DATA / 'args_talker.py'
    code, out = colcon_wasm('run', '--install-base', install, '--print-plan',
                            '--python', f"{script} --count 2 --ros-args -p 'greeting:=Hi you'")
    assert code == 0, out
    assert f'[args_talker-1] {script} --count 2 --ros-args -p greeting:=Hi you' in out
    # with PKG EXE, the arguments after EXE are the executable's, as before
    code, out = colcon_wasm('run', '--install-base', install, '--print-plan',
                            '--python', script, 'demo_nodes', 'talker', '--ros-args',
                            '-p', 'rate:=3')
    assert code == 0, out
    assert out.splitlines()[-1] == f'[args_talker-2] {script}', out
    assert 'talker.js --ros-args -p rate:=3' in out, out
    code, out = colcon_wasm('run', '--install-base', install, '--print-plan',
                            '--python', f'{script} "unclosed')
    assert code == 1 and 'No closing quotation (the value is the script, then its arguments' \
        in out, out
    code, out = colcon_wasm('run', '--install-base', install, '--print-plan', '--python',
                            script, '--python', script, '--', '--ros-args')
    assert code == 1 and ('the arguments --ros-args go to a Python script, and there are 2 '
                          '(--python): give each script its arguments in its own value') in out
    code, out = colcon_wasm('launch', '--install-base', install, '--print-plan', '--python',
                            'nope.py --count 2')
    assert code == 1 and ("Python node 'nope.py' does not exist (from --python 'nope.py "
                          "--count 2': the script, then its arguments)") in out, out
