"""Recorded signals of a run, streamed to a CSV file with a units sidecar as they are recorded."""
from __future__ import annotations

import csv
import json
import threading
import time
from array import array
from operator import itemgetter
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .observers import Observer

# Rows reach the results file when FLUSH_ROWS of them wait or FLUSH_SECONDS of wall time passed
# since the last write, whichever comes first, and when the recorder is closed: a crash loses at
# most that much, and a run recording every one of 1e5 steps per second makes 100 writes per
# second, not 1e5 (one system call per row would cost as much as a cheap FMU's step).
FLUSH_ROWS = 1000
FLUSH_SECONDS = 1.0  # s of wall time


@dataclass
class Recording:
    """Recorded signals: ``time`` [s] and one column per ``<instance>.<variable>``, with its
    unit and the description its FMU gives the variable (may be missing)."""

    time: np.ndarray
    columns: dict[str, np.ndarray]
    units: dict[str, str]
    descriptions: dict[str, str] = field(default_factory=dict)


class Recorder(Observer):
    """Collects rows of values at the start, at accepted communication points at most one per
    ``interval`` [s], and at the stop time.

    With a ``path`` the rows also go to that CSV file (header ``time,<instance>.<variable>,...``)
    as the run goes (FLUSH_ROWS, FLUSH_SECONDS), and ``<name>.units.json`` beside it maps every
    column to its unit; :meth:`close` writes the rest. ``descriptions`` (column -> the FMU's
    description of the variable) go into the recording, for the plots' axis labels. Another thread may call :meth:`close`
    (the step watchdog) while the run is stuck in an FMU.
    """

    def __init__(self, names: list[str], units: dict[str, str], interval: float = 0.0,
                 path: str | Path | None = None, descriptions: dict[str, str] | None = None):
        self.names, self.units, self.interval = names, units, interval
        self.descriptions = descriptions or {}
        keys = [tuple(n.split(".", 1)) for n in names]
        # one row's values from the bus's values in one call (itemgetter gives a tuple from two)
        self._row = (itemgetter(*keys) if len(keys) > 1 else
                     lambda values: tuple(values[k] for k in keys))
        self._time = array("d")  # flat arrays: nothing for the garbage collector to traverse
        self._rows = array("d")
        self._next = -np.inf
        self._last = np.inf
        self._lock = threading.Lock()
        self._file = self._csv = None
        self._written, self._flushed = 0, time.perf_counter()
        if path is not None:
            path = Path(path)
            path.with_suffix(".units.json").write_text(
                json.dumps({"time": "s", **{n: units[n] for n in names}}, indent=1))
            self._file = path.open("w", newline="")
            self._csv = csv.writer(self._file)
            self._csv.writerow(["time", *names])
            self._file.flush()

    def started(self, system, bus):
        exp = system.experiment
        self._last = exp.stop - 1e-9 * exp.step  # a step ending beyond this is the last
        self._sample(exp.start, bus)

    def stepped(self, t, bus):
        if t >= self._next or t >= self._last:
            self._sample(t, bus)

    def _sample(self, t: float, bus) -> None:
        bus.observe()
        self._rows.extend(self._row(bus.values))
        self._time.append(t)  # after its row: a row counted in _time is complete
        self._next = t + self.interval * (1 - 1e-9)
        if self._file is not None and (len(self._time) - self._written >= FLUSH_ROWS
                                       or time.perf_counter() - self._flushed >= FLUSH_SECONDS):
            self.flush()

    def flush(self) -> None:
        """Write the rows recorded since the last write to the file (no-op without one)."""
        with self._lock:
            if self._file is None:
                return
            n, k = len(self._time), len(self.names)
            self._csv.writerows([self._time[i], *self._rows[i * k:(i + 1) * k]]
                                for i in range(self._written, n))
            self._file.flush()
            self._written, self._flushed = n, time.perf_counter()

    def close(self) -> None:
        """Write the remaining rows and close the file; later rows stay in memory only."""
        self.flush()
        with self._lock:
            if self._file is not None:
                self._file.close()
                self._file = None

    def recording(self) -> Recording:
        rows, k = len(self._time), len(self.names)
        data = np.array(self._rows[:rows * k], dtype=float).reshape(rows, k)
        return Recording(np.array(self._time[:rows]), {n: data[:, i] for i, n in enumerate(self.names)},
                         {n: self.units[n] for n in self.names},
                         {n: self.descriptions[n] for n in self.names if n in self.descriptions})
