"""A wall-clock limit on each fmi2DoStep (``step_timeout``), for third-party FMUs that may hang.

A call stuck in an FMU's C code cannot be interrupted from Python, so a thread watches the
instances (``FmuInstance.stepping``) and, when one call outlasts the limit, hands the name and
time to ``expired`` (the master writes the cause and the results there) and ends the process
with STEP_TIMEOUT_STATUS. The hung instance is never terminated nor freed: only the process's
end releases it. An FMU that holds Python's GIL while it hangs would block this thread too.
"""
from __future__ import annotations

import threading
import time
import traceback
from typing import Callable

from .interrupts import exit_without_finalising

STEP_TIMEOUT_STATUS = 124  # exit status after a step timeout, that of coreutils' timeout(1)
POLL_PERIOD = 0.5  # s, longest interval between two looks at the instances


class StepWatchdog:
    """Watches ``instances`` ({name: FmuInstance}) while entered; ``limit`` [s] per doStep."""

    def __init__(self, instances: dict, limit: float, expired: Callable[[str, float], None]):
        self.instances, self.limit, self.expired = instances, limit, expired
        self._done = threading.Event()
        self._thread = threading.Thread(target=self._watch, name="step-watchdog", daemon=True)

    def __enter__(self) -> "StepWatchdog":
        self._thread.start()
        return self

    def __exit__(self, *exc_info) -> None:
        self._done.set()
        self._thread.join()

    def _watch(self) -> None:
        period = min(POLL_PERIOD, self.limit / 10)
        while not self._done.wait(period):
            now = time.perf_counter()
            for name, inst in self.instances.items():
                stepping = inst.stepping
                if stepping is not None and now - stepping[1] > self.limit:
                    try:
                        self.expired(name, stepping[0])
                    except BaseException:  # noqa: BLE001 - the process ends all the same
                        traceback.print_exc()
                    exit_without_finalising(STEP_TIMEOUT_STATUS)
