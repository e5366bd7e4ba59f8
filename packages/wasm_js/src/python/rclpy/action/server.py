# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
rclpy.action.server: ActionServer and ServerGoalHandle, on the bus.

An action is what rcl_action makes of it, so rclcpp and rclpy clients use
it unchanged: the services ``<action>/_action/send_goal``, ``cancel_goal``
and ``get_result`` and the topics ``<action>/_action/feedback`` and
``status`` (TRANSIENT_LOCAL), with the goal state machine of rcl_action.
Goals run as tasks of the executor (rclpy.task.Task): an execute callback
may be a coroutine, and one that sleeps in a MultiThreadedExecutor still
hears cancel requests (rclpy.executors).
"""

import enum
import time
import traceback

from rclpy import _messages
from rclpy.executors import create_task
from rclpy.qos import DurabilityPolicy
from rclpy.qos import qos_profile_services_default
from rclpy.qos import QoSProfile
from rclpy.task import Future

"""rcl_action's status topic QoS: the last status array, kept for late joiners."""
qos_profile_action_status_default = QoSProfile(depth=1,
                                               durability=DurabilityPolicy.TRANSIENT_LOCAL)


class GoalResponse(enum.Enum):
    """What a goal callback answers."""

    REJECT = 1
    ACCEPT = 2


class CancelResponse(enum.Enum):
    """What a cancel callback answers."""

    REJECT = 1
    ACCEPT = 2


class GoalEvent(enum.Enum):
    """The events of rcl_action's goal state machine."""

    EXECUTE = 1
    CANCEL_GOAL = 2
    SUCCEED = 3
    ABORT = 4
    CANCELED = 5


class GoalStatus(enum.IntEnum):
    """action_msgs/msg/GoalStatus' constants."""

    STATUS_UNKNOWN = 0
    STATUS_ACCEPTED = 1
    STATUS_EXECUTING = 2
    STATUS_CANCELING = 3
    STATUS_SUCCEEDED = 4
    STATUS_CANCELED = 5
    STATUS_ABORTED = 6


"""rcl_action's transitions: (state, event) -> state."""
_TRANSITIONS = {
    (GoalStatus.STATUS_ACCEPTED, GoalEvent.EXECUTE): GoalStatus.STATUS_EXECUTING,
    (GoalStatus.STATUS_ACCEPTED, GoalEvent.CANCEL_GOAL): GoalStatus.STATUS_CANCELING,
    (GoalStatus.STATUS_EXECUTING, GoalEvent.CANCEL_GOAL): GoalStatus.STATUS_CANCELING,
    (GoalStatus.STATUS_EXECUTING, GoalEvent.SUCCEED): GoalStatus.STATUS_SUCCEEDED,
    (GoalStatus.STATUS_EXECUTING, GoalEvent.ABORT): GoalStatus.STATUS_ABORTED,
    (GoalStatus.STATUS_CANCELING, GoalEvent.SUCCEED): GoalStatus.STATUS_SUCCEEDED,
    (GoalStatus.STATUS_CANCELING, GoalEvent.ABORT): GoalStatus.STATUS_ABORTED,
    (GoalStatus.STATUS_CANCELING, GoalEvent.CANCELED): GoalStatus.STATUS_CANCELED,
}
_ACTIVE = (GoalStatus.STATUS_ACCEPTED, GoalStatus.STATUS_EXECUTING,
           GoalStatus.STATUS_CANCELING)

"""action_msgs/srv/CancelGoal's return codes."""
ERROR_NONE, ERROR_REJECTED, ERROR_UNKNOWN_GOAL_ID, ERROR_GOAL_TERMINATED = 0, 1, 2, 3


class InvalidGoalTransition(RuntimeError):
    """A goal handle was asked for a transition rcl_action does not allow."""


def default_handle_accepted_callback(goal_handle):
    """Execute an accepted goal now."""
    goal_handle.execute()


def default_goal_callback(goal_request):
    """Accept every goal."""
    return GoalResponse.ACCEPT


def default_cancel_callback(cancel_request):
    """Reject every cancel request."""
    return CancelResponse.REJECT


async def _await_or_execute(callback, *args):
    """Call ``callback``; await what it returns when that is a coroutine."""
    result = callback(*args)
    if hasattr(result, '__await__'):
        result = await result
    return result


class ServerGoalHandle:
    """A goal an action server accepted: its request, its state, its feedback."""

    def __init__(self, action_server, goal_info, goal_request):
        """Made by the action server when its goal callback accepts a goal."""
        self._action_server = action_server
        self._goal_info = goal_info
        self._goal_request = goal_request
        self._status = GoalStatus.STATUS_ACCEPTED

    def __eq__(self, other):
        """Equal when the goal ids are."""
        return isinstance(other, ServerGoalHandle) and \
            bytes(self.goal_id.uuid) == bytes(other.goal_id.uuid)

    def __hash__(self):
        """Hash the goal id."""
        return hash(bytes(self.goal_id.uuid))

    @property
    def request(self):
        """Return the goal (the action's Goal message)."""
        return self._goal_request

    @property
    def goal_id(self):
        """Return the goal id (unique_identifier_msgs/UUID)."""
        return self._goal_info.goal_id

    @property
    def is_active(self):
        """Return True while accepted, executing or canceling."""
        return self._status in _ACTIVE

    @property
    def is_cancel_requested(self):
        """Return True once a cancel request was accepted."""
        return self._status == GoalStatus.STATUS_CANCELING

    @property
    def status(self):
        """Return the status: one of action_msgs/GoalStatus' STATUS_ constants."""
        return int(self._status)

    def _update_state(self, event):
        state = _TRANSITIONS.get((self._status, event))
        if state is None:
            raise InvalidGoalTransition(
                f'goal_handle attempted invalid transition from state '
                f'{GoalStatus(self._status).name[7:]} with event {event.name}')
        self._status = state
        self._action_server._publish_status()
        if not self.is_active:
            self._action_server._finished(self)

    def execute(self, execute_callback=None):
        """Start executing the goal (a task of the executor; the server's callback by default)."""
        self._update_state(GoalEvent.EXECUTE)
        self._action_server._execute(self, execute_callback)

    def publish_feedback(self, feedback):
        """Publish feedback (the action's Feedback message) for this goal."""
        self._action_server._publish_feedback(self, feedback)

    def succeed(self):
        """Mark the goal succeeded."""
        self._update_state(GoalEvent.SUCCEED)

    def abort(self):
        """Mark the goal aborted."""
        self._update_state(GoalEvent.ABORT)

    def canceled(self):
        """Mark the goal canceled, once a cancel request was accepted."""
        self._update_state(GoalEvent.CANCELED)

    def destroy(self):
        """Free nothing: the server forgets the goal when its result expires."""


class ActionServer:
    """Serves an action on a node: goals, cancel requests, results, feedback, status."""

    def __init__(self, node, action_type, action_name, execute_callback, *,
                 callback_group=None, goal_callback=default_goal_callback,
                 handle_accepted_callback=default_handle_accepted_callback,
                 cancel_callback=default_cancel_callback,
                 goal_service_qos_profile=qos_profile_services_default,
                 result_service_qos_profile=qos_profile_services_default,
                 cancel_service_qos_profile=qos_profile_services_default,
                 feedback_pub_qos_profile=QoSProfile(depth=10),
                 status_pub_qos_profile=qos_profile_action_status_default,
                 result_timeout=900):
        """Create the action's services and topics on ``node``."""
        self._node = node
        self._action_type = action_type
        self._action_name = action_name
        self._logger = node.get_logger()
        self._result_timeout = result_timeout
        self.register_execute_callback(execute_callback)
        self.register_goal_callback(goal_callback)
        self.register_handle_accepted_callback(handle_accepted_callback)
        self.register_cancel_callback(cancel_callback)
        self._goal_handles = {}
        self._result_futures = {}
        self._finished_at = {}
        impl = action_type.Impl
        self._goal_info_type = _messages.message_class('action_msgs/msg/GoalInfo')
        self._goal_status_type = _messages.message_class('action_msgs/msg/GoalStatus')
        base = f'{action_name}/_action'
        self.callback_group = callback_group or node.default_callback_group
        self._services = [
            node.create_service(impl.SendGoalService, f'{base}/send_goal', self._on_send_goal,
                                qos_profile=goal_service_qos_profile,
                                callback_group=self.callback_group),
            node.create_service(impl.CancelGoalService, f'{base}/cancel_goal',
                                self._on_cancel_goal, qos_profile=cancel_service_qos_profile,
                                callback_group=self.callback_group),
            node.create_service(impl.GetResultService, f'{base}/get_result',
                                self._on_get_result, qos_profile=result_service_qos_profile,
                                callback_group=self.callback_group),
        ]
        self._feedback_publisher = node.create_publisher(
            impl.FeedbackMessage, f'{base}/feedback', feedback_pub_qos_profile)
        self._status_publisher = node.create_publisher(
            impl.GoalStatusMessage, f'{base}/status', status_pub_qos_profile)
        node._action_servers.append(self)

    def register_execute_callback(self, execute_callback):
        """Set the callback that executes goals (``execute_callback(goal_handle)``)."""
        if not callable(execute_callback):
            raise TypeError('Failed to register goal execution callback: not callable')
        self._execute_callback = execute_callback

    def register_goal_callback(self, goal_callback):
        """Set the callback that accepts or rejects goals (None: accept all)."""
        self._goal_callback = goal_callback or default_goal_callback

    def register_handle_accepted_callback(self, handle_accepted_callback):
        """Set the callback given accepted goals (None: execute them now)."""
        self._handle_accepted_callback = \
            handle_accepted_callback or default_handle_accepted_callback

    def register_cancel_callback(self, cancel_callback):
        """Set the callback that accepts or rejects cancel requests (None: reject all)."""
        self._cancel_callback = cancel_callback or default_cancel_callback

    async def _on_send_goal(self, request, response):
        self._expire_results()
        uuid = bytes(request.goal_id.uuid)
        goal_info = self._goal_info_type(goal_id=request.goal_id,
                                         stamp=self._node.get_clock().now().to_msg())
        accepted = False
        if uuid not in self._goal_handles:
            answer = await _await_or_execute(self._goal_callback, request.goal)
            if not isinstance(answer, GoalResponse):
                self._logger.warning('Goal request callback did not return a GoalResponse '
                                     'type. Rejecting goal.')
            else:
                accepted = answer == GoalResponse.ACCEPT
        response.accepted = accepted
        response.stamp = goal_info.stamp
        if accepted:
            goal_handle = ServerGoalHandle(self, goal_info, request.goal)
            self._goal_handles[uuid] = goal_handle
            self._result_futures[uuid] = Future()
            self._publish_status()
            # after the response went out, as rclpy: the accepted callback runs next
            self._task(self._accepted, goal_handle)
        return response

    def _task(self, callback, *args):
        """Create a task of the executor in this server's callback group."""
        task = create_task(callback, *args)
        task._group = (self.callback_group, self)
        return task

    async def _accepted(self, goal_handle):
        await _await_or_execute(self._handle_accepted_callback, goal_handle)

    def _execute(self, goal_handle, execute_callback):
        self._task(self._execute_goal, execute_callback or self._execute_callback, goal_handle)

    async def _execute_goal(self, execute_callback, goal_handle):
        uuid = bytes(goal_handle.goal_id.uuid)
        try:
            result = await _await_or_execute(execute_callback, goal_handle)
        except Exception as e:
            result = self._action_type.Result()
            self._logger.error(f'Error raised in execute callback: {e}')
            traceback.print_exc()
        if goal_handle.is_active:
            self._logger.warning(f'Goal state not set, assuming aborted. Goal ID: {list(uuid)}')
            goal_handle.abort()
        response = self._action_type.Impl.GetResultService.Response()
        response.status = goal_handle.status
        response.result = result if result is not None else self._action_type.Result()
        future = self._result_futures.get(uuid)
        if future is not None and not future.done():
            future.set_result(response)

    async def _on_cancel_goal(self, request, response):
        self._expire_results()
        wanted = bytes(request.goal_info.goal_id.uuid)
        stamp = request.goal_info.stamp
        stamp_ns = stamp.sec * 10 ** 9 + stamp.nanosec
        everything = not any(wanted)
        code = ERROR_NONE
        candidates = []
        if not everything:
            handle = self._goal_handles.get(wanted)
            if handle is None:
                code = ERROR_UNKNOWN_GOAL_ID
            elif not handle.is_active:
                code = ERROR_GOAL_TERMINATED
            else:
                candidates.append(handle)
        if everything or stamp_ns:
            for handle in self._goal_handles.values():
                accepted = handle._goal_info.stamp
                accepted_ns = accepted.sec * 10 ** 9 + accepted.nanosec
                if handle not in candidates and handle.is_active and \
                        (everything and not stamp_ns or stamp_ns and accepted_ns <= stamp_ns):
                    candidates.append(handle)
        canceling = []
        for handle in candidates:
            if handle.is_cancel_requested:
                canceling.append(handle._goal_info)
                continue
            if await _await_or_execute(self._cancel_callback, handle) == CancelResponse.ACCEPT:
                handle._update_state(GoalEvent.CANCEL_GOAL)
                canceling.append(handle._goal_info)
        if code == ERROR_NONE and not canceling:
            code = ERROR_REJECTED
        response.return_code = code
        response.goals_canceling = canceling
        return response

    async def _on_get_result(self, request, response):
        self._expire_results()
        future = self._result_futures.get(bytes(request.goal_id.uuid))
        if future is None:
            response.status = GoalStatus.STATUS_UNKNOWN
            return response
        return await future

    def _publish_feedback(self, goal_handle, feedback):
        if not isinstance(feedback, self._action_type.Feedback):
            raise TypeError(f'Expected {self._action_type.Feedback}, got {type(feedback)}')
        message = self._action_type.Impl.FeedbackMessage()
        message.goal_id = goal_handle.goal_id
        message.feedback = feedback
        self._feedback_publisher.publish(message)

    def _publish_status(self):
        message = self._action_type.Impl.GoalStatusMessage()
        message.status_list = [self._goal_status_type(goal_info=h._goal_info, status=h.status)
                               for h in self._goal_handles.values()]
        if self._status_publisher._handle is not None:
            self._status_publisher.publish(message)

    def _finished(self, goal_handle):
        self._finished_at[bytes(goal_handle.goal_id.uuid)] = time.monotonic()

    def _expire_results(self):
        """Forget the goals that finished more than result_timeout ago, as rcl_action."""
        limit = time.monotonic() - self._result_timeout
        expired = [uuid for uuid, at in self._finished_at.items() if at < limit]
        for uuid in expired:
            del self._finished_at[uuid]
            self._goal_handles.pop(uuid, None)
            self._result_futures.pop(uuid, None)
        if expired:
            self._publish_status()

    def destroy(self):
        """Leave the graph: the services and topics of the action go."""
        for service in self._services:
            self._node.destroy_service(service)
        self._services = []
        self._node.destroy_publisher(self._feedback_publisher)
        self._node.destroy_publisher(self._status_publisher)
        if self in self._node._action_servers:
            self._node._action_servers.remove(self)
