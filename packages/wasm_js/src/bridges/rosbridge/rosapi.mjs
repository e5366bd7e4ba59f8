// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The rosapi services (rosbridge_suite's `rosapi` node) answered by the
 * bridge itself from the bus graph and the build's type descriptions: what
 * roslibjs' getTopics, getNodes, getServices, getTopicType,
 * getMessageDetails, getParams and Param use, and the rest of rosapi_msgs'
 * services. They are listed in the graph views of rosapi as services of a
 * `/rosapi` node, as with rosbridge_server. The parameter services answer
 * rosapi_msgs' `successful` and `reason` (roslibjs 2 hands the reason to
 * its failure callback), as serve's relay does (relay_parameters.py).
 *
 * @module bridges/rosbridge/rosapi
 */

import { normalizeTypeName } from '../../cdr.mjs';
import { fullText } from '../common/schema_texts.mjs';
import { ParameterClient, ParameterType } from '../../page/ros_clients.mjs';
import { parseJson, stringifyJson } from './json.mjs';

export const ROSAPI_NODE = '/rosapi';

const SERVICES = {
  topics: 'Topics', topics_for_type: 'TopicsForType', topics_and_raw_types: 'TopicsAndRawTypes',
  services: 'Services', services_for_type: 'ServicesForType', nodes: 'Nodes', node_details: 'NodeDetails',
  action_servers: 'GetActionServers', topic_type: 'TopicType', service_type: 'ServiceType',
  publishers: 'Publishers', subscribers: 'Subscribers', service_providers: 'ServiceProviders',
  service_node: 'ServiceNode', message_details: 'MessageDetails',
  service_request_details: 'ServiceRequestDetails', service_response_details: 'ServiceResponseDetails',
  set_param: 'SetParam', get_param: 'GetParam', has_param: 'HasParam', delete_param: 'DeleteParam',
  get_param_names: 'GetParamNames', get_time: 'GetTime', get_ros_version: 'GetROSVersion',
};

/** rosapi's services as [name, type] pairs. */
export function rosapiServices() {
  return Object.entries(SERVICES).map(([name, type]) => [`${ROSAPI_NODE}/${name}`, `rosapi_msgs/srv/${type}`]);
}

/** Is this service one of rosapi's? */
export function isRosapi(service) {
  return service.startsWith(`${ROSAPI_NODE}/`) && service.slice(ROSAPI_NODE.length + 1) in SERVICES;
}

const str = (args, name) => (typeof args[name] === 'string' ? args[name] : '');
const full = (name) => (name.startsWith('/') ? name : `/${name}`);

/** [node, param] of rosapi's `<node>:<param>` name, or {reason} naming what is wrong. */
function splitName(args) {
  const name = str(args, 'name');
  const i = name.lastIndexOf(':');
  if (i <= 0 || i === name.length - 1) {
    return { reason: `malformed parameter name '${name}': expected <node_name>:<param_name>, e.g. /talker:greeting` };
  }
  return [full(name.slice(0, i)), name.slice(i + 1)];
}

/** A failed parameter request, with rosapi_msgs' successful and reason. */
const failed = (reason) => ({ successful: false, reason });

/** rosapi's answer for a parameter that is not there: the request's default, as JSON text. */
function defaultOf(args) {
  const d = str(args, 'default_value');
  if (d === '') return 'null';
  try {
    return stringifyJson(parseJson(d));
  } catch {
    return JSON.stringify(d);
  }
}

/** Why a node's parameter service cannot be called, or '' when it can. */
function unreachable(g, node, service) {
  const name = `${node}/${service}`;
  if (g.services.some((s) => s.name === name)) return '';
  return `no node ${node} with parameter services is on the graph (nobody serves ${name})`;
}

/** Get the parameter a request names: {found, value, node, param} or {found: false, why}. */
async function parameterOf(g, paramsOf, args) {
  const split = splitName(args);
  if (split.reason) return { found: false, why: split.reason };
  const [node, param] = split;
  const why = unreachable(g, node, 'get_parameters');
  if (why) return { found: false, why };
  try {
    const [v] = await paramsOf(node).get([param]);
    if (v.type !== 'not set') return { found: true, value: v.value, node, param };
    return { found: false, why: `${node} has no parameter '${param}'` };
  } catch (e) {
    return { found: false, why: `${node} did not answer: ${e.message}` };
  }
}

/** A JS value for a JSON text, typed as ros2 param set types it. */
function parameterFromJson(text) {
  let value;
  try {
    value = parseJson(text);
  } catch {
    throw new Error(`the value of set_param must be JSON text (e.g. 5, 2.5, "text", [1, 2]), got ${JSON.stringify(text)}`);
  }
  if (value === null) return ''; // as rosapi: null sets an empty string
  if (typeof value === 'number' && /[.eE]/.test(text)) return { type: ParameterType.DOUBLE, double_value: value };
  return value;
}

/**
 * Answer a rosapi call.
 * @param {object} core the server's shared state (link, converter, registry)
 * @param {string} service e.g. /rosapi/topics
 * @param {object} args the request
 * @returns {Promise<object>} the response values
 */
export async function rosapiCall(core, service, args) {
  const name = service.slice(ROSAPI_NODE.length + 1);
  const { link, converter } = core;
  const g = link.graph();
  const topics = g.topics.filter((t) => !t.hidden);
  const services = [...g.services.filter((s) => !s.hidden).map((s) => ({ name: s.name, type: s.types[0] })),
    ...rosapiServices().map(([n, t]) => ({ name: n, type: t }))].sort((a, b) => (a.name < b.name ? -1 : 1));
  const nodes = [...new Set([...g.nodes.map((n) => n.fqn), ROSAPI_NODE])].sort();
  const endpointNodes = (topic, kind) => g.nodes.filter((n) => n[kind].some((e) => e.name === topic)).map((n) => n.fqn);
  const paramsOf = (node) => new ParameterClient(link.clientBus(), core.registry, node);
  switch (name) {
    case 'topics': return { topics: topics.map((t) => t.name), types: topics.map((t) => t.types[0] || '') };
    case 'topics_for_type': {
      const type = normalizeTypeName(str(args, 'type'));
      return { topics: topics.filter((t) => t.types.includes(type)).map((t) => t.name) };
    }
    case 'topics_and_raw_types': return {
      topics: topics.map((t) => t.name),
      types: topics.map((t) => t.types[0] || ''),
      typedefs_full_text: topics.map((t) => fullText(core.schemas, t.types[0] || '')),
    };
    case 'services': return { services: services.map((s) => s.name) };
    case 'services_for_type': {
      const type = normalizeTypeName(str(args, 'type')).replace('/msg/', '/srv/');
      return { services: services.filter((s) => s.type === type).map((s) => s.name) };
    }
    case 'nodes': return { nodes };
    case 'node_details': {
      const node = g.nodes.find((n) => n.fqn === full(str(args, 'node')));
      if (!node) return { subscribing: [], publishing: [], services: [] };
      return {
        subscribing: node.subscriptions.map((e) => e.name), publishing: node.publishers.map((e) => e.name),
        services: node.services.map((e) => e.name),
      };
    }
    case 'action_servers': return { action_servers: g.actions.filter((a) => a.servers > 0).map((a) => a.name) };
    case 'topic_type': {
      const t = g.topics.find((x) => x.name === full(str(args, 'topic')));
      return { type: t ? t.types[0] || '' : '' };
    }
    case 'service_type': {
      const s = services.find((x) => x.name === full(str(args, 'service')));
      return { type: s ? s.type : '' };
    }
    case 'publishers': return { publishers: endpointNodes(full(str(args, 'topic')), 'publishers') };
    case 'subscribers': return { subscribers: endpointNodes(full(str(args, 'topic')), 'subscriptions') };
    case 'service_providers': return { providers: endpointNodes(full(str(args, 'service')), 'services') };
    case 'service_node': {
      const providers = endpointNodes(full(str(args, 'service')), 'services');
      return { node: providers[0] || (isRosapi(full(str(args, 'service'))) ? ROSAPI_NODE : '') };
    }
    case 'message_details': return { typedefs: converter.typedefs(str(args, 'type')) };
    case 'service_request_details':
    case 'service_response_details': {
      const entry = core.registry.service(str(args, 'type'));
      return { typedefs: converter.typedefs(name === 'service_request_details' ? entry.request : entry.response) };
    }
    case 'get_param': {
      const got = await parameterOf(g, paramsOf, args);
      if (got.found) return { value: stringifyJson(got.value), successful: true, reason: '' };
      if (str(args, 'default_value') !== '') return { value: defaultOf(args), successful: true, reason: '' };
      return { value: 'null', successful: false, reason: got.why };
    }
    case 'has_param': return { exists: (await parameterOf(g, paramsOf, args)).found };
    case 'set_param': {
      const split = splitName(args);
      if (split.reason) return failed(split.reason);
      const [node, param] = split;
      let value;
      try {
        value = parameterFromJson(str(args, 'value'));
      } catch (e) {
        return failed(e.message);
      }
      const why = unreachable(g, node, 'set_parameters');
      if (why) return failed(`cannot set ${node}:${param}: ${why}`);
      const client = paramsOf(node);
      let r;
      try {
        r = value && value.type === ParameterType.DOUBLE
          ? (await client.request('SetParameters', { parameters: [{ name: param, value }] })).results[0]
          : await client.set(param, value);
      } catch (e) {
        return failed(`cannot set ${node}:${param}: ${e.message}`);
      }
      if (!r.successful) return failed(`setting ${node}:${param} failed: ${r.reason || 'refused by the node'}`);
      return { successful: true, reason: '' };
    }
    case 'delete_param': {
      const got = await parameterOf(g, paramsOf, args);
      if (!got.found) return failed(`cannot delete ${str(args, 'name')}: ${got.why}`);
      const r = (await paramsOf(got.node).request('SetParameters', {
        parameters: [{ name: got.param, value: { type: ParameterType.NOT_SET } }],
      })).results[0];
      if (!r.successful) return failed(`deleting ${got.node}:${got.param} failed: ${r.reason || 'refused by the node'}`);
      return { successful: true, reason: '' };
    }
    case 'get_param_names': {
      const names = [];
      for (const n of g.nodes) {
        if (!n.services.some((s) => s.name === `${n.fqn === '/' ? '' : n.fqn}/list_parameters`)) continue;
        try {
          for (const p of await paramsOf(n.fqn).list()) names.push(`${n.fqn}:${p}`);
        } catch {
          // a node that does not answer is left out, as rosapi does
        }
      }
      return { names };
    }
    case 'get_time': {
      const ms = Date.now();
      return { time: { sec: Math.floor(ms / 1000), nanosec: (ms % 1000) * 1e6 } };
    }
    case 'get_ros_version': return { version: 2, distro: 'humble' };
    default: throw new Error(`rosapi has no service ${service}`);
  }
}
