# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The `tests` key of a package rule (recipes/schema.md): its tests in WebAssembly.

    packages:
      rcutils:
        tests:
          not-built: its tests need mimick_vendor (...)
      rcl:
        tests:
          not-applicable:
            test_signal_handler*: installs a SIGINT handler; ...

* `not-built`: the reason why `--wasm-tests` without package names leaves this
  package's tests unbuilt (naming the package still builds them);
* `not-applicable`: test names (CTest names, globs) that `colcon test --wasm`
  does not run, each with the reason; the results list them as skipped with
  that reason.
"""

from fnmatch import fnmatchcase

TESTS_KEYS = ('not-built', 'not-applicable')


class TestsRule:
    """What the recipe says about a package's tests."""

    __test__ = False  # not a pytest class

    def __init__(self):
        """Create an empty rule: tests are built and every test runs."""
        self.not_built = None
        self.not_applicable = {}

    def merge(self, other):
        """Add an overlay's rule (`not-built` replaces, `not-applicable` is updated)."""
        if other.not_built is not None:
            self.not_built = other.not_built
        self.not_applicable.update(other.not_applicable)

    def unlisted_not_applicable(self, test_names):
        """
        Get the not-applicable tests CTest does not list (they were not built).

        Only exact names (no glob characters) can be reported without a test
        of that name: {name: reason}.
        """
        return {name: reason for name, reason in self.not_applicable.items()
                if name not in test_names and not any(c in name for c in '*?[')}

    def not_applicable_reason(self, test_name):
        """Get why a test is not run in WebAssembly, or None when it is run."""
        if test_name in self.not_applicable:
            return self.not_applicable[test_name]
        for pattern, reason in self.not_applicable.items():
            if fnmatchcase(test_name, pattern):
                return reason
        return None


def check_tests_rule(path, parent, dotted, value, *, fail, check_keys, check_string,
                     check_mapping):
    """
    Check a package's `tests` mapping.

    The schema helpers of :mod:`colcon_wasm.recipe.spec` are passed in, so
    that errors read like every other recipe error (file, line, key).

    :returns: the :class:`TestsRule`
    """
    check_mapping(path, parent, 'tests', dotted, value)
    check_keys(path, value, f'{dotted}.', TESTS_KEYS)
    rule = TestsRule()
    if 'not-built' in value:
        rule.not_built = check_string(
            path, value, 'not-built', f'{dotted}.not-built', value['not-built'])
    if 'not-applicable' in value:
        mapping = value['not-applicable']
        check_mapping(path, value, 'not-applicable', f'{dotted}.not-applicable', mapping)
        for name, reason in mapping.items():
            key = f'{dotted}.not-applicable.{name}'
            if not isinstance(name, str) or not name.strip():
                fail(path, mapping, name, key, 'expected a test name or glob')
            rule.not_applicable[name] = check_string(path, mapping, name, key, reason)
    return rule
