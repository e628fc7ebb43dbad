"""A wall-clock limit on each FMI call of a run (``step_timeout``): instantiation,
initialisation, each step, each read or write, terminating and freeing, for third-party FMUs
that may hang.

A call stuck in an FMU's C code cannot be interrupted from Python, so a thread looks at the call
in progress (``busy()``: instance, FMI function, when it began) and, when one outlasts the limit,
hands the instance and function to ``expired`` (the master writes the cause and the results
there) and ends the process with STEP_TIMEOUT_STATUS. The hung instance is never terminated nor
freed: only the process's end releases it. An FMU that holds Python's GIL while it hangs would
block this thread too.
"""
from __future__ import annotations

import threading
import time
import traceback
from typing import Callable

from .interrupts import exit_without_finalising

STEP_TIMEOUT_STATUS = 124  # exit status after a step timeout, that of coreutils' timeout(1)
POLL_PERIOD = 0.5  # s, longest interval between two looks at the call in progress


class Watchdog:
    """Watches the FMI call in progress while entered: ``busy()`` -> (instance, FMI function,
    perf_counter() at its call [s]) or None between calls; ``limit`` [s] per call."""

    def __init__(self, busy: Callable[[], tuple[str, str, float] | None], limit: float,
                 expired: Callable[[str, str], None]):
        self.busy, self.limit, self.expired = busy, limit, expired
        self._done = threading.Event()
        self._thread = threading.Thread(target=self._watch, name="watchdog", daemon=True)

    def __enter__(self) -> "Watchdog":
        self._thread.start()
        return self

    def __exit__(self, *exc_info) -> None:
        self._done.set()
        self._thread.join()

    def _watch(self) -> None:
        period = min(POLL_PERIOD, self.limit / 10)
        while not self._done.wait(period):
            call = self.busy()
            if call is not None and time.perf_counter() - call[2] > self.limit:
                try:
                    self.expired(*call[:2])
                except BaseException:  # noqa: BLE001 - the process ends all the same
                    traceback.print_exc()
                exit_without_finalising(STEP_TIMEOUT_STATUS)
