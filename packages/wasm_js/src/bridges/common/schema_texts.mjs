// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The complete definitions of the install's message types, as rosbag2
 * writes them (the `ros2msg` schema encoding: the type's text, then each
 * type it uses after a line of 80 `=` and `MSG: pkg/Type`). The launcher
 * assembles them (colcon_wasm/launch/foxglove.py, `schema_texts`) into a
 * JSON file for the host's run; the Foxglove server advertises them as
 * channel schemas, the rosbridge server answers rosapi's
 * `topics_and_raw_types` with them.
 *
 * @module bridges/common/schema_texts
 */

import { readFileSync } from 'node:fs';

/**
 * Read the schema texts of the plan.
 * @param {?string} path the launcher's JSON file; none gives no texts
 * @returns {{messages: Object<string, string>, errors: Object<string, string>}}
 *   the texts by full type name, and why a type has none
 * @throws {Error} naming the file when it cannot be read
 */
export function loadSchemas(path) {
  if (!path) return { messages: {}, errors: {} };
  try {
    const data = JSON.parse(readFileSync(path, 'utf-8'));
    return { messages: data.messages || {}, errors: data.errors || {} };
  } catch (e) {
    throw new Error(`cannot read the schema texts ${path}: ${e.message}`);
  }
}

/**
 * The complete definition of a type, or rosapi's comment on why there is none.
 * @param {{messages: object, errors: object}} schemas
 * @param {string} type `pkg/msg/Type`
 */
export function fullText(schemas, type) {
  const text = schemas.messages[type];
  if (text !== undefined) return text;
  const why = schemas.errors[type] || `no type description of '${type}' in the install`;
  return `# failed to get full definition text for ${type}: ${why}`;
}
