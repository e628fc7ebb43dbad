"""A measured force replayed in time: a table of samples, interpolated linearly and held at the
end values outside it, SI units. It drives a model with a recorded load (the normal force of a
measured run) the way FeedKinematics' replay drives it with a recorded motion."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..dynamics import ContinuousModel
from .feed_motion import check_csv_columns, linear_at, read_csv_columns


@dataclass(frozen=True)
class ForceTable:
    """``time`` [s] (strictly increasing, at least 2) and ``force`` [N] samples, kept as
    tuples of floats."""

    time: tuple
    force: tuple

    def __post_init__(self):
        object.__setattr__(self, "time", tuple(np.asarray(self.time, dtype=float).tolist()))
        object.__setattr__(self, "force", tuple(np.asarray(self.force, dtype=float).tolist()))

    @classmethod
    def from_csv(cls, path, column: str) -> "ForceTable":
        """The columns ``time`` and ``column`` of a comma-separated file with a header; errors
        name the file, the row and the column."""
        if not str(path).strip():
            raise ValueError("table_file is empty: name a CSV file with columns time and "
                             f"{column}")
        columns, rows = read_csv_columns(path, ["time", column])
        check_csv_columns(path, columns, rows, "time")
        return cls(columns["time"], columns[column])

    def __call__(self, t: float) -> float:
        """The force [N] at the time t [s]."""
        return linear_at(self.time, self.force, t)


class ForceTableModel(ContinuousModel):
    """The table as a stateless continuous-time model: output F [N] at t."""

    def __init__(self, table: ForceTable):
        self.table = table

    def outputs(self, t, state, inputs, wanted=None):
        return {"F": self.table(float(t))}


def from_parameters(table_file, column) -> ForceTableModel:
    """The model of the ForceTable FMU's parameters (fmus/README.md)."""
    return ForceTableModel(ForceTable.from_csv(table_file, str(column)))
