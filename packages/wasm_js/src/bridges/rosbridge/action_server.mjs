// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * An action served on the bus for someone across a bridge (a rosbridge
 * client that sent advertise_action, or a remote action server our local
 * action clients use): the action's send_goal, cancel_goal and get_result
 * services and its feedback and status topics, as rclcpp_action's server
 * does them. Goals are accepted and handed on (`onGoal`), cancels too
 * (`onCancel`); `feedback()` and `finish()` bring back what the other side
 * says. The last 100 goals are kept for late get_result calls.
 *
 * @module bridges/rosbridge/action_server
 */

import { GoalStatus } from './protocol.mjs';

const FEEDBACK_QOS = { history: 'keep_last', depth: 10, reliability: 'reliable', durability: 'volatile' };
const STATUS_QOS = { history: 'keep_last', depth: 1, reliability: 'reliable', durability: 'transient_local' };
const KEPT_RESULTS = 100;
const hex = (uuid) => Array.from(uuid, (b) => b.toString(16).padStart(2, '0')).join('');
const stampNow = () => {
  const ms = Date.now();
  return { sec: Math.floor(ms / 1000), nanosec: (ms % 1000) * 1e6 };
};

/** See the module's comment. */
export class BusActionServer {
  /**
   * @param {object} o {link, registry, converter, action, full (type), spec (registry.action()),
   *   onGoal(rid, goalJsonText), onCancel(rid), onError(text), onClose()}
   */
  constructor({ link, registry, converter, action, full, spec, onGoal, onCancel, onError, onClose }) {
    this.link = link;
    this.registry = registry;
    this.converter = converter;
    this.onGoal = onGoal;
    this.onCancel = onCancel;
    this.onError = onError;
    this.onClose = onClose || (() => {});
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
    this.feedbackPub = await this.link.publisher(`${base}/feedback`, spec.feedback_message, FEEDBACK_QOS);
    this.statusPub = await this.link.publisher(`${base}/status`, 'action_msgs/msg/GoalStatusArray', STATUS_QOS);
    const serve = async (name, type, entry, onRequest) => {
      const h = await this.link.serve(`${base}/${name}`, type, (requests) => {
        for (const r of requests) {
          let value;
          try {
            value = this.registry.decode(entry.request, r.data);
          } catch (e) {
            this.onError(`a ${name} request of ${action} could not be decoded: ${e.message}`);
            continue;
          }
          Promise.resolve(onRequest(value, (response) => h.respond(r.id, this.registry.encode(entry.response, response))))
            .catch((e) => this.onError(`${action} ${name}: ${e.message}`));
        }
      });
      this.handles.push(h);
    };
    await serve('send_goal', `${full}_SendGoal`, spec.send_goal, (req, respond) => this.goal(req, respond));
    await serve('cancel_goal', 'action_msgs/srv/CancelGoal', this.registry.service('action_msgs/srv/CancelGoal'), (req, respond) => this.cancel(req, respond));
    await serve('get_result', `${full}_GetResult`, spec.get_result, (req, respond) => this.getResult(req, respond));
  }

  publishStatus() {
    const list = [...this.goals.values()].map((g) => ({ goal_info: { goal_id: { uuid: g.uuid }, stamp: g.stamp }, status: g.status }));
    this.statusPub.publish(this.registry.encode('action_msgs/msg/GoalStatusArray', { status_list: list })).catch(() => {});
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
    this.onGoal(rid, this.converter.jsonWriter(this.spec.goal)(req.goal));
  }

  async cancel(req, respond) {
    const uuid = req.goal_info.goal_id.uuid;
    const all = uuid.every((b) => b === 0);
    const canceling = [];
    for (const g of this.goals.values()) {
      if (g.result || !(all || hex(g.uuid) === hex(uuid))) continue;
      g.status = GoalStatus.CANCELING;
      canceling.push({ goal_id: { uuid: g.uuid }, stamp: g.stamp });
      this.onCancel(g.rid);
    }
    await respond({ return_code: canceling.length ? 0 : 2, goals_canceling: canceling });
    if (canceling.length) this.publishStatus();
  }

  async getResult(req, respond) {
    const g = this.goals.get(hex(req.goal_id.uuid));
    if (!g) {
      await respond({ status: GoalStatus.UNKNOWN, result: this.registry.create(this.spec.result) });
      return;
    }
    if (g.result) await respond({ status: g.status, result: g.result });
    else g.waiting.push(respond);
  }

  async feedback(g, values) {
    const feedback = this.converter.fromJson(this.spec.feedback, values);
    await this.feedbackPub.publish(this.registry.encode(this.spec.feedback_message, { goal_id: { uuid: g.uuid }, feedback }));
  }

  async finish(g, status, values) {
    const result = this.converter.fromJson(this.spec.result, values);
    this.registry.encode(this.spec.result, result);
    g.status = status;
    g.result = result;
    this.publishStatus();
    for (const respond of g.waiting.splice(0)) await respond({ status, result });
  }

  close() {
    this.onClose();
    for (const g of this.goals.values()) {
      if (!g.result) {
        g.status = GoalStatus.ABORTED;
        g.result = this.registry.create(this.spec.result);
        for (const respond of g.waiting.splice(0)) respond({ status: g.status, result: g.result }).catch(() => {});
      }
    }
    for (const h of this.handles) h.close().catch(() => {});
    if (this.feedbackPub) this.feedbackPub.release();
    if (this.statusPub) this.statusPub.release();
  }
}
