"""The Python module of an ament_cmake package."""


def shout(count):
    """Return the text of message ``count``."""
    return f'Hello from an ament_cmake_python package: {count}'
