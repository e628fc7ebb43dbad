"""The results table of a sweep: results.csv, one row per finished point, appended and flushed
as each point finishes (a killed sweep loses no finished point); results.json rebuilt from it.

Columns: ``point`` (the point's id), the swept parameters, the reduced outputs (empty for a
failed point), ``status`` ("ok" or "failed"), ``attempts``, ``wall_time_s`` (of the last
attempt, on its worker), ``error`` (the failed point's last error).
"""
from __future__ import annotations

import csv
import io
import json
import math
import os
from pathlib import Path

from .sweep_file import Sweep

TAIL = ("status", "attempts", "wall_time_s", "error")


def header(sweep: Sweep) -> list[str]:
    return ["point", *sweep.parameters, *(o.column for o in sweep.outputs), *TAIL]


class ResultsTable:
    """results.csv of ``sweep`` in ``out``; :meth:`open` before :meth:`append`."""

    def __init__(self, sweep: Sweep, out: Path):
        self.sweep, self.path = sweep, Path(out) / "results.csv"
        self.header = header(sweep)
        self._file = None

    def open(self, resume: bool) -> set[str]:
        """Start the table, or with ``resume`` continue it; returns the ids of the points it holds
        already. A torn last line (a sweep killed while writing it) is cut off. ValueError when
        the table exists and ``resume`` is off, or when it does not belong to this sweep."""
        done: set[str] = set()
        if self.path.exists():
            if not resume:
                raise ValueError(f"{self.path} exists: continue that sweep with 'resume', or "
                                 "choose another 'out' folder")
            done = self._finished()
        else:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            self.path.write_text(_line(self.header))
        self._file = self.path.open("a", newline="")
        return done

    def _finished(self) -> set[str]:
        text = self.path.read_text()
        if not text.endswith("\n"):
            text = text[:text.rfind("\n") + 1]
            self.path.write_text(text)
        rows = list(csv.reader(io.StringIO(text)))
        if not rows or rows[0] != self.header:
            raise ValueError(f"{self.path}: its columns {rows[0] if rows else []} are not those of "
                             f"{self.sweep.path} ({self.header}); use another 'out' folder")
        ids = [row[0] for row in rows[1:]]
        strangers = sorted(set(ids) - set(self.sweep.ids))
        if strangers:
            raise ValueError(f"{self.path}: {len(strangers)} point(s) (first {strangers[0]}) are not "
                             f"points of {self.sweep.path} (another scenario, experiment or "
                             "design?); use another 'out' folder")
        return set(ids)

    def append(self, index: int, outputs: dict | None, attempts: int, wall_time: float | None,
               error: str | None) -> None:
        """Write the row of the point ``index`` (of the design) and flush it to disk."""
        point = self.sweep.points[index]
        row = [self.sweep.ids[index], *(point[p] for p in self.sweep.parameters),
               *((outputs or {}).get(o.column, "") for o in self.sweep.outputs),
               "ok" if error is None else "failed", attempts,
               "" if wall_time is None else wall_time, error or ""]
        self._file.write(_line(row))
        self._file.flush()
        os.fsync(self._file.fileno())

    def close(self) -> None:
        if self._file is not None:
            self._file.close()

    def write_json(self) -> Path:
        """results.json beside the table: the sweep's description and every row in design order,
        parameters as the design holds them, numbers as numbers (null for none)."""
        with self.path.open(newline="") as f:
            rows = {row["point"]: row for row in csv.DictReader(f)}
        units = {f"{i}.{v}": self.sweep.system.unit(i, v)
                 for i, v in (o.variable.split(".", 1) for o in self.sweep.outputs)}
        points = []
        for point_id, point in zip(self.sweep.ids, self.sweep.points):
            row = rows.get(point_id)
            if row is None:
                continue
            points.append({
                "point": point_id, "parameters": point,
                "outputs": {o.column: _number(row[o.column]) for o in self.sweep.outputs},
                "status": row["status"], "attempts": int(row["attempts"]),
                "wall_time_s": _number(row["wall_time_s"]), "error": row["error"] or None})
        data = {"sweep": str(self.sweep.path), "scenario": self.sweep.system.name,
                "experiment": {k: v if math.isfinite(v) else str(v) for k, v in
                               self.sweep.system.experiment.__dict__.items()
                               if not isinstance(v, str)},
                "algorithm": self.sweep.system.experiment.algorithm, "design": self.sweep.kind,
                "parameters": list(self.sweep.parameters),
                "parameter_units": {p: self.sweep.system.unit(*p.split(".", 1))
                                    for p in self.sweep.parameters},
                "descriptions": {n: self.sweep.system.variable_description(*n.split(".", 1))
                                 for n in (*self.sweep.parameters, *units)},
                "outputs": [{"column": o.column, "variable": o.variable, "reduce": o.kind,
                             "settle_s": o.settle, "unit": o.unit(units[o.variable])}
                            for o in self.sweep.outputs],
                "points_in_design": len(self.sweep.points), "points": points}
        path = self.path.with_suffix(".json")
        path.write_text(json.dumps(data, indent=1, default=str))
        return path


def _line(values) -> str:
    buffer = io.StringIO()
    csv.writer(buffer, lineterminator="\n").writerow(values)
    return buffer.getvalue()


def _number(text: str) -> float | None:
    return float(text) if text else None
