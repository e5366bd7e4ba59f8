# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Node loggers: rcutils' console format, ``[INFO] [sec.nsec] [name]: text``."""

import enum
import sys
import time


class LoggingSeverity(enum.IntEnum):
    """Severities, with rcutils' values."""

    UNSET = 0
    DEBUG = 10
    INFO = 20
    WARN = 30
    ERROR = 40
    FATAL = 50


class RcutilsLogger:
    """A named logger: INFO and DEBUG on stdout, WARN and above on stderr."""

    def __init__(self, name=''):
        """Create a logger; ``name`` is shown in each line."""
        self.name = name
        self._level = LoggingSeverity.INFO

    def get_child(self, name):
        """Return the logger ``<this>.<name>``."""
        return RcutilsLogger(f'{self.name}.{name}' if self.name else name)

    def set_level(self, level):
        """Set the lowest severity logged."""
        self._level = LoggingSeverity(level)

    def get_effective_level(self):
        """Return the lowest severity logged."""
        return self._level

    def is_enabled_for(self, severity):
        """Return True when messages of this severity are logged."""
        return LoggingSeverity(severity) >= self._level

    def log(self, message, level, **kwargs):
        """Log ``message`` at ``level``; returns True when it was printed."""
        level = LoggingSeverity(level)
        if not self.is_enabled_for(level):
            return False
        now = time.time_ns()
        line = f'[{level.name}] [{now // 10 ** 9}.{now % 10 ** 9:09d}] [{self.name}]: {message}'
        stream = sys.stderr if level >= LoggingSeverity.WARN else sys.stdout
        print(line, file=stream, flush=True)
        return True

    def debug(self, message, **kwargs):
        """Log at DEBUG."""
        return self.log(message, LoggingSeverity.DEBUG, **kwargs)

    def info(self, message, **kwargs):
        """Log at INFO."""
        return self.log(message, LoggingSeverity.INFO, **kwargs)

    def warning(self, message, **kwargs):
        """Log at WARN."""
        return self.log(message, LoggingSeverity.WARN, **kwargs)

    warn = warning

    def error(self, message, **kwargs):
        """Log at ERROR."""
        return self.log(message, LoggingSeverity.ERROR, **kwargs)

    def fatal(self, message, **kwargs):
        """Log at FATAL."""
        return self.log(message, LoggingSeverity.FATAL, **kwargs)


def get_logger(name):
    """Return a logger by name."""
    return RcutilsLogger(name)
