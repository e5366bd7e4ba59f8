// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * Complete message definitions in rosbag2's `ros2msg` schema encoding, for
 * the page's recorder: the type's own `.msg` text, then each type it uses
 * (recursively, each once, depth first, the dependencies of one definition
 * sorted) after a line of 80 `=` and `MSG: pkg/Type`, as rosbag2's
 * `MessageDefinitionCache::get_full_text` writes them. A port of
 * colcon_wasm/ros2msg.py (the text of `colcon-wasm record` and serve's
 * recorder), from the same `definition` texts of the install's types.json
 * documents; tests/test_mcap_page.py checks that both give the same text.
 *
 * @module page/ros2msg
 */

/** The line between two definitions (followed by `MSG: pkg/Type`). */
export const DELIMITER = '='.repeat(80);

const KINDS = ['msg', 'srv', 'action'];

/** A type whose complete definition cannot be assembled (named in the text). */
export class SchemaError extends Error {
  constructor(message) {
    super(message);
    this.name = 'SchemaError';
  }
}

/**
 * `pkg/Type`, as `.msg` files and rosbag2's delimiters name a type.
 * @param {string} typeName `pkg/msg/Type`
 */
export function shortName(typeName) {
  const parts = typeName.split('/');
  return parts.length === 3 ? `${parts[0]}/${parts[2]}` : typeName;
}

/** The complete definitions of the messages of some types.json documents. */
export class Ros2MsgSchemas {
  /** @param {Object<string, object>} messages `{'pkg/msg/Type': description}` as types.json holds them */
  constructor(messages) {
    this.messages = new Map(Object.entries(messages));
    this.cache = new Map();
  }

  /**
   * Collect the messages of several types.json documents.
   * @param {object[]} documents
   */
  static fromDocuments(documents) {
    const messages = {};
    for (const document of documents) Object.assign(messages, document.messages || {});
    return new Ros2MsgSchemas(messages);
  }

  /**
   * The full name of a type named `pkg/Type` or `pkg/msg/Type`, or null when no document describes it.
   * @param {string} name
   */
  resolve(name) {
    if (this.messages.has(name)) return name;
    const parts = name.split('/');
    if (parts.length === 2) {
      for (const kind of KINDS) {
        const candidate = `${parts[0]}/${kind}/${parts[1]}`;
        if (this.messages.has(candidate)) return candidate;
      }
    }
    return null;
  }

  _description(name, neededBy) {
    const full = this.resolve(name);
    if (full === null) {
      const where = neededBy ? ` (used by '${neededBy}')` : '';
      throw new SchemaError(`no type description of '${name}'${where}: build its interface package `
        + 'with `colcon build --wasm`, or add it to the install chain');
    }
    const description = this.messages.get(full);
    if (!('definition' in description)) {
      throw new SchemaError(`the type description of '${full}' has no definition text (written by an `
        + 'older colcon-wasm): rebuild its package with `colcon build --wasm`');
    }
    return [full, description];
  }

  /**
   * The full names of the message types a type's fields use, sorted by their short names.
   * @param {string} name
   */
  dependencies(name) {
    const [, description] = this._description(name, null);
    const used = new Set();
    for (const field of description.fields || []) {
      if (field.type.split('/').length === 3) used.add(field.type);
    }
    const key = (t) => shortName(t);
    return [...used].sort((a, b) => (key(a) < key(b) ? -1 : key(a) > key(b) ? 1 : 0));
  }

  /**
   * The complete definition of a type, as rosbag2 writes it.
   * @param {string} name `pkg/msg/Type` or `pkg/Type`
   * @throws {SchemaError} naming the type (and its user) with no description
   */
  fullText(name) {
    const [root] = this._description(name, null);
    if (this.cache.has(root)) return this.cache.get(root);
    const parts = [];
    const seen = new Set([root]);
    const append = (type, neededBy) => {
      const [full, description] = this._description(type, neededBy);
      if (parts.length) parts.push(`\n${DELIMITER}\nMSG: ${shortName(full)}\n`);
      parts.push(description.definition);
      for (const dependency of this.dependencies(full)) {
        if (!seen.has(dependency)) {
          seen.add(dependency);
          append(dependency, full);
        }
      }
    };
    append(root, null);
    const text = parts.join('');
    this.cache.set(root, text);
    return text;
  }
}
