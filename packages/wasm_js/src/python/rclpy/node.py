# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Node, Publisher, Subscription and Timer on the bus."""

import time

from rclpy import _graph
from rclpy import _messages
from rclpy import parameter_service
from rclpy._bus import bus
from rclpy._bus import plain_to_js
from rclpy._graph import NodeNameNonExistentError  # noqa: F401 (rclpy's name for it)
from rclpy._waiting import block
from rclpy._waiting import runnable_threads
from rclpy._waiting import WaitSet
from rclpy.callback_groups import MutuallyExclusiveCallbackGroup
from rclpy.clock import ROSClock
from rclpy.context import default_context
from rclpy.exceptions import InvalidParameterValueException
from rclpy.exceptions import ParameterAlreadyDeclaredException
from rclpy.exceptions import ParameterNotDeclaredException
from rclpy.exceptions import ROSInterruptException
from rclpy.logging import RcutilsLogger
from rclpy.parameter import Parameter
from rclpy.parameter import SetParametersResult
from rclpy.qos import profile_of
from rclpy.qos import qos_profile_services_default
from rclpy.qos_event import PublisherEventCallbacks
from rclpy.qos_event import SubscriptionEventCallbacks
from rclpy.task import Future


class _Endpoint:
    """What every endpoint has: its node, its QoS and its bus handle."""

    def __init__(self, node, handle, qos_profile):
        """Keep the node, the bus handle and the QoS."""
        self.node = node
        self.qos_profile = qos_profile
        self._handle = handle

    def destroy(self):
        """Leave the graph."""
        if self._handle is not None:
            bus.destroy_endpoint(self._handle)
            self._handle = None


class _TopicEndpoint(_Endpoint):
    """A publisher or subscription: one message type on one topic."""

    def __init__(self, node, msg_type, topic, handle, qos_profile):
        """Keep the type and the fully qualified topic name."""
        super().__init__(node, handle, qos_profile)
        self.msg_type = msg_type
        self.topic = topic
        self._type_name = _messages.type_name(msg_type)

    @property
    def topic_name(self):
        """Return the fully qualified topic name."""
        return self.topic


class _ServiceEndpoint(_Endpoint):
    """A service server or client: one service type under one name."""

    def __init__(self, node, srv_type, srv_name, handle, qos_profile):
        """Keep the type, its request and response type names and the service name."""
        super().__init__(node, handle, qos_profile)
        self.srv_type = srv_type
        self.srv_name = srv_name
        self._type_name = _messages.type_name(srv_type)
        self._request = _messages.type_name(srv_type.Request)
        self._response = _messages.type_name(srv_type.Response)

    @property
    def service_name(self):
        """Return the fully qualified service name."""
        return self.srv_name


class Publisher(_TopicEndpoint):
    """Publishes messages of one type on one topic."""

    def publish(self, msg):
        """Publish a message (an instance of msg_type)."""
        if not isinstance(msg, self.msg_type):
            raise TypeError(f'Expected {self.msg_type}, got {type(msg)}')
        bus.publish(self._handle, self._type_name, plain_to_js(msg._to_plain()))

    def get_subscription_count(self):
        """Return the number of matched subscriptions."""
        return bus.matched_count(self._handle)

    def assert_liveliness(self):
        """Assert this publisher's liveliness (MANUAL_BY_TOPIC; publishing asserts it too)."""
        bus.assert_liveliness(self._handle)


class Subscription(_TopicEndpoint):
    """Calls ``callback(msg)`` for each message of a topic."""

    def __init__(self, node, msg_type, topic, callback, handle, qos_profile):
        """Made by Node.create_subscription."""
        super().__init__(node, msg_type, topic, handle, qos_profile)
        self.callback = callback

    def _take(self):
        value = bus.take(self._handle, self._type_name)
        if value is None:
            return None
        return self.msg_type._from_plain(value.to_py())

    def get_publisher_count(self):
        """Return the number of matched publishers."""
        return bus.matched_count(self._handle)


class Service(_ServiceEndpoint):
    """Answers requests: ``callback(request, response)`` returns the response."""

    def __init__(self, node, srv_type, srv_name, callback, handle, qos_profile):
        """Made by Node.create_service."""
        super().__init__(node, srv_type, srv_name, handle, qos_profile)
        self.callback = callback

    def _take_request(self):
        """Take the next request: (request, its id for _respond), or None."""
        taken = bus.take_request(self._handle, self._request)
        if taken is None:
            return None
        return self.srv_type.Request._from_plain(taken.value.to_py()), taken.id

    def _respond(self, request_id, response):
        """Send what the callback returned to the client that asked."""
        if not isinstance(response, self.srv_type.Response):
            raise TypeError(f'the callback of service {self.srv_name!r} returned '
                            f'{type(response)!r}, not a {self.srv_type.Response}')
        if self._handle is not None:
            bus.send_response(self._handle, request_id, self._response,
                              plain_to_js(response._to_plain()))


class Client(_ServiceEndpoint):
    """Calls a service: ``call_async(request)`` returns a Future of the response."""

    def __init__(self, node, srv_type, srv_name, handle, qos_profile):
        """Made by Node.create_client."""
        super().__init__(node, srv_type, srv_name, handle, qos_profile)
        self._pending = {}

    def call_async(self, request):
        """Send a request; the Future completes while the node spins."""
        if not isinstance(request, self.srv_type.Request):
            raise TypeError(f'Expected {self.srv_type.Request}, got {type(request)}')
        sequence = bus.send_request(self._handle, self._request, plain_to_js(request._to_plain()))
        future = Future()
        self._pending[int(sequence)] = future
        return future

    def call(self, request, timeout_sec=None):
        """
        Send a request and wait for the response (None after ``timeout_sec``).

        There is no other thread to wait for: this spins the node's executor
        (rclpy's global one when the node is in none) until the response is
        there, so the node's other callbacks run meanwhile.
        """
        future = self.call_async(request)
        executor = self.node.executor
        if executor is None:
            import rclpy
            rclpy.spin_until_future_complete(self.node, future, timeout_sec=timeout_sec)
        else:
            executor.spin_until_future_complete(future, timeout_sec=timeout_sec)
        if not future.done():
            self._pending = {k: f for k, f in self._pending.items() if f is not future}
            return None
        return future.result()

    def service_is_ready(self):
        """Return True when a server is matched."""
        return bool(bus.server_available(self._handle))

    def wait_for_service(self, timeout_sec=None):
        """Block until a server is there (sleeping on graph changes); False on timeout.

        The spin threads (rclpy/_threads.py) run meanwhile.
        """
        if timeout_sec is not None and timeout_sec < 0:
            timeout_sec = None
        if not runnable_threads():
            timeout_ms = -1 if timeout_sec is None else timeout_sec * 1000.0
            return bool(bus.wait_for_server(self._handle, timeout_ms))
        end = None if timeout_sec is None else time.monotonic() + timeout_sec
        while True:
            version = bus.graph_version()
            if self.service_is_ready():
                return True
            left = None if end is None else end - time.monotonic()
            if left is not None and left <= 0:
                return False
            wait_set = WaitSet(left)
            wait_set.add('graph', 0, version)
            block(wait_set)

    def _take_response(self):
        """Take the next response: (its request's sequence number, the response), or None."""
        taken = bus.take_response(self._handle, self._response)
        if taken is None:
            return None
        return int(taken.seq), self.srv_type.Response._from_plain(taken.value.to_py())

    def _complete(self, sequence, response):
        """Complete the future of the request ``sequence`` (the executor's client callback)."""
        future = self._pending.pop(sequence, None)
        if future is not None and not future.done():
            future.set_result(response)


class Timer:
    """
    Calls ``callback()`` every ``timer_period_ns`` of its clock.

    The clock is the node's ROS clock unless another is given, as in rclpy:
    while the node uses simulated time (``use_sim_time``), the timer counts
    the time of ``/clock`` (it fires as ``/clock`` messages arrive, never
    before the first one), else the steady clock. A switch between the two
    starts a period anew.
    """

    def __init__(self, callback, timer_period_sec, callback_group=None, clock=None):
        """Made by Node.create_timer; first call one period from now."""
        if timer_period_sec <= 0:
            raise ValueError(f'timer period must be > 0, got {timer_period_sec}')
        self.callback = callback
        self.callback_group = callback_group
        self.timer_period_ns = int(timer_period_sec * 1e9)
        self._period = timer_period_sec
        self._clock = clock
        self._simulated, now = self._now()
        self._next = now + timer_period_sec
        self._canceled = False

    @property
    def clock(self):
        """Return the clock the timer counts (None: the steady clock)."""
        return self._clock

    def _now(self):
        """Return (simulated?, seconds): the ROS clock's /clock time, else the steady clock."""
        if self._clock is not None and getattr(self._clock, 'ros_time_is_active', False):
            return True, self._clock.now().nanoseconds / 1e9
        return False, time.monotonic()

    def _current(self):
        """Return the time now on the timer's base; a change of base starts a period."""
        simulated, now = self._now()
        if simulated != self._simulated:
            self._simulated = simulated
            self._next = now + self._period
        return now

    def cancel(self):
        """Stop calling back."""
        self._canceled = True

    def reset(self):
        """Start a period from now."""
        self._canceled = False
        self._next = self._current() + self._period

    def is_canceled(self):
        """Return True when canceled."""
        return self._canceled

    def time_until_next_call(self):
        """Return nanoseconds until the next call (None when canceled)."""
        if self._canceled:
            return None
        return max(0, int((self._next - self._current()) * 1e9))

    def destroy(self):
        """Stop calling back."""
        self.cancel()

    def _seconds_left(self):
        """Return the steady seconds to wait for it, or None (simulated: wait for /clock).

        A simulated timer that /clock made due is due now (0), as rcl's is
        ready after the clock's jump.
        """
        now = self._current()
        if self._simulated:
            return 0.0 if now >= self._next else None
        return max(0.0, self._next - now)

    def _due(self):
        return not self._canceled and self._current() >= self._next

    def _advance(self):
        now = self._current()
        self._next += self._period
        if self._next <= now:  # late by more than a period: do not call in a burst
            self._next = now + self._period


class Rate:
    """
    Sleeps until the next period of a frequency, on a clock (the node's ROS clock).

    Off simulated time the periods are counted on the steady clock; while the
    clock follows ``/clock`` (``use_sim_time``), on its time, and ``sleep()``
    waits for ``/clock`` to reach the period's end (Clock.sleep_until). A
    switch between the two starts a period anew. ``sleep()`` uses time.sleep
    (rclpy.executors): inside a callback of a MultiThreadedExecutor the other
    ready callbacks run meanwhile; elsewhere it blocks, as rclpy's blocks its
    thread. After rclpy's shutdown it raises ROSInterruptException, as rclpy's.
    """

    def __init__(self, frequency, clock=None, context=None):
        """Made by Node.create_rate; the first period starts now."""
        if frequency <= 0:
            raise ValueError(f'frequency must be > 0, got {frequency}')
        self._period_ns = int(1e9 / frequency)
        self._clock = clock
        self._context = context or default_context()
        self._simulated, now = self._now_ns()
        self._next = now + self._period_ns
        self._destroyed = False

    def _now_ns(self):
        """Return (simulated?, nanoseconds now on the rate's base)."""
        if self._clock is not None and getattr(self._clock, 'ros_time_is_active', False):
            return True, self._clock.now().nanoseconds
        return False, time.monotonic_ns()

    def sleep(self):
        """Sleep until the end of the current period; a late call starts a new period now."""
        if self._destroyed:
            raise RuntimeError('Rate cannot sleep because it has been destroyed')
        if not self._context.ok():
            raise ROSInterruptException()
        simulated, now = self._now_ns()
        if simulated != self._simulated:
            self._simulated, self._next = simulated, now + self._period_ns
        if self._next <= now:
            self._next = now + self._period_ns
            return
        if simulated:
            from rclpy.time import Time
            until = Time(nanoseconds=self._next, clock_type=self._clock.clock_type)
            self._clock.sleep_until(until, self._context)
        else:
            time.sleep((self._next - now) / 1e9)
        self._next += self._period_ns
        if not self._context.ok():
            raise ROSInterruptException()

    def destroy(self):
        """Refuse further sleeps."""
        self._destroyed = True


class GuardCondition:
    """Calls ``callback()`` once while the node spins after each trigger()."""

    def __init__(self, callback, callback_group=None):
        """Made by Node.create_guard_condition."""
        self.callback = callback
        self.callback_group = callback_group
        self._triggered = False

    def trigger(self):
        """Make the next spin call the callback (this thread spins: no wake-up needed)."""
        self._triggered = True

    def destroy(self):
        """Never call back again."""
        self._triggered = False


def _expand(name, namespace, node_name, what):
    if not name:
        raise ValueError(f'{what} name must not be empty')
    if name.startswith('~'):
        base = f"{namespace.rstrip('/')}/{node_name}"
        name = base + name[1:]
    elif not name.startswith('/'):
        name = f"{namespace.rstrip('/')}/{name}"
    return name


class Node:
    """A ROS node of this process on the bus."""

    def __init__(self, node_name, *, context=None, namespace=None, cli_args=None,
                 parameter_overrides=None, allow_undeclared_parameters=False,
                 automatically_declare_parameters_from_overrides=False, **kwargs):
        """Create the node (it joins the graph now); ``-r __node:=`` and ``__ns:=`` apply.

        ``parameter_overrides`` (Parameters) win over the command line's
        ``-p``, as in rclpy; ``automatically_declare_parameters_from_overrides``
        declares every override now; with ``allow_undeclared_parameters``,
        setting an undeclared parameter declares it and getting one returns
        a NOT_SET Parameter.
        """
        self.context = context or default_context()
        self.context._check_ok('create a node')
        remaps = self.context.remappings(cli_args)
        node_name = remaps.get('__node', node_name)
        namespace = remaps.get('__ns', namespace) or '/'
        if not namespace.startswith('/'):
            namespace = f'/{namespace}'
        if len(namespace) > 1:
            namespace = namespace.rstrip('/')
        self._remaps = remaps
        self._name = node_name
        self._namespace = namespace
        self._handle = bus.create_node(node_name, namespace, self.context.domain_id)
        self._logger = RcutilsLogger(node_name if namespace == '/' else
                                     f"{namespace.strip('/').replace('/', '.')}.{node_name}")
        self._clock = ROSClock()
        self.publishers = []
        self.subscriptions = []
        self.timers = []
        self.services = []
        self.clients = []
        self.guards = []
        self._action_servers = []
        self._action_clients = []
        self.executor = None
        self._default_callback_group = MutuallyExclusiveCallbackGroup()
        self._parameters = {}
        self._parameter_callbacks = []
        self._overrides = self.context.parameter_overrides(node_name, cli_args)
        self._overrides.update((p.name, p.value) for p in parameter_overrides or ())
        self._allow_undeclared = allow_undeclared_parameters
        if automatically_declare_parameters_from_overrides:
            self._parameters.update((name, Parameter(name, value=value))
                                    for name, value in self._overrides.items())
        self.context._nodes.append(self)
        self._parameter_service = None
        if kwargs.get('start_parameter_services', True) and parameter_service.available():
            self._parameter_service = parameter_service.ParameterService(self)
        from rclpy.time_source import TimeSource
        self._time_source = TimeSource(self)

    @property
    def default_callback_group(self):
        """Return the group of the entities created without one (mutually exclusive)."""
        return self._default_callback_group

    def _group(self, entity, callback_group):
        group = callback_group or self._default_callback_group
        entity.callback_group = group
        group.add_entity(entity)
        return entity

    def get_name(self):
        """Return the node's name."""
        return self._name

    def get_namespace(self):
        """Return the node's namespace."""
        return self._namespace

    def get_fully_qualified_name(self):
        """Return ``/ns/name``."""
        return f"{self._namespace.rstrip('/')}/{self._name}"

    def get_logger(self):
        """Return the node's logger."""
        return self._logger

    def get_clock(self):
        """Return the node's clock (ROS time: /clock while use_sim_time is true)."""
        return self._clock

    def resolve_topic_name(self, topic):
        """Expand a topic name (relative, ``~``) and apply remappings."""
        topic = self._remaps.get(topic, topic)
        full = _expand(topic, self._namespace, self._name, 'topic')
        return self._remaps.get(full, full)

    def create_publisher(self, msg_type, topic, qos_profile, *, callback_group=None,
                         event_callbacks=None, **kwargs):
        """Create a publisher; ``qos_profile`` is a QoSProfile or a history depth."""
        qos = profile_of(qos_profile)
        type_name = _messages.type_name(msg_type)
        name = self.resolve_topic_name(topic)
        handle = bus.create_publisher(self._handle, name, type_name, qos.to_bus())
        publisher = Publisher(self, msg_type, name, handle, qos)
        self._group(publisher, callback_group)
        publisher.event_handlers = (event_callbacks or PublisherEventCallbacks()) \
            .create_event_handlers(publisher)
        self.publishers.append(publisher)
        return publisher

    def create_subscription(self, msg_type, topic, callback, qos_profile, *,
                            callback_group=None, event_callbacks=None, **kwargs):
        """Create a subscription that calls ``callback(msg)`` while the node spins."""
        qos = profile_of(qos_profile)
        type_name = _messages.type_name(msg_type)
        name = self.resolve_topic_name(topic)
        handle = bus.create_subscription(self._handle, name, type_name, qos.to_bus())
        subscription = Subscription(self, msg_type, name, callback, handle, qos)
        self._group(subscription, callback_group)
        subscription.event_handlers = (event_callbacks or SubscriptionEventCallbacks()) \
            .create_event_handlers(subscription)
        self.subscriptions.append(subscription)
        return subscription

    def create_timer(self, timer_period_sec, callback, callback_group=None, clock=None):
        """Create a timer that calls ``callback()`` every period while the node spins."""
        timer = self._group(Timer(callback, timer_period_sec, clock=clock or self._clock),
                            callback_group)
        self.timers.append(timer)
        return timer

    def create_rate(self, frequency, clock=None):
        """Create a Rate: ``sleep()`` waits until the next period of ``frequency`` Hz.

        ``clock``: the clock it counts (default: the node's ROS clock).
        """
        return Rate(frequency, clock or self._clock, self.context)

    def create_guard_condition(self, callback, callback_group=None):
        """Create a guard condition: ``trigger()`` makes the next spin call ``callback()``."""
        guard = self._group(GuardCondition(callback), callback_group)
        self.guards.append(guard)
        return guard

    def destroy_guard_condition(self, guard):
        """Destroy a guard condition of this node."""
        guard.destroy()
        if guard in self.guards:
            self.guards.remove(guard)
        return True

    def create_service(self, srv_type, srv_name, callback, *,
                       qos_profile=qos_profile_services_default, callback_group=None, **kwargs):
        """Create a service server; ``callback(request, response)`` returns the response."""
        name = self._resolve_service_name(srv_name)
        handle = bus.create_service(self._handle, name, _messages.type_name(srv_type),
                                    qos_profile.to_bus())
        service = Service(self, srv_type, name, callback, handle, qos_profile)
        self._group(service, callback_group)
        self.services.append(service)
        return service

    def create_client(self, srv_type, srv_name, *, qos_profile=qos_profile_services_default,
                      callback_group=None, **kwargs):
        """Create a service client."""
        name = self._resolve_service_name(srv_name)
        handle = bus.create_client(self._handle, name, _messages.type_name(srv_type),
                                   qos_profile.to_bus())
        client = Client(self, srv_type, name, handle, qos_profile)
        self._group(client, callback_group)
        self.clients.append(client)
        return client

    def _resolve_service_name(self, name):
        name = self._remaps.get(name, name)
        full = _expand(name, self._namespace, self._name, 'service')
        return self._remaps.get(full, full)

    def destroy_service(self, service):
        """Destroy a service server of this node."""
        service.destroy()
        if service in self.services:
            self.services.remove(service)
        return True

    def destroy_client(self, client):
        """Destroy a service client of this node."""
        client.destroy()
        if client in self.clients:
            self.clients.remove(client)
        return True

    def declare_parameter(self, name, value=None, descriptor=None, ignore_override=False):
        """Declare a parameter; a ``-p name:=value`` override wins over ``value``."""
        if name in self._parameters:
            raise ParameterAlreadyDeclaredException(name)
        if not ignore_override and name in self._overrides:
            value = self._overrides[name]
        parameter = Parameter(name, value=value)
        result = self._run_parameter_callbacks([parameter])
        if not result.successful:
            raise InvalidParameterValueException(name, value, result.reason)
        self._parameters[name] = parameter
        if self._parameter_service is not None:
            self._parameter_service.publish_event(new=[parameter])
        return parameter

    def declare_parameters(self, namespace, parameters):
        """Declare ``[(name, value), ...]`` under ``namespace.``."""
        prefix = f'{namespace}.' if namespace else ''
        return [self.declare_parameter(prefix + entry[0], *entry[1:2]) for entry in parameters]

    def has_parameter(self, name):
        """Return True when the parameter is declared."""
        return name in self._parameters

    def get_parameter(self, name):
        """Return a declared parameter."""
        if name in self._parameters:
            return self._parameters[name]
        if self._allow_undeclared:
            return Parameter(name)
        raise ParameterNotDeclaredException(name)

    def get_parameter_or(self, name, alternative_value=None):
        """Return a declared parameter, else ``alternative_value``."""
        if name not in self._parameters:
            return alternative_value
        return self._parameters[name]

    def get_parameters(self, names):
        """Return declared parameters."""
        return [self.get_parameter(n) for n in names]

    def set_parameters(self, parameters):
        """Set declared parameters one by one; returns a SetParametersResult each."""
        results = []
        for parameter in parameters:
            new = parameter.name not in self._parameters
            if new and not self._allow_undeclared:
                raise ParameterNotDeclaredException(parameter.name)
            result = self._run_parameter_callbacks([parameter])
            if result.successful:
                self._parameters[parameter.name] = parameter
                if self._parameter_service is not None:
                    self._parameter_service.publish_event(
                        **{'new' if new else 'changed': [parameter]})
            results.append(result)
        return results

    def add_on_set_parameters_callback(self, callback):
        """Call ``callback([Parameter])`` before parameters change; it may refuse."""
        self._parameter_callbacks.insert(0, callback)

    def remove_on_set_parameters_callback(self, callback):
        """Remove a parameter callback."""
        self._parameter_callbacks.remove(callback)

    def _run_parameter_callbacks(self, parameters):
        for callback in self._parameter_callbacks:
            result = callback(parameters)
            if not result.successful:
                return result
        return SetParametersResult(successful=True)

    # ------------------------------------------------------------ graph

    def get_node_names(self):
        """Return the names of the nodes in this node's domain."""
        return [n['name'] for n in _graph.snapshot(self.context.domain_id)[0]]

    def get_node_names_and_namespaces(self):
        """Return ``[(name, namespace)]`` of the nodes in this node's domain."""
        return [(n['name'], n['namespace']) for n in _graph.snapshot(self.context.domain_id)[0]]

    def get_node_names_and_namespaces_with_enclaves(self):
        """Return ``[(name, namespace, enclave)]`` (one enclave, ``/``, on the bus)."""
        return [(n, ns, '/') for n, ns in self.get_node_names_and_namespaces()]

    def get_topic_names_and_types(self, no_demangle=False):
        """Return ``[(topic, [types])]`` of every publisher and subscription in the domain."""
        _, endpoints = _graph.snapshot(self.context.domain_id)
        return _graph.names_and_types(endpoints, ('publisher', 'subscription'))

    def get_service_names_and_types(self):
        """Return ``[(service, [types])]`` of every service server in the domain."""
        _, endpoints = _graph.snapshot(self.context.domain_id)
        return _graph.names_and_types(endpoints, ('service',))

    def _by_node(self, kinds, node_name, node_namespace):
        nodes, endpoints = _graph.snapshot(self.context.domain_id)
        _graph.require_node(nodes, node_name, node_namespace)
        return _graph.names_and_types(endpoints, kinds, (node_name, node_namespace))

    def get_publisher_names_and_types_by_node(self, node_name, node_namespace,
                                              no_demangle=False):
        """Return ``[(topic, [types])]`` a node publishes; NodeNameNonExistentError if none."""
        return self._by_node(('publisher',), node_name, node_namespace)

    def get_subscriber_names_and_types_by_node(self, node_name, node_namespace,
                                               no_demangle=False):
        """Return ``[(topic, [types])]`` a node subscribes to."""
        return self._by_node(('subscription',), node_name, node_namespace)

    def get_service_names_and_types_by_node(self, node_name, node_namespace):
        """Return ``[(service, [types])]`` a node serves."""
        return self._by_node(('service',), node_name, node_namespace)

    def get_client_names_and_types_by_node(self, node_name, node_namespace):
        """Return ``[(service, [types])]`` a node has clients of."""
        return self._by_node(('client',), node_name, node_namespace)

    def count_publishers(self, topic_name):
        """Return the number of publishers of a topic (the name is expanded and remapped)."""
        _, endpoints = _graph.snapshot(self.context.domain_id)
        return _graph.count(endpoints, 'publisher', self.resolve_topic_name(topic_name))

    def count_subscribers(self, topic_name):
        """Return the number of subscriptions of a topic."""
        _, endpoints = _graph.snapshot(self.context.domain_id)
        return _graph.count(endpoints, 'subscription', self.resolve_topic_name(topic_name))

    def get_publishers_info_by_topic(self, topic_name, no_mangle=False):
        """Return a TopicEndpointInfo for each publisher of a topic."""
        _, endpoints = _graph.snapshot(self.context.domain_id)
        topic = topic_name if no_mangle else self.resolve_topic_name(topic_name)
        return _graph.endpoint_infos(endpoints, 'publisher', topic)

    def get_subscriptions_info_by_topic(self, topic_name, no_mangle=False):
        """Return a TopicEndpointInfo for each subscription of a topic."""
        _, endpoints = _graph.snapshot(self.context.domain_id)
        topic = topic_name if no_mangle else self.resolve_topic_name(topic_name)
        return _graph.endpoint_infos(endpoints, 'subscription', topic)

    def destroy_publisher(self, publisher):
        """Destroy a publisher of this node."""
        publisher.destroy()
        if publisher in self.publishers:
            self.publishers.remove(publisher)
        return True

    def destroy_subscription(self, subscription):
        """Destroy a subscription of this node."""
        subscription.destroy()
        if subscription in self.subscriptions:
            self.subscriptions.remove(subscription)
        return True

    def destroy_timer(self, timer):
        """Destroy a timer of this node."""
        timer.destroy()
        if timer in self.timers:
            self.timers.remove(timer)
        return True

    def destroy_node(self):
        """Leave the graph with every endpoint of this node."""
        for action in list(self._action_servers) + list(self._action_clients):
            action.destroy()
        for guard in list(self.guards):
            self.destroy_guard_condition(guard)
        for publisher in list(self.publishers):
            self.destroy_publisher(publisher)
        for subscription in list(self.subscriptions):
            self.destroy_subscription(subscription)
        for timer in list(self.timers):
            self.destroy_timer(timer)
        for service in list(self.services):
            self.destroy_service(service)
        for client in list(self.clients):
            self.destroy_client(client)
        if self._handle is not None:
            bus.destroy_node(self._handle)
            self._handle = None
        if self in self.context._nodes:
            self.context._nodes.remove(self)
        return True
