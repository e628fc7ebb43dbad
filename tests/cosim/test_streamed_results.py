"""The recorder writes results.csv as the run goes (recording.py: FLUSH_ROWS, FLUSH_SECONDS), so
that an interrupted or crashed run keeps what it computed; the finished file is the one written
at the end before: header ``time,<instance>.<variable>``, one CSV row per sample."""
from __future__ import annotations

import csv
import io
import json

import numpy as np
import pytest

from guideway_fmu.cosim import master, observers, recording, system


class DiskWatcher(observers.Observer):
    """Counts, after every step, the rows recorded so far and the data rows in the file."""

    def __init__(self, path):
        self.path, self.seen = path, []

    def stepped(self, t, bus):
        recorded = round(t / 0.001) + 1  # a sample at start and after every step
        on_disk = len(self.path.read_text().splitlines()) - 1
        self.seen.append((recorded, on_disk))


@pytest.mark.parametrize("knob, value, expected", [
    ("FLUSH_ROWS", 5, lambda recorded: recorded - recorded % 5),
    ("FLUSH_SECONDS", 0.0, lambda recorded: recorded),
])
def test_rows_reach_the_file_during_the_run_and_it_ends_in_the_former_format(
        faulty, tmp_path, monkeypatch, knob, value, expected):
    monkeypatch.setattr(recording, "FLUSH_ROWS", 10**9)
    monkeypatch.setattr(recording, "FLUSH_SECONDS", 1e9)
    monkeypatch.setattr(recording, knob, value)
    s = (system.Builder("stream").experiment(stop=0.03, step=0.001, algorithm="jacobi")
         .component("P", faulty, fault="none").system())
    path = tmp_path / "results.csv"
    watcher = DiskWatcher(path)
    rec = master.simulate(s, observers=(watcher,), results=path).recording
    assert len(watcher.seen) == 30
    assert all(on_disk == expected(recorded) for recorded, on_disk in watcher.seen), watcher.seen
    former = io.StringIO(newline="")  # how results.csv was written after the run before
    writer = csv.writer(former)
    writer.writerow(["time", "P.x"])
    writer.writerows(np.column_stack([rec.time, rec.columns["P.x"]]).tolist())
    assert path.read_bytes() == former.getvalue().encode()
    assert len(rec.time) == 31 and rec.columns["P.x"][-1] == pytest.approx(0.03)
    assert json.loads(path.with_suffix(".units.json").read_text()) == {"time": "s", "P.x": ""}
