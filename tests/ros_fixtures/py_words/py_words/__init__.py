"""Words of py_chatter's nodes, from another package of the install space."""


def greeting(count):
    """Return the talker's text for message number ``count``."""
    return f'Hello from a Python package: {count}'
