# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
GUI programs that launch files start and that have no WebAssembly build.

``rviz2``, the ``rqt`` tools and ``joint_state_publisher_gui`` are Qt
programs (the recipe skips their packages, ``recipes/humble.yaml``). A
launch file that starts one is not refused for it: its ``Node`` starts
``gui_shim.py``, which says once what was left out and why, then waits
until the launch stops it, as the window would. Headless, ``rviz2 -d
FILE.rviz`` is such a note.
"""

#: package: (its executables, why it cannot run)
GUI_PROGRAMS = {
    'rviz2': (('rviz2',), 'RViz is a Qt and OpenGL program'),
    'rqt_gui': (('rqt_gui',), 'rqt is a Qt program'),
    'rqt_graph': (('rqt_graph',), 'rqt is a Qt program'),
    'rqt_plot': (('rqt_plot',), 'rqt is a Qt program'),
    'rqt_console': (('rqt_console',), 'rqt is a Qt program'),
    'rqt_image_view': (('rqt_image_view',), 'rqt is a Qt program'),
    'rqt_reconfigure': (('rqt_reconfigure',), 'rqt is a Qt program'),
    'rqt_robot_steering': (('rqt_robot_steering',), 'rqt is a Qt program'),
    'rqt_controller_manager': (('rqt_controller_manager',), 'rqt is a Qt program'),
    'rqt_joint_trajectory_controller': (('rqt_joint_trajectory_controller',),
                                        'rqt is a Qt program'),
    'joint_state_publisher_gui': (('joint_state_publisher_gui',),
                                  'joint_state_publisher_gui is a Qt program'),
    'turtlesim': (('turtlesim_node',), 'turtlesim draws with Qt'),
}


def gui_programs(installed):
    """
    Return the GUI programs to stand in for, those the install space lacks.

    :param installed: names of the install space's packages (a package that
      was built after all is run as it is)
    :returns: ``{package: (executables, reason)}``
    """
    return {name: entry for name, entry in GUI_PROGRAMS.items() if name not in installed}
