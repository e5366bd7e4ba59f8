// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Actions: the live list and a goal form with feedback, result and cancel.

import { ActionClient } from '../../wasm_js/page/ros_clients.mjs';
import { formatYaml } from '../../wasm_js/page/yaml.mjs';
import { breakable, h, setChildren, WHOLE_NAME } from '../dom.mjs';
import { MessageForm } from './message_form.mjs';

export class ActionsView {
  constructor(session) {
    this.title = 'Actions';
    this.session = session;
    this.selected = null;
    this.table = h('tbody');
    this.detail = h('div');
    this.element = h('section.view', { dataset: { view: 'actions' } },
      h('div.split', {},
        h('div.card', {}, h('h3', {}, 'Actions'),
          h('table.list', {}, h('thead', {}, h('tr', {}, h('th', {}, 'Name'), h('th', {}, 'Type'),
            h('th', { title: 'action servers' }, 'Srv'), h('th', { title: 'action clients' }, 'Cli'))), this.table)),
        this.detail));
    session.on('graph', (model) => this.render(model));
    this.render(session.graph);
  }

  render(model) {
    setChildren(this.table, model.actions.length ? model.actions.map((a) => h(`tr.clickable${this.selected === a.name ? '.selected' : ''}`, {
      dataset: { action: a.name }, onclick: () => this.select(a),
    }, h('td.name', {}, breakable(a.name, WHOLE_NAME)), h('td.type', {}, breakable(a.type)), h('td.num', {}, String(a.servers)),
    h('td.num', {}, String(a.clients)))) : h('tr', {}, h('td.empty', { colSpan: 4 }, 'No action servers.')));
    if (!this.selected) setChildren(this.detail, h('div.card.note', {}, 'Select an action to send it a goal.'));
  }

  select(action) {
    this.selected = action.name;
    setChildren(this.detail, new GoalPanel(this.session, action).element);
    this.render(this.session.graph);
  }
}

class GoalPanel {
  constructor(session, action) {
    this.session = session;
    this.action = action;
    let client = null;
    let problem = null;
    try {
      client = new ActionClient(session.toolsBus(), session.registry, action.name, action.type);
      session.registry.service('action_msgs/srv/CancelGoal');
    } catch (e) {
      problem = e.message;
    }
    if (!client) {
      this.element = h('div.card', {}, h('h3', {}, action.name, h('span.type', {}, action.type)),
        h('div.note', {}, `Goals cannot be sent: ${problem}`));
      return;
    }
    this.client = client;
    this.form = new MessageForm(session.registry, client.spec.goal);
    this.sendButton = h('button.primary', { onclick: () => this.send() }, 'Send goal');
    this.cancelButton = h('button.stop', { disabled: true, onclick: () => this.cancel() }, 'Cancel goal');
    this.state = h('div.note');
    this.feedback = h('div.echo-list', { style: { maxHeight: '30vh' } });
    this.result = h('div');
    this.element = h('div.card.goal-panel', { dataset: { goal: action.name } },
      h('h3', {}, action.name, h('span.type', {}, action.type)),
      h('div.note', {}, 'Goal'), this.form.element,
      h('div.actions-row', {}, this.sendButton, this.cancelButton), this.state,
      h('div.note', { style: { marginTop: '8px' } }, 'Feedback'), this.feedback, this.result);
  }

  async send() {
    let goal;
    try { goal = this.form.getValue(); this.session.registry.encode(this.client.spec.goal, goal); } catch (e) {
      this.form.error.textContent = e.message;
      return;
    }
    setChildren(this.feedback);
    setChildren(this.result);
    this.sendButton.disabled = true;
    this.state.textContent = 'sending the goal…';
    let count = 0;
    try {
      const sent = await this.client.sendGoal(goal, {
        onFeedback: (value) => {
          count++;
          this.feedback.prepend(h('div.echo-msg', {}, h('div.meta', {}, `feedback #${count}`), h('pre.yaml', {}, formatYaml(value))));
          while (this.feedback.childElementCount > 30) this.feedback.lastElementChild.remove();
        },
      });
      if (!sent.accepted) {
        this.state.textContent = 'the goal was rejected by the server';
        return;
      }
      this.handle = sent.handle;
      this.cancelButton.disabled = false;
      this.state.textContent = `goal ${sent.handle.id.slice(0, 8)} accepted, executing…`;
      const outcome = await sent.result;
      this.state.textContent = `goal ${sent.handle.id.slice(0, 8)} finished: ${outcome.statusText}`;
      setChildren(this.result, h(`div.result${outcome.statusText === 'SUCCEEDED' ? '' : '.error'}`, { dataset: { result: this.action.name } },
        h('div', {}, `Result (${outcome.statusText})`), h('pre.yaml', {}, formatYaml(outcome.result))));
    } catch (e) {
      this.state.textContent = '';
      setChildren(this.result, h('div.result.error', {}, h('div.error-text', {}, e.message)));
    } finally {
      this.sendButton.disabled = false;
      this.cancelButton.disabled = true;
    }
  }

  async cancel() {
    if (!this.handle) return;
    try {
      const response = await this.handle.cancel();
      this.state.textContent = response.return_code === 0 ? 'cancel requested' : `cancel refused (code ${response.return_code})`;
    } catch (e) {
      this.state.textContent = `cancel failed: ${e.message}`;
    }
  }
}
