// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The ROS 2 action operations of rosbridge 2.x:
 *
 *  - send_action_goal / cancel_action_goal: the client is an action client
 *    of a bus action server (rcl_action's hidden `_action` services and
 *    topics, page/ros_clients.mjs' ActionClient); the server answers with
 *    action_feedback (when `feedback` is true) and one action_result;
 *  - advertise_action / unadvertise_action, action_feedback, action_result:
 *    the client is the action server. The bridge serves the action's
 *    send_goal, cancel_goal and get_result services and publishes its
 *    feedback and status topics (action_server.mjs); goals are accepted (as
 *    rosbridge_library's server does) and passed to the client as
 *    send_action_goal, cancels as cancel_action_goal.
 *
 * @module bridges/rosbridge/actions
 */

import { ActionClient } from '../../page/ros_clients.mjs';
import { BusActionServer } from './action_server.mjs';
import { stringifyJson } from './json.mjs';
import { field, FieldError, GoalStatus, rosName } from './protocol.mjs';


/** Register the action operations on a session. */
export function installActions(session) {
  const { core } = session;
  const { converter, registry, link } = core;
  const goals = new Map();
  const served = new Map();

  const actionSpec = (op, fieldName, type) => {
    try {
      const full = type.split('/').length === 2 ? type.replace('/', '/action/') : type;
      return { full, spec: registry.action(full) };
    } catch (e) {
      throw new FieldError(op, fieldName, `names an unknown action type: ${e.message}`);
    }
  };
  const idPart = (id) => (id === undefined ? '' : `,"id":${stringifyJson(id)}`);

  session.register('send_action_goal', async (msg) => {
    const action = rosName('send_action_goal', 'action', field(msg, 'action', 'string', { required: true }));
    if (!core.capabilities.allows('call', action)) throw new Error(core.capabilities.refusal('call', action));
    const { full, spec } = actionSpec('send_action_goal', 'action_type', field(msg, 'action_type', 'string', { required: true, what: 'e.g. example_interfaces/action/Fibonacci' }));
    const wantFeedback = field(msg, 'feedback', 'bool', { fallback: false });
    const goal = converter.fromJson(spec.goal, Array.isArray(msg.args) ? Object.fromEntries(registry.message(spec.goal).fields.map((f, i) => [f.name, msg.args[i]]).filter(([, v]) => v !== undefined)) : (msg.args || {}));
    const fail = (text) => {
      session.sendText(`{"op":"action_result","action":${JSON.stringify(action)},"values":${JSON.stringify(text)},"status":${GoalStatus.UNKNOWN},"result":false${idPart(msg.id)}}`);
      session.status('error', `send_action_goal ${action}: ${text}`, msg.id);
    };
    if (!link.hasServer(`${action}/_action/send_goal`)) {
      fail(`action '${action}' has no server in the graph`);
      return;
    }
    const client = new ActionClient(link.clientBus(), registry, action, full);
    let sent;
    try {
      registry.encode(spec.goal, goal);
    } catch (e) {
      throw new FieldError('send_action_goal', 'args', `do not fit ${spec.goal}: ${e.message.replace(/^encoding [^:]+: /, '')}`);
    }
    const record = { handle: null, cancelled: false };
    if (msg.id !== undefined) goals.set(String(msg.id), record);
    try {
      sent = await client.sendGoal(goal, {
        timeoutMs: core.limits.callTimeoutMs,
        onFeedback: (value) => {
          if (!wantFeedback || session.closed) return;
          session.sendText(`{"op":"action_feedback","action":${JSON.stringify(action)},"values":${converter.jsonWriter(spec.feedback)(value)}${idPart(msg.id)}}`);
        },
      });
    } catch (e) {
      goals.delete(String(msg.id));
      fail(e.message);
      return;
    }
    if (!sent.accepted) {
      goals.delete(String(msg.id));
      fail('Action goal was rejected');
      return;
    }
    record.handle = sent.handle;
    if (record.cancelled) sent.handle.cancel().catch(() => {});
    try {
      const r = await sent.result;
      if (session.closed) return;
      session.sendText(`{"op":"action_result","action":${JSON.stringify(action)},"values":${converter.jsonWriter(spec.result)(r.result)},"status":${r.status},"result":true${idPart(msg.id)}}`);
    } catch (e) {
      fail(e.message);
    } finally {
      goals.delete(String(msg.id));
    }
  });

  session.register('cancel_action_goal', async (msg) => {
    rosName('cancel_action_goal', 'action', field(msg, 'action', 'string', { required: true }));
    const id = field(msg, 'id', 'id', { required: true, what: 'the id of the send_action_goal to cancel' });
    const record = goals.get(String(id));
    if (!record) throw new FieldError('cancel_action_goal', 'id', `'${id}' names no goal of this client in progress`);
    if (!record.handle) {
      record.cancelled = true;
      return;
    }
    await record.handle.cancel(core.limits.callTimeoutMs);
  });

  session.register('advertise_action', async (msg) => {
    const action = rosName('advertise_action', 'action', field(msg, 'action', 'string', { required: true }));
    if (!core.capabilities.allows('advertise', action)) throw new Error(core.capabilities.refusal('advertise', action));
    const { full, spec } = actionSpec('advertise_action', 'type', field(msg, 'type', 'string', { required: true }));
    const previous = core.actions.get(action);
    if (previous) {
      previous.session.status('warning', `action ${action} was advertised again by another client: this client no longer serves it`);
      previous.close();
    }
    const server = new BusActionServer({
      link, registry, converter, action, full, spec,
      onGoal: (rid, goalJson) => session.sendText(`{"op":"send_action_goal","id":${JSON.stringify(rid)},"action":${JSON.stringify(action)},"action_type":${JSON.stringify(full)},"args":${goalJson},"feedback":true}`),
      onCancel: (rid) => session.sendText(`{"op":"cancel_action_goal","id":${JSON.stringify(rid)},"action":${JSON.stringify(action)}}`),
      onError: (text) => session.status('error', text),
      onClose: () => {
        if (core.actions.get(action) === server) core.actions.delete(action);
        served.delete(action);
      },
    });
    server.session = session;
    await server.start();
    served.set(action, server);
    core.actions.set(action, server);
    session.status('info', `Advertised action ${action}`, msg.id);
  });

  session.register('unadvertise_action', (msg) => {
    const action = rosName('unadvertise_action', 'action', field(msg, 'action', 'string', { required: true }));
    const server = served.get(action);
    if (!server) {
      session.status('warning', `unadvertise_action: this client does not serve '${action}'`, msg.id);
      return;
    }
    server.close();
  });

  const servedAction = (msg) => {
    const action = rosName(msg.op, 'action', field(msg, 'action', 'string', { required: true }));
    const server = served.get(action);
    if (!server) throw new Error(`action ${action} has not been advertised by this client`);
    const id = String(field(msg, 'id', 'id', { required: true, what: 'the id of the send_action_goal it is for' }));
    const goal = server.byRid.get(id);
    if (!goal) throw new FieldError(msg.op, 'id', `'${id}' names no goal of ${action} in progress`);
    return { server, goal };
  };

  session.register('action_feedback', async (msg) => {
    const { server, goal } = servedAction(msg);
    await server.feedback(goal, msg.values || {});
  });

  session.register('action_result', async (msg) => {
    const { server, goal } = servedAction(msg);
    const result = field(msg, 'result', 'bool', { required: true });
    const status = field(msg, 'status', 'int', { fallback: result ? GoalStatus.SUCCEEDED : GoalStatus.ABORTED });
    await server.finish(goal, result ? status : GoalStatus.ABORTED, result && msg.values && typeof msg.values === 'object' ? msg.values : {});
  });

  session.onClose(() => {
    for (const s of [...served.values()]) s.close();
    goals.clear();
  });

}
