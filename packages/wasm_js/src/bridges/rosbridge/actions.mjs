// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The ROS 2 action operations of rosbridge 2.x:
 *
 *  - send_action_goal / cancel_action_goal: the client is an action client
 *    of a bus action server (rcl_action's hidden `_action` services and
 *    topics, tools/ros_clients.mjs' ActionClient); the server answers with
 *    action_feedback (when `feedback` is true) and one action_result;
 *  - advertise_action / unadvertise_action, action_feedback, action_result:
 *    the client is the action server. The bridge serves the action's
 *    send_goal, cancel_goal and get_result services and publishes its
 *    feedback and status topics, as rclcpp_action's server does; goals are
 *    accepted (as rosbridge_library's server does) and passed to the client
 *    as send_action_goal, cancels as cancel_action_goal.
 *
 * @module bridges/rosbridge/actions
 */

import { ActionClient } from '../../tools/ros_clients.mjs';
import { stringifyJson } from './json.mjs';
import { field, FieldError, GoalStatus, rosName } from './protocol.mjs';

const FEEDBACK_QOS = { history: 'keep_last', depth: 10, reliability: 'reliable', durability: 'volatile' };
const STATUS_QOS = { history: 'keep_last', depth: 1, reliability: 'reliable', durability: 'transient_local' };
const KEPT_RESULTS = 100;
const hex = (uuid) => Array.from(uuid, (b) => b.toString(16).padStart(2, '0')).join('');
const stampNow = () => {
  const ms = Date.now();
  return { sec: Math.floor(ms / 1000), nanosec: (ms % 1000) * 1e6 };
};

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
    const server = new ActionServer(session, action, full, spec);
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

  /** An action served by this client, on the bus. */
  class ActionServer {
    constructor(owner, action, full, spec) {
      this.session = owner;
      this.action = action;
      this.full = full;
      this.spec = spec;
      this.goals = new Map();
      this.byRid = new Map();
      this.seq = 0;
      this.handles = [];
    }

    async start() {
      const { action, full, spec } = this;
      const base = `${action}/_action`;
      this.feedbackPub = await link.publisher(`${base}/feedback`, spec.feedback_message, FEEDBACK_QOS);
      this.statusPub = await link.publisher(`${base}/status`, 'action_msgs/msg/GoalStatusArray', STATUS_QOS);
      const serve = async (name, type, entry, onRequest) => {
        const h = await link.serve(`${base}/${name}`, type, (requests) => {
          for (const r of requests) {
            let value;
            try {
              value = registry.decode(entry.request, r.data);
            } catch (e) {
              this.session.status('error', `a ${name} request of ${action} could not be decoded: ${e.message}`);
              continue;
            }
            Promise.resolve(onRequest(value, (response) => h.respond(r.id, registry.encode(entry.response, response))))
              .catch((e) => this.session.status('error', `${action} ${name}: ${e.message}`));
          }
        });
        this.handles.push(h);
      };
      await serve('send_goal', `${full}_SendGoal`, spec.send_goal, (req, respond) => this.goal(req, respond));
      await serve('cancel_goal', 'action_msgs/srv/CancelGoal', registry.service('action_msgs/srv/CancelGoal'), (req, respond) => this.cancel(req, respond));
      await serve('get_result', `${full}_GetResult`, spec.get_result, (req, respond) => this.getResult(req, respond));
    }

    publishStatus() {
      const list = [...this.goals.values()].map((g) => ({ goal_info: { goal_id: { uuid: g.uuid }, stamp: g.stamp }, status: g.status }));
      this.statusPub.publish(registry.encode('action_msgs/msg/GoalStatusArray', { status_list: list })).catch(() => {});
    }

    async goal(req, respond) {
      const uuid = req.goal_id.uuid;
      const rid = `action_goal:${this.action}:${++this.seq}`;
      const g = { uuid, rid, stamp: stampNow(), status: GoalStatus.EXECUTING, result: null, waiting: [] };
      this.goals.set(hex(uuid), g);
      this.byRid.set(rid, g);
      while (this.goals.size > KEPT_RESULTS) {
        const [key, old] = this.goals.entries().next().value;
        this.goals.delete(key);
        this.byRid.delete(old.rid);
      }
      await respond({ accepted: true, stamp: g.stamp });
      this.publishStatus();
      this.session.sendText(`{"op":"send_action_goal","id":${JSON.stringify(rid)},"action":${JSON.stringify(this.action)},"action_type":${JSON.stringify(this.full)},"args":${converter.jsonWriter(this.spec.goal)(req.goal)},"feedback":true}`);
    }

    async cancel(req, respond) {
      const uuid = req.goal_info.goal_id.uuid;
      const all = uuid.every((b) => b === 0);
      const canceling = [];
      for (const g of this.goals.values()) {
        if (g.result || !(all || hex(g.uuid) === hex(uuid))) continue;
        g.status = GoalStatus.CANCELING;
        canceling.push({ goal_id: { uuid: g.uuid }, stamp: g.stamp });
        this.session.sendText(`{"op":"cancel_action_goal","id":${JSON.stringify(g.rid)},"action":${JSON.stringify(this.action)}}`);
      }
      await respond({ return_code: canceling.length ? 0 : 2, goals_canceling: canceling });
      if (canceling.length) this.publishStatus();
    }

    async getResult(req, respond) {
      const g = this.goals.get(hex(req.goal_id.uuid));
      if (!g) {
        await respond({ status: GoalStatus.UNKNOWN, result: registry.create(this.spec.result) });
        return;
      }
      if (g.result) await respond({ status: g.status, result: g.result });
      else g.waiting.push(respond);
    }

    async feedback(g, values) {
      const feedback = converter.fromJson(this.spec.feedback, values);
      await this.feedbackPub.publish(registry.encode(this.spec.feedback_message, { goal_id: { uuid: g.uuid }, feedback }));
    }

    async finish(g, status, values) {
      const result = converter.fromJson(this.spec.result, values);
      registry.encode(this.spec.result, result);
      g.status = status;
      g.result = result;
      this.publishStatus();
      for (const respond of g.waiting.splice(0)) await respond({ status, result });
    }

    close() {
      if (core.actions.get(this.action) === this) core.actions.delete(this.action);
      served.delete(this.action);
      for (const g of this.goals.values()) {
        if (!g.result) {
          g.status = GoalStatus.ABORTED;
          g.result = registry.create(this.spec.result);
          for (const respond of g.waiting.splice(0)) respond({ status: g.status, result: g.result }).catch(() => {});
        }
      }
      for (const h of this.handles) h.close().catch(() => {});
      if (this.feedbackPub) this.feedbackPub.release();
      if (this.statusPub) this.statusPub.release();
    }
  }
}
