"""Ending a process that has loaded FMUs."""
from __future__ import annotations

import os
import sys
from typing import NoReturn


def exit_without_finalising(code: int) -> NoReturn:
    """Flush stdout and stderr and end the process with ``code``, skipping the interpreter's
    finalisation: there, pythonfmu 0.7 with SciPy's LAPACK loaded sometimes aborts the process
    ('corrupted double-linked list', SIGSEGV) after every output has been written (issue 21).
    Only for a program's last statement: nothing after it runs, no atexit handler either."""
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)
