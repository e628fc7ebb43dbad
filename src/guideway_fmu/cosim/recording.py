"""Recorded signals of a run, streamed to a CSV file with a units sidecar as they are recorded,
and read back (:func:`read`) only as the recorder wrote it."""
from __future__ import annotations

import csv
import io
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


class RecordingError(OSError):
    """The results file could not be written (a full disk, a file-size limit): the message
    names it and the rows it keeps."""


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
    description of the variable) go into the recording, for the plots' axis labels. Another
    thread may call :meth:`close` (the watchdog) while the run is stuck in an FMU.

    A write that fails (RecordingError, from the sample that flushed) leaves the file cut back
    to its last whole row and closed; the later rows stay in memory, and ``error`` keeps the
    failure. :meth:`stored` says what the file holds, for :func:`read`.
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
        self.path = None if path is None else Path(path)
        self._file = None
        self.error: RecordingError | None = None
        self._written, self._size, self._flushed = 0, 0, time.perf_counter()
        if self.path is not None:
            self.path.with_suffix(".units.json").write_text(
                json.dumps({"time": "s", **{n: units[n] for n in names}}, indent=1))
            self._file = self.path.open("wb", buffering=0)
            with self._lock:
                self._write([["time", *names]], 0)

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
        """Write the rows recorded since the last write to the file (no-op without one, or after
        a failed write); RecordingError if the write fails."""
        with self._lock:
            if self._file is None:
                return
            n, k = len(self._time), len(self.names)
            self._write(([self._time[i], *self._rows[i * k:(i + 1) * k]]
                         for i in range(self._written, n)), n - self._written)
            self._flushed = time.perf_counter()

    def _write(self, rows, count: int) -> None:
        """Append ``count`` CSV ``rows`` to the file, whole or not at all (with the lock held)."""
        text = io.StringIO(newline="")
        csv.writer(text).writerows(rows)
        encoded = text.getvalue().encode()
        data = memoryview(encoded)
        try:
            while data:
                data = data[self._file.write(data):]
        except OSError as exc:
            try:
                self._file.truncate(self._size)  # back to the last whole row
                self._file.close()
            except OSError:
                pass  # a part of a row stays: the size in stored() tells a reader
            self._file = None
            kept = (f"the first {self._written} rows of the run, to t = "
                    f"{self._time[self._written - 1]:.9g} s" if self._written else "no row")
            self.error = RecordingError(f"cannot write {self.path}: {exc.strerror or exc}; it "
                                        f"keeps {kept}")
            raise self.error from exc
        self._size += len(encoded)
        self._written += count

    def close(self) -> None:
        """Write the remaining rows and close the file; later rows stay in memory only. A failed
        write is kept in ``error``, not raised."""
        try:
            self.flush()
        except RecordingError:
            pass
        with self._lock:
            if self._file is not None:
                self._file.close()
                self._file = None

    def stored(self) -> dict | None:
        """What the results file holds: ``rows`` (without the header) and ``bytes``; None
        without a file."""
        if self.path is None:
            return None
        with self._lock:
            return {"rows": self._written, "bytes": self._size}

    def recording(self) -> Recording:
        rows, k = len(self._time), len(self.names)
        data = np.array(self._rows[:rows * k], dtype=float).reshape(rows, k)
        return Recording(np.array(self._time[:rows]), {n: data[:, i] for i, n in enumerate(self.names)},
                         {n: self.units[n] for n in self.names},
                         {n: self.descriptions[n] for n in self.names if n in self.descriptions})


def read(path: str | Path, rows: int, size: int) -> Recording:
    """The recording in the CSV file ``path`` that a Recorder reported to hold ``rows`` rows in
    ``size`` bytes (:meth:`Recorder.stored`), with the units of its sidecar; ValueError naming
    the file when it is not that (cut by a full disk or a file-size limit, changed since)."""
    path = Path(path)
    actual = path.stat().st_size
    if actual != size:
        raise ValueError(f"{path}: {actual} bytes, but the run wrote {size} ({rows} rows): the file "
                         "was cut (a full disk or a file-size limit?) or changed since")
    with path.open() as f:
        header = next(csv.reader([f.readline()]), [])
        try:
            data = (np.loadtxt(f, delimiter=",", ndmin=2) if rows else
                    np.empty((0, len(header))))
        except ValueError as exc:
            raise ValueError(f"{path}: not rows of numbers: {exc}") from None
    if data.shape != (rows, len(header)) or header[:1] != ["time"]:
        raise ValueError(f"{path}: {data.shape[0]} rows of {data.shape[1]} values under a header of "
                         f"{len(header)}, but the run wrote {rows} rows: the file was changed since")
    sidecar = path.with_suffix(".units.json")
    units = json.loads(sidecar.read_text()) if sidecar.is_file() else {}
    return Recording(data[:, 0], {n: data[:, i] for i, n in enumerate(header[1:], 1)},
                     {n: units.get(n, "") for n in header[1:]})
