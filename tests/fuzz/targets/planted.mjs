// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * A target with planted bugs, for the test that the runner reports them
 * (tests/test_fuzz.py): an input with a NUL byte throws out of the
 * handler; one with a 0xff byte breaks the instance, so that the next check
 * fails. A runner that missed either would pass everything.
 */

export const options = { json: false };

export async function setup() {
  let broken = false;
  return {
    one(input) {
      if (input.includes(0)) throw new TypeError('a planted bug: a NUL byte');
      if (input.includes(0xff)) broken = true;
      return 'ok';
    },
    check() {
      if (broken) {
        broken = false;
        throw new Error('a planted bug: the instance was left broken');
      }
    },
  };
}
