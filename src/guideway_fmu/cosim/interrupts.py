"""SIGINT (Ctrl-C) and SIGTERM during a run: noted by a handler, acted on by the master between
steps, so that no FMU call is cut short (a pythonfmu FMU runs its Python code in the master's
thread, where Python's default handler would raise KeyboardInterrupt inside the FMU), and ending a
process that has loaded FMUs.

One signal always ends the run: a scheduler sends SIGTERM once. If the run has not stopped
GRACE_PERIOD after it (an FMU call that does not return), the process ends with 128 + the
signal's number, after the master wrote what it has. Python runs a signal's handler only
between bytecodes of the main thread, never while that thread is stuck in an FMU's C code, so a
thread of :class:`StopRequests` learns of the signal from the interpreter's wakeup file
(``signal.set_wakeup_fd``), which the C-level handler writes at once.
"""
from __future__ import annotations

import os
import signal
import sys
import threading
import traceback
from typing import Callable, NoReturn

SIGNALS = (signal.SIGINT, signal.SIGTERM)
GRACE_PERIOD = 5.0  # s from a stop signal to the process's end if the run has not stopped


class StopRequested(Exception):
    """A signal asked the run to stop; ``time`` [s] is where the instances are (None: still
    initialising)."""

    def __init__(self, signum: int, time: float | None):
        self.signal, self.time = signum, time
        super().__init__(f"interrupted by {signal.Signals(signum).name}")


class StopRequests:
    """While entered (in the main thread; elsewhere it does nothing), SIGINT and SIGTERM are
    noted in ``signal`` instead of acting; :meth:`check` raises StopRequested once one came. A
    second signal of the same kind takes its default action at once. If GRACE_PERIOD passes
    after the first before leaving, ``unstopped(signum)`` is called (in another thread) and the
    process ends with 128 + signum (module doc). Signals a parent set to be ignored stay
    ignored, and so do handlers installed outside Python (they could not be restored). Leaving
    restores the handlers."""

    def __init__(self, unstopped: Callable[[int], None] | None = None):
        self.signal: int | None = None
        self.unstopped = unstopped
        self._previous: dict[int, object] = {}
        self._left = threading.Event()
        self._wakeup: tuple[int, int] | None = None  # (the former wakeup fd, our pipe's end)

    def __enter__(self) -> "StopRequests":
        if threading.current_thread() is threading.main_thread():
            for s in SIGNALS:
                if signal.getsignal(s) not in (signal.SIG_IGN, None):
                    self._previous[s] = signal.signal(s, self._note)
            if self._previous:
                read, write = os.pipe()
                os.set_blocking(write, False)
                self._wakeup = signal.set_wakeup_fd(write, warn_on_full_buffer=False), write
                threading.Thread(target=self._grace, args=(read,), name="stop-grace",
                                 daemon=True).start()
        return self

    def __exit__(self, *exc_info) -> None:
        self._left.set()
        for s, handler in self._previous.items():
            signal.signal(s, handler)
        if self._wakeup is not None:
            former, write = self._wakeup
            signal.set_wakeup_fd(former)
            os.write(write, b"\0")  # ends the thread
            os.close(write)

    def _note(self, signum, frame) -> None:
        self.signal = self.signal or signum
        signal.signal(signum, signal.SIG_DFL)

    def _grace(self, read: int) -> None:
        """Wait for the first stop signal, then for leaving; end the process if that takes
        longer than GRACE_PERIOD."""
        try:
            while True:
                for signum in os.read(read, 64):
                    if signum == 0:  # left
                        return
                    if signum in SIGNALS and not self._left.wait(GRACE_PERIOD):
                        try:
                            if self.unstopped is not None:
                                self.unstopped(signum)
                        except BaseException:  # noqa: BLE001 - the process ends all the same
                            traceback.print_exc()
                        exit_without_finalising(128 + signum)
        finally:
            os.close(read)

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
