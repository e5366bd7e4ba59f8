// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * The files of the pure-Python `rclpy` next to this module, for workers that
 * cannot list a folder (a browser fetches each one). tests/test_pyodide_page.py
 * checks the list against the folder.
 *
 * @module python/rclpy_files
 */

export const RCLPY_FILES = Object.freeze([
  'rclpy/__init__.py',
  'rclpy/_bus.py',
  'rclpy/_event_loop.py',
  'rclpy/_graph.py',
  'rclpy/_host_link.py',
  'rclpy/_messages.py',
  'rclpy/_names.py',
  'rclpy/_native_only.py',
  'rclpy/_threads.py',
  'rclpy/_waiting.py',
  'rclpy/action/__init__.py',
  'rclpy/action/client.py',
  'rclpy/action/server.py',
  'rclpy/callback_groups.py',
  'rclpy/clock.py',
  'rclpy/context.py',
  'rclpy/duration.py',
  'rclpy/exceptions.py',
  'rclpy/executors.py',
  'rclpy/logging.py',
  'rclpy/node.py',
  'rclpy/parameter.py',
  'rclpy/parameter_service.py',
  'rclpy/qos.py',
  'rclpy/qos_event.py',
  'rclpy/task.py',
  'rclpy/time.py',
  'rclpy/time_source.py',
  'rclpy/topic_endpoint_info.py',
  'rclpy/utilities.py',
  'rclpy/validate_full_topic_name.py',
  'rclpy/validate_namespace.py',
  'rclpy/validate_node_name.py',
]);

/**
 * The rclpy modules imported into the host's Pyodide snapshot
 * (pyodide_snapshot.mjs): every module whose import needs neither the bus
 * nor a message type (rclpy.action needs action_msgs' types: it is
 * imported by the nodes that use it).
 */
export const SNAPSHOT_RCLPY_MODULES = Object.freeze([
  'rclpy', 'rclpy.node', 'rclpy.executors', 'rclpy.duration', 'rclpy.time',
]);
