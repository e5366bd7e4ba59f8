// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * BusError: the one error type of bus operations, with a wasm_cpp::Code.
 *
 * @module bus/errors
 */

import { Code } from '../abi/bus_abi.mjs';

export { Code };

/** An error of a bus operation, with a wasm_cpp::Code. */
export class BusError extends Error {
  /**
   * @param {number} code one of Code
   * @param {string} message what failed, where, and what to do
   */
  constructor(code, message) {
    super(message);
    this.name = 'BusError';
    this.code = code;
  }
}
