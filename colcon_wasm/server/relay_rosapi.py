# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The rosapi services of serve's rosbridge relay.

rosbridge_server runs a ``rosapi`` node beside it; roslibjs' ``getTopics``,
``getNodes``, ``getServices``, ``getMessageDetails``, ``getParams`` and
``Param`` call its services (rosapi_msgs). The relay answers them itself,
as the Node.js server of ``run``/``launch --rosbridge`` does
(packages/wasm_js/src/bridges/rosbridge/rosapi.mjs), with the same service
names, types and answers:

* the graph services from what the clients advertised, subscribed and
  (colcon-wasm clients) reported of their nodes (``colcon_wasm_graph``);
* the type services from the install space's type descriptions
  (types.json); ``topics_and_raw_types`` gives each type's complete
  definition as rosbag2 writes it (:mod:`colcon_wasm.ros2msg`);
* the parameter services through the nodes' own rcl parameter services,
  which the pages advertise to the relay (relay_parameters.py).

The services are listed as those of a ``/rosapi`` node.
"""

import time

from colcon_wasm.ros2msg import Ros2MsgSchemas
from colcon_wasm.ros2msg import SchemaError
from colcon_wasm.server.relay_forms import normalize
from colcon_wasm.server.relay_forms import PRIMITIVES
from colcon_wasm.server.relay_parameters import RosapiParameters

NODE = '/rosapi'
"""rosapi's services and their rosapi_msgs types."""
SERVICES = {
    'topics': 'Topics', 'topics_for_type': 'TopicsForType',
    'topics_and_raw_types': 'TopicsAndRawTypes', 'services': 'Services',
    'services_for_type': 'ServicesForType', 'nodes': 'Nodes', 'node_details': 'NodeDetails',
    'action_servers': 'GetActionServers', 'topic_type': 'TopicType',
    'service_type': 'ServiceType', 'publishers': 'Publishers', 'subscribers': 'Subscribers',
    'service_providers': 'ServiceProviders', 'service_node': 'ServiceNode',
    'message_details': 'MessageDetails', 'service_request_details': 'ServiceRequestDetails',
    'service_response_details': 'ServiceResponseDetails', 'set_param': 'SetParam',
    'get_param': 'GetParam', 'has_param': 'HasParam', 'delete_param': 'DeleteParam',
    'get_param_names': 'GetParamNames', 'get_time': 'GetTime',
    'get_ros_version': 'GetROSVersion',
}
"""The names rosapi gives primitive field types in message_details."""
TYPEDEF_NAMES = {'float64': 'double', 'float32': 'float', 'bool': 'boolean', 'byte': 'octet'}


def rosapi_service(name):
    """
    Name the rosapi service that ``name`` is, if it is one.

    :param name: a full service name, e.g. ``/rosapi/topics``
    :returns: ``topics``, or None for any other service
    """
    prefix = f'{NODE}/'
    if name.startswith(prefix) and name[len(prefix):] in SERVICES:
        return name[len(prefix):]
    return None


def _full(name):
    return name if name.startswith('/') else f'/{name}'


class Rosapi:
    """rosapi's services over the graph of one relay's clients."""

    def __init__(self, relay):
        """Answer from ``relay``'s clients, services and type descriptions."""
        self.relay = relay
        self.schemas = Ros2MsgSchemas(relay.messages)
        self.parameters = RosapiParameters(relay)

    def call(self, service, args, answer):
        """
        Answer one call, under the relay's lock.

        :param service: the rosapi service's own name (``get_param``)
        :param args: the request
        :param answer: called with the response values: at once, or (the
          parameter services) once the nodes' parameter services answered
        """
        if service in RosapiParameters.SERVICES:
            self.parameters.call(service, args, answer)
        else:
            answer(self._answer(service, args))

    def services(self):
        """List every service of the graph: the clients' and rosapi's, sorted."""
        return sorted(set(self.relay.services) | {f'{NODE}/{n}' for n in SERVICES})

    def _answer(self, name, args):
        def arg(key):
            value = args.get(key) if isinstance(args, dict) else None
            return value if isinstance(value, str) else ''

        relay = self.relay
        topics = self._topics()
        if name == 'topics':
            return {'topics': list(topics), 'types': list(topics.values())}
        if name == 'topics_for_type':
            return {'topics': [t for t, ty in topics.items() if ty == normalize(arg('type'))]}
        if name == 'topics_and_raw_types':
            return {'topics': list(topics), 'types': list(topics.values()),
                    'typedefs_full_text': [self._full_text(t) for t in topics.values()]}
        if name == 'services':
            return {'services': self.services()}
        if name == 'services_for_type':
            wanted = normalize(arg('type').replace('/msg/', '/srv/'), 'srv')
            return {'services': [s for s in self.services() if self._service_type(s) == wanted]}
        if name == 'nodes':
            nodes = {NODE, '/rosbridge_websocket'}
            for p in relay.peers:
                nodes.update(p.label)
            return {'nodes': sorted(nodes)}
        if name == 'node_details':
            return self._node_details(_full(arg('node')))
        if name == 'topic_type':
            return {'type': topics.get(_full(arg('topic')), '')}
        if name == 'service_type':
            return {'type': self._service_type(_full(arg('service')))}
        if name in ('publishers', 'subscribers'):
            topic = _full(arg('topic'))
            table, kind = ('publications', 'publishing') if name == 'publishers' else (
                'subscriptions', 'subscribing')
            return {name: sorted({n for p in relay.peers if topic in getattr(p, table)
                                  for n in p.holders(kind, topic)})}
        if name == 'service_providers':
            return {'providers': self._providers(_full(arg('service')))}
        if name == 'service_node':
            providers = self._providers(_full(arg('service')))
            return {'node': providers[0] if providers else ''}
        if name == 'action_servers':
            return {'action_servers': sorted(relay.actions)}
        if name == 'message_details':
            return {'typedefs': self.typedefs(arg('type'))}
        if name in ('service_request_details', 'service_response_details'):
            entry = relay.service_types.get(normalize(arg('type'), 'srv')) or {}
            part = entry.get('request' if name == 'service_request_details' else 'response')
            return {'typedefs': self.typedefs(part) if part else []}
        if name == 'get_time':
            now = time.time()
            return {'time': {'sec': int(now), 'nanosec': int((now % 1) * 1e9)}}
        return {'version': 2, 'distro': 'humble'}

    def _topics(self):
        topics = {}
        for p in self.relay.peers:
            for topic, type_name in p.publications.items():
                topics.setdefault(topic, type_name)
            for topic, sub in p.subscriptions.items():
                if sub.type:
                    topics.setdefault(topic, sub.type)
        return dict(sorted(topics.items()))

    def _service_type(self, service):
        own = rosapi_service(service)
        if own:
            return f'rosapi_msgs/srv/{SERVICES[own]}'
        entry = self.relay.services.get(service)
        return entry[1] if entry else ''

    def _providers(self, service):
        if rosapi_service(service):
            return [NODE]
        entry = self.relay.services.get(service)
        return entry[0].holders('services', service) if entry else []

    def _full_text(self, type_name):
        """Give a type's complete definition, or rosapi's comment on why there is none."""
        try:
            return self.schemas.full_text(type_name)
        except SchemaError as e:
            return f'# failed to get full definition text for {type_name}: {e}'

    def _node_details(self, node):
        """
        Answer rosapi node_details: the endpoints of ``node``.

        A colcon-wasm client reports which of its nodes holds which endpoint
        (``colcon_wasm_graph`` with ``endpoints``: all of the node's topics and
        the services it serves, bridged or not, as rosapi lists them). A client
        that reports none (roslibjs, roslibpy, an older colcon-wasm client)
        stands for one node, its label: its advertised, subscribed and served
        names are that node's. A node nobody stands for gets empty lists.
        """
        relay = self.relay
        out = {'subscribing': set(), 'publishing': set(), 'services': set()}
        if node == NODE:
            out['services'] = {f'{NODE}/{n}' for n in SERVICES}
        for p in relay.peers:
            if p.endpoints:
                for kind, names in p.endpoints.get(node, {}).items():
                    out[kind] |= names
            elif p.label == [node]:
                out['subscribing'] |= set(p.subscriptions)
                out['publishing'] |= set(p.publications)
                out['services'] |= {n for n, (q, _) in relay.services.items() if q is p}
        return {kind: sorted(names) for kind, names in out.items()}

    def typedefs(self, type_name):
        """
        Describe a message type and the types it uses, as rosapi's message_details does.

        :returns: rosapi_msgs/TypeDef dicts, the type's first; none for a type
          no types.json describes
        """
        messages = self.relay.messages
        out, seen = [], set()

        def visit(full):
            if full in seen or full not in messages:
                return
            seen.add(full)
            nested = []
            td = {'type': full.replace('/msg/', '/'), 'fieldnames': [], 'fieldtypes': [],
                  'fieldarraylen': [], 'examples': [], 'constnames': [], 'constvalues': []}
            for f in messages[full].get('fields', []):
                primitive = f['type'] in PRIMITIVES
                td['fieldnames'].append(f['name'])
                td['fieldtypes'].append(TYPEDEF_NAMES.get(f['type'], f['type']) if primitive
                                        else normalize(f['type']).replace('/msg/', '/'))
                length = f.get('array_size', 0 if f.get('sequence') else -1)
                td['fieldarraylen'].append(length)
                td['examples'].append('[]' if length >= 0 else '{}' if not primitive else '0')
                if not primitive:
                    nested.append(normalize(f['type']))
            for c in messages[full].get('constants', []):
                td['constnames'].append(c['name'])
                td['constvalues'].append(str(c.get('value')))
            out.append(td)
            for n in nested:
                visit(n)

        visit(normalize(type_name))
        return out
