"""SIGINT (Ctrl-C) and SIGTERM during a run: noted by a handler, acted on by the master between
steps, so that no FMU call is cut short (a pythonfmu FMU runs its Python code in the master's
thread, where Python's default handler would raise KeyboardInterrupt inside the FMU), and ending a
process that has loaded FMUs."""
from __future__ import annotations

import os
import signal
import sys
import threading
from typing import NoReturn

SIGNALS = (signal.SIGINT, signal.SIGTERM)


class StopRequested(Exception):
    """A signal asked the run to stop; ``time`` [s] is where the instances are (None: still
    initialising)."""

    def __init__(self, signum: int, time: float | None):
        self.signal, self.time = signum, time
        super().__init__(f"interrupted by {signal.Signals(signum).name}")


class StopRequests:
    """While entered (in the main thread; elsewhere it does nothing), SIGINT and SIGTERM are
    noted in ``signal`` instead of acting; :meth:`check` raises StopRequested once one came. A
    second signal of the same kind takes its default action at once (for an FMU that never
    returns). Signals a parent set to be ignored stay ignored, and so do handlers installed
    outside Python (they could not be restored). Leaving restores the handlers."""

    def __init__(self):
        self.signal: int | None = None
        self._previous: dict[int, object] = {}

    def __enter__(self) -> "StopRequests":
        if threading.current_thread() is threading.main_thread():
            for s in SIGNALS:
                if signal.getsignal(s) not in (signal.SIG_IGN, None):
                    self._previous[s] = signal.signal(s, self._note)
        return self

    def __exit__(self, *exc_info) -> None:
        for s, handler in self._previous.items():
            signal.signal(s, handler)

    def _note(self, signum, frame) -> None:
        self.signal = self.signal or signum
        signal.signal(signum, signal.SIG_DFL)

    def check(self, time: float | None) -> None:
        """Raise StopRequested if a signal came; ``time`` [s] as for StopRequested."""
        if self.signal is not None:
            raise StopRequested(self.signal, time)


def exit_without_finalising(code: int) -> NoReturn:
    """Flush stdout and stderr and end the process with ``code``, skipping the interpreter's
    finalisation. Our FMUs exit cleanly (fmu_build/exit_patch.py, components/runtime.py); an
    FMU built by plain pythonfmu 0.7 carries its exit-time use-after-free, which corrupts the
    heap of a Python host in a few per cent of runs after every output has been written.
    Only for a program's last statement: nothing after it runs, no atexit handler either."""
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)
