// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * Walking message values by field path (`pose.position.x`, `ranges[3]`), for
 * plots and forms. Paths are found from the type descriptions (cdr.mjs).
 */

const NUMERIC = new Set([
  'byte', 'char', 'int8', 'uint8', 'int16', 'uint16', 'int32', 'uint32', 'int64', 'uint64',
  'float32', 'float64', 'bool',
]);

/**
 * The paths of the numeric scalar fields of a message type, nested ones
 * included, and elements of fixed arrays up to `maxArray` elements.
 */
export function numericPaths(registry, type, { maxArray = 16 } = {}) {
  const out = [];
  const visit = (typeName, prefix, depth) => {
    if (depth > 8) return;
    for (const field of registry.message(typeName).fields) {
      const path = prefix ? `${prefix}.${field.name}` : field.name;
      if (field.sequence) continue;
      const size = field.array_size;
      if (NUMERIC.has(field.type)) {
        if (size === undefined) out.push(path);
        else if (size <= maxArray) for (let i = 0; i < size; i++) out.push(`${path}[${i}]`);
      } else if (field.type.includes('/') && size === undefined) {
        visit(field.type, path, depth + 1);
      }
    }
  };
  visit(type, '', 0);
  return out.filter((p) => !p.endsWith('structure_needs_at_least_one_member'));
}

const compiled = new Map();

/** Read the value at a field path; undefined when it is not there. */
export function getPath(value, path) {
  let steps = compiled.get(path);
  if (!steps) {
    steps = [];
    for (const part of path.split('.')) {
      const m = /^([^[\]]+)((\[\d+\])*)$/.exec(part);
      if (!m) throw new Error(`'${path}' is not a field path (e.g. pose.position.x or data[2])`);
      steps.push(m[1]);
      for (const index of m[2].matchAll(/\[(\d+)\]/g)) steps.push(Number(index[1]));
    }
    compiled.set(path, steps);
  }
  let v = value;
  for (const step of steps) {
    if (v === null || v === undefined) return undefined;
    v = v[step];
  }
  return v;
}

/** A number for plotting: BigInt and bool converted, anything else NaN. */
export function asNumber(v) {
  if (typeof v === 'number') return v;
  if (typeof v === 'bigint') return Number(v);
  if (typeof v === 'boolean') return v ? 1 : 0;
  return NaN;
}
