// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// One display's subscription, kept matching the live graph: it subscribes
// when the topic has publishers, with their QoS (a latched /tf_static or
// /robot_description is heard as transient local), subscribes again when
// that QoS changes, and says why nothing comes (no publisher, another type,
// a type the install space does not describe) in rviz's words.

import { subscriptionQos } from '../../../wasm_js/page/graph.mjs';

function qosKey(qos) {
  return `${qos.reliability}/${qos.durability}`;
}

export class TopicFeed {
  /**
   * @param session the page's Session
   * @param {string} topic
   * @param {string} type e.g. sensor_msgs/msg/LaserScan (or a list of accepted types)
   * @param {(values: object[], type: string) => void} onMessages decoded messages, oldest first
   */
  constructor(session, topic, type, onMessages) {
    this.session = session;
    this.topic = topic;
    this.types = Array.isArray(type) ? type : [type];
    this.onMessages = onMessages;
    this.subscription = null;
    this.key = null;
    this.received = 0;
    this.problem = null;
    this.lastError = null;
    this.onGraph = (model) => this.follow(model);
    session.on('graph', this.onGraph);
    this.follow(session.graph);
  }

  /** Subscribe, re-subscribe or leave, as the topic's publishers say. */
  follow(model) {
    const entry = (model.topics || []).find((t) => t.name === this.topic);
    // the page's own publishers (the publish form, the pose tools) are left
    // out of the graph the views show; rviz hears them, and so does this
    const rawGraph = this.session.rawGraph;
    const raw = rawGraph ? (rawGraph.topics || []).find((t) => t.name === this.topic) : null;
    const publishers = raw ? raw.publishers.length : entry ? entry.publishers.length : 0;
    const offered = (entry && entry.types) || (raw && raw.types) || [];
    const type = offered.find((t) => this.types.includes(t)) || (offered.length ? null : this.types[0]);
    if (publishers === 0 && !(entry && entry.publishers.length)) {
      this.problem = `No publisher on ${this.topic}`;
      return;
    }
    if (!type) {
      this.problem = `${this.topic} is ${offered.join(', ')}, not ${this.types.join(' or ')}`;
      this.leave();
      return;
    }
    if (!this.session.registry.has(type)) {
      this.problem = `the install space has no description of ${type} (build its package)`;
      this.leave();
      return;
    }
    this.problem = null;
    const qos = subscriptionQos([...(entry ? entry.publisherQos : []),
      ...(raw ? raw.publishers.map((e) => e.qos).filter(Boolean) : [])]);
    const key = `${type}|${qosKey(qos)}`;
    if (key === this.key) return;
    this.leave();
    this.key = key;
    this.subscription = this.session.subscribe(this.topic, type, (batch) => {
      const values = [];
      for (const m of batch) {
        try {
          values.push(this.session.registry.decode(type, m.bytes));
        } catch (e) {
          this.lastError = `a message on ${this.topic} did not decode: ${e.message}`;
        }
      }
      this.received += values.length;
      if (values.length) this.onMessages(values, type);
    }, qos);
  }

  leave() {
    if (this.subscription) this.subscription.close();
    this.subscription = null;
    this.key = null;
  }

  /** {level, text} for the display's status line. */
  status() {
    if (this.problem) return { level: this.received ? 'warn' : 'error', text: this.problem };
    if (this.lastError) return { level: 'error', text: this.lastError };
    if (!this.received) return { level: 'warn', text: `No messages received on ${this.topic}` };
    return { level: 'ok', text: `${this.received} messages received` };
  }

  close() {
    this.session.off('graph', this.onGraph);
    this.leave();
  }
}
