# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
A bag's written pages, let go of as the recording goes.

A camera topic grows a bag by tens of MB a second. Kept in the page cache,
those pages push out what the user's other programs had there, and on a
virtual machine whose balloon takes freed memory back (the project's CI
machine) each new page costs a fault in the host: writing 28 MB/s into a
new file cost 8 % of one core in the kernel there, against 1.7 % when the
pages written were let go of 16 MiB behind the writer (bench/record).

``posix_fadvise(POSIX_FADV_DONTNEED)`` starts the writeback of a range and
drops its pages that are already on the disk. Dirty pages are never
dropped, so nothing is lost; a later call, over the range again, drops
them once written back. The next pages the writer needs are the ones just
freed, still in the host's memory.
"""

import os

STEP = 16 * 1024 * 1024
LAG = 16 * 1024 * 1024
# a later call goes over this many steps before its start again: the pages
# whose writeback was not done at the earlier call
_RETRY_STEPS = 4


class WrittenPages:
    """The written part of one file, let go of from the page cache behind its writer."""

    def __init__(self, fd, *, step=STEP, lag=LAG):
        """
        Follow the file `fd`.

        :param fd: the file, written from its start towards its end
        :param step: ask again once this much more is written
        :param lag: keep the last this many bytes written (the writer may
          still be in them, the summary reads none of them back)
        """
        self.fd = fd
        self.step = step
        self.lag = lag
        self._asked_at = 0
        self._dropped_to = 0
        self._on = hasattr(os, 'posix_fadvise')

    def wrote_up_to(self, end):
        """Note that the file is written up to ``end``; let go of the pages far enough behind."""
        if not self._on or end - self._asked_at < self.step:
            return
        self._asked_at = end
        upto = end - self.lag
        start = max(0, self._dropped_to - _RETRY_STEPS * self.step)
        if upto <= start:
            return
        try:
            os.posix_fadvise(self.fd, start, upto - start, os.POSIX_FADV_DONTNEED)
        except OSError:
            # a file the kernel gives no advice on (a pipe, some FUSE file
            # systems): its pages stay, as any file's
            self._on = False
            return
        self._dropped_to = upto
