// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// A form for a message value (publish, service request, action goal):
// one input per field, or the whole message as YAML/JSON text.

import { formatYaml, parseYaml } from '../../wasm_js/page/yaml.mjs';
import { toPlain } from '../../wasm_js/cdr.mjs';
import { h, setChildren } from '../dom.mjs';

const INTEGER = new Set(['byte', 'char', 'int8', 'uint8', 'int16', 'uint16', 'int32', 'uint32']);
const BIG = new Set(['int64', 'uint64']);
const FLOAT = new Set(['float32', 'float64']);

function typeLabel(field) {
  let t = field.type.replace('/msg/', '/');
  if (field.string_bound) t += `<=${field.string_bound}`;
  if (field.array_size !== undefined) t += `[${field.array_size}]`;
  else if (field.sequence) t += field.sequence_bound ? `[<=${field.sequence_bound}]` : '[]';
  return t;
}

function flowYaml(value) {
  // arrays in one line: [1, 2, 3]; messages in arrays as {a: 1}
  const plain = toPlain(value);
  return JSON.stringify(plain, null, 0).replace(/"([A-Za-z_][A-Za-z0-9_]*)":/g, '$1: ').replace(/,/g, ', ');
}

export class MessageForm {
  constructor(registry, type, { initial } = {}) {
    this.registry = registry;
    this.type = type;
    this.mode = 'fields';
    this.inputs = null;
    this.body = h('div.form-body');
    this.error = h('div.error-text');
    this.textarea = h('textarea.yaml-input', { spellcheck: false, 'aria-label': `${type} as YAML` });
    this.fieldsButton = h('button.active', { onclick: () => this.setMode('fields') }, 'Fields');
    this.yamlButton = h('button', { onclick: () => this.setMode('yaml') }, 'YAML / JSON');
    this.element = h('div.message-form', { dataset: { type } },
      h('div.form-mode.subtabs', {}, this.fieldsButton, this.yamlButton,
        h('button.link', { onclick: () => this.reset() }, 'reset')),
      this.body, this.error);
    this.setValue(initial ?? registry.create(type));
  }

  reset() {
    this.error.textContent = '';
    this.setValue(this.registry.create(this.type));
  }

  setMode(mode) {
    if (mode === this.mode) return;
    this.error.textContent = '';
    let value;
    try {
      value = this.getValue();
    } catch (e) {
      this.error.textContent = e.message;
      return;
    }
    this.mode = mode;
    this.fieldsButton.classList.toggle('active', mode === 'fields');
    this.yamlButton.classList.toggle('active', mode === 'yaml');
    this.setValue(value);
  }

  setValue(value) {
    if (this.mode === 'yaml') {
      this.textarea.value = formatYaml(value, { maxArray: Infinity });
      setChildren(this.body, this.textarea);
      return;
    }
    this.inputs = [];
    setChildren(this.body, this.fields(this.type, value, ''));
  }

  fields(type, value, prefix) {
    const out = [];
    for (const field of this.registry.message(type).fields) {
      if (field.name === 'structure_needs_at_least_one_member') continue;
      const path = prefix ? `${prefix}.${field.name}` : field.name;
      const v = value ? value[field.name] : undefined;
      const collection = field.array_size !== undefined || field.sequence;
      if (!collection && field.type.includes('/')) {
        out.push(h('fieldset.msg', {}, h('legend', {}, `${field.name}: ${typeLabel(field)}`),
          this.fields(field.type, v, path)));
        continue;
      }
      let input;
      let read;
      if (collection) {
        input = h('input', { type: 'text', value: flowYaml(v ?? []), spellcheck: false });
        read = () => {
          const parsed = parseYaml(input.value);
          if (!Array.isArray(parsed)) throw new Error(`${path}: write a list, e.g. [1, 2, 3]`);
          return parsed;
        };
      } else if (field.type === 'bool') {
        input = h('input', { type: 'checkbox', checked: Boolean(v) });
        read = () => input.checked;
      } else if (INTEGER.has(field.type) || FLOAT.has(field.type)) {
        input = h('input', { type: 'number', step: FLOAT.has(field.type) ? 'any' : '1', value: String(v ?? 0) });
        read = () => {
          if (input.value.trim() === '') throw new Error(`${path}: enter a number`);
          return Number(input.value);
        };
      } else if (BIG.has(field.type)) {
        input = h('input', { type: 'text', value: String(v ?? 0), inputmode: 'numeric' });
        read = () => input.value.trim();
      } else {
        input = h('input', { type: 'text', value: v ?? '', spellcheck: false });
        read = () => input.value;
      }
      input.dataset.field = path;
      this.inputs.push({ path, read });
      out.push(h('div.field', {}, h('label', { title: path }, field.name, h('span.ftype', {}, typeLabel(field))), input));
    }
    if (out.length === 0) out.push(h('div.note', {}, 'This message has no fields.'));
    return out;
  }

  /** The message value; throws an Error naming the field when input is bad. */
  getValue() {
    if (this.mode === 'yaml') {
      const value = parseYaml(this.textarea.value);
      if (value === null || typeof value !== 'object' || Array.isArray(value)) {
        throw new Error(`write the ${this.type} message as a mapping, e.g. {field: value}`);
      }
      return value;
    }
    const value = {};
    for (const { path, read } of this.inputs) {
      const parts = path.split('.');
      let target = value;
      for (const p of parts.slice(0, -1)) target = target[p] ?? (target[p] = {});
      target[parts[parts.length - 1]] = read();
    }
    return value;
  }

  /** The CDR bytes of the value; shows and rethrows errors. */
  encode() {
    this.error.textContent = '';
    try {
      return this.registry.encode(this.type, this.getValue());
    } catch (e) {
      this.error.textContent = e.message;
      throw e;
    }
  }
}
