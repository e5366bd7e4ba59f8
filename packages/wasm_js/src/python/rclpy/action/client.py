# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
rclpy.action.client: ActionClient and ClientGoalHandle, on the bus.

The client side of rcl_action's protocol (rclpy.action.server): goals go to
``<action>/_action/send_goal``, results come from ``get_result``, cancels
go to ``cancel_goal``; feedback and status arrive on their topics and reach
the goal they name. Futures complete while the node spins. The blocking
calls (send_goal, get_result, cancel_goal) spin the node's executor until
their future is done: there is no other thread to wait for.
"""

import time
import uuid as uuid_module

from rclpy import _messages
from rclpy.action.server import GoalStatus
from rclpy.action.server import qos_profile_action_status_default
from rclpy.qos import qos_profile_services_default
from rclpy.qos import QoSProfile
from rclpy.task import Future


class ClientGoalHandle:
    """A goal sent by an ActionClient: accepted or not, its status, its result."""

    def __init__(self, action_client, goal_id, goal_response):
        """Made when the server answered the goal request."""
        self._action_client = action_client
        self._goal_id = goal_id
        self._goal_response = goal_response
        self._status = GoalStatus.STATUS_UNKNOWN

    def __eq__(self, other):
        """Equal when the goal ids are."""
        return isinstance(other, ClientGoalHandle) and \
            bytes(self._goal_id.uuid) == bytes(other._goal_id.uuid)

    def __hash__(self):
        """Hash the goal id."""
        return hash(bytes(self._goal_id.uuid))

    def __repr__(self):
        """Show the goal id and the status."""
        return f'ClientGoalHandle <id: {list(self._goal_id.uuid)}, accepted: {self.accepted}, ' \
               f'status: {self.status}>'

    @property
    def goal_id(self):
        """Return the goal id (unique_identifier_msgs/UUID)."""
        return self._goal_id

    @property
    def stamp(self):
        """Return the time the server accepted the goal."""
        return self._goal_response.stamp

    @property
    def accepted(self):
        """Return True when the server accepted the goal."""
        return self._goal_response.accepted

    @property
    def status(self):
        """Return the last status heard (action_msgs/GoalStatus' STATUS_*)."""
        return int(self._status)

    def cancel_goal(self):
        """Cancel the goal and wait: returns the CancelGoal response."""
        return self._action_client._cancel_goal(self)

    def cancel_goal_async(self):
        """Cancel the goal: returns a Future of the CancelGoal response."""
        return self._action_client._cancel_goal_async(self)

    def get_result(self):
        """Wait for the result: returns the GetResult response (status, result)."""
        return self._action_client._get_result(self)

    def get_result_async(self):
        """Ask for the result: returns a Future of the GetResult response (status, result)."""
        return self._action_client._get_result_async(self)


class ActionClient:
    """Sends goals of one action type to the server of one action name."""

    def __init__(self, node, action_type, action_name, *, callback_group=None,
                 goal_service_qos_profile=qos_profile_services_default,
                 result_service_qos_profile=qos_profile_services_default,
                 cancel_service_qos_profile=qos_profile_services_default,
                 feedback_sub_qos_profile=QoSProfile(depth=10),
                 status_sub_qos_profile=qos_profile_action_status_default):
        """Create the action's clients and subscriptions on ``node``."""
        self._node = node
        self._action_type = action_type
        self._action_name = action_name
        impl = action_type.Impl
        base = f'{action_name}/_action'
        self._goal_info_type = _messages.message_class('action_msgs/msg/GoalInfo')
        self._uuid_type = _messages.message_class('unique_identifier_msgs/msg/UUID')
        self.callback_group = callback_group or node.default_callback_group
        self._goal_client = node.create_client(impl.SendGoalService, f'{base}/send_goal',
                                               qos_profile=goal_service_qos_profile,
                                               callback_group=self.callback_group)
        self._cancel_client = node.create_client(impl.CancelGoalService, f'{base}/cancel_goal',
                                                 qos_profile=cancel_service_qos_profile,
                                                 callback_group=self.callback_group)
        self._result_client = node.create_client(impl.GetResultService, f'{base}/get_result',
                                                 qos_profile=result_service_qos_profile,
                                                 callback_group=self.callback_group)
        self._feedback_subscription = node.create_subscription(
            impl.FeedbackMessage, f'{base}/feedback', self._on_feedback,
            feedback_sub_qos_profile, callback_group=self.callback_group)
        self._status_subscription = node.create_subscription(
            impl.GoalStatusMessage, f'{base}/status', self._on_status,
            status_sub_qos_profile, callback_group=self.callback_group)
        self._feedback_callbacks = {}
        self._goal_handles = {}
        node._action_clients.append(self)

    def _on_feedback(self, message):
        callback = self._feedback_callbacks.get(bytes(message.goal_id.uuid))
        if callback is not None:
            callback(message)

    def _on_status(self, message):
        for status in message.status_list:
            key = bytes(status.goal_info.goal_id.uuid)
            handle = self._goal_handles.get(key)
            if handle is None:
                continue
            handle._status = status.status
            if status.status >= GoalStatus.STATUS_SUCCEEDED:
                self._goal_handles.pop(key, None)
                self._feedback_callbacks.pop(key, None)

    def send_goal_async(self, goal, feedback_callback=None, goal_uuid=None):
        """Send a goal: returns a Future of its ClientGoalHandle (accepted or not)."""
        if not isinstance(goal, self._action_type.Goal):
            raise TypeError(f'Expected {self._action_type.Goal}, got {type(goal)}')
        request = self._action_type.Impl.SendGoalService.Request()
        request.goal_id = goal_uuid if goal_uuid is not None else self._random_uuid()
        request.goal = goal
        key = bytes(request.goal_id.uuid)
        if feedback_callback is not None:
            self._feedback_callbacks[key] = feedback_callback
        future = Future()

        def answered(sent):
            if sent.cancelled():
                future.cancel()
                return
            if sent.exception() is not None:
                future.set_exception(sent.exception())
                return
            handle = ClientGoalHandle(self, request.goal_id, sent.result())
            if handle.accepted:
                self._goal_handles[key] = handle
            else:
                self._feedback_callbacks.pop(key, None)
            future.set_result(handle)

        self._goal_client.call_async(request).add_done_callback(answered)
        return future

    def send_goal(self, goal, **kwargs):
        """Send a goal and wait for its result: returns the GetResult response, or None."""
        handle = self._wait(self.send_goal_async(goal, **kwargs))
        if handle is None or not handle.accepted:
            return None
        return handle.get_result()

    def _cancel_goal_async(self, goal_handle):
        request = self._action_type.Impl.CancelGoalService.Request()
        request.goal_info = self._goal_info_type(goal_id=goal_handle.goal_id)
        return self._cancel_client.call_async(request)

    def _cancel_goal(self, goal_handle):
        return self._wait(self._cancel_goal_async(goal_handle))

    def _get_result_async(self, goal_handle):
        request = self._action_type.Impl.GetResultService.Request()
        request.goal_id = goal_handle.goal_id
        future = self._result_client.call_async(request)

        def arrived(done):
            if done.exception() is None and not done.cancelled():
                goal_handle._status = done.result().status

        future.add_done_callback(arrived)
        return future

    def _get_result(self, goal_handle):
        return self._wait(self._get_result_async(goal_handle))

    def _wait(self, future):
        """Spin the node's executor (or rclpy's global one) until ``future`` is done."""
        import rclpy
        executor = self._node.executor
        if executor is None:
            rclpy.spin_until_future_complete(self._node, future)
        else:
            executor.spin_until_future_complete(future)
        return future.result() if future.done() and not future.cancelled() else None

    def _random_uuid(self):
        return self._uuid_type(uuid=list(uuid_module.uuid4().bytes))

    def server_is_ready(self):
        """Return True when the action's three services have a server."""
        return all(c.service_is_ready() for c in
                   (self._goal_client, self._cancel_client, self._result_client))

    def wait_for_server(self, timeout_sec=None):
        """Block until the action server is there; False after ``timeout_sec``."""
        end = None if timeout_sec is None or timeout_sec < 0 else time.monotonic() + timeout_sec
        for client in (self._goal_client, self._cancel_client, self._result_client):
            left = None if end is None else max(0.0, end - time.monotonic())
            if not client.wait_for_service(timeout_sec=left):
                return False
        return True

    def destroy(self):
        """Leave the graph: the clients and subscriptions of the action go."""
        for client in (self._goal_client, self._cancel_client, self._result_client):
            self._node.destroy_client(client)
        self._node.destroy_subscription(self._feedback_subscription)
        self._node.destroy_subscription(self._status_subscription)
        if self in self._node._action_clients:
            self._node._action_clients.remove(self)
