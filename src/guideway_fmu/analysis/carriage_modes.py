"""Natural frequencies and mode shapes of a ball-guide carriage from a carriage file
(``guideway-fmu modes CARRIAGE.toml``), SI units; the format is in docs/ball-guides.md.

The ball stiffnesses are given (``[balls] stiffness``, one value per ball of a row, both rows
alike: Wu et al. 2012, Table 2) or computed: the balls' Hertz constant from ``diameter`` and
``conformity`` (two equal contacts in series), every ball preloaded to ``preload`` [N], the
static equilibrium under ``[load]``, then each ball's tangent stiffness (physics/ball_guides/carriage_5dof.py).
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..physics.ball_guides import carriage_5dof as bc
from ..physics.ball_guides import hertz_point
from . import input_file

LOAD_KEYS = ("force_y", "force_z", "moment_x", "moment_y", "moment_z")  # order of bc.LOADS
CARRIAGE_KEYS = ("mass", "inertia", "contact_angle_deg", "d", "e")
HERTZ_KEYS = ("diameter", "conformity", "preload")


@dataclass(frozen=True)
class CarriageCase:
    """A carriage file's content: the body, the ball layout, the stiffness source and the load."""

    path: Path
    body: bc.CarriageBody
    per_row: int
    pitch: float
    stiffness: tuple | None  # per ball of a row [N/m], or None: the Hertz route
    k_h: float | None  # Hertz constant of a ball [N/m^1.5]
    preload: float | None  # N per ball
    load: np.ndarray  # (F_y, F_z, M_x, M_y, M_z)

    def positions(self) -> np.ndarray:
        return bc.ball_positions(self.per_row, self.pitch)


def read_carriage(path) -> CarriageCase:
    """Read and check a carriage file; ValueError or FileNotFoundError naming the file, table
    and key."""
    path = Path(path)
    data = input_file.read(path, "carriage")
    carriage, balls = (input_file.table(path, data, "carriage"),
                       input_file.table(path, data, "balls"))
    load_table = input_file.table(path, data, "load", required=False)
    input_file.refuse_unknown(path, {
        "carriage": (carriage, CARRIAGE_KEYS),
        "balls": (balls, ("per_row", "pitch", "stiffness", *HERTZ_KEYS)),
        "load": (load_table, LOAD_KEYS)})
    inertia = carriage.get("inertia")
    if (not isinstance(inertia, list) or len(inertia) != 3
            or not all(isinstance(j, (int, float)) and j > 0 for j in inertia)):
        raise ValueError(f"{path}: [carriage] key 'inertia': must be [J_x, J_y, J_z] > 0 in "
                         f"kg m^2, got {inertia!r}")
    angle = input_file.number(path, "carriage", carriage, "contact_angle_deg")
    if not 0.0 < angle < 90.0:
        raise ValueError(f"{path}: [carriage] key 'contact_angle_deg': must lie in (0, 90), "
                         f"got {angle!r}")
    body = bc.CarriageBody(input_file.number(path, "carriage", carriage, "mass", True),
                           tuple(float(j) for j in inertia), np.radians(angle),
                           input_file.number(path, "carriage", carriage, "d"),
                           input_file.number(path, "carriage", carriage, "e"))
    per_row = input_file.whole(path, "balls", balls, "per_row")
    pitch = input_file.number(path, "balls", balls, "pitch", True)
    load = np.array([input_file.number(path, "load", load_table, k) if k in load_table else 0.0
                     for k in LOAD_KEYS])
    hertz = [k for k in HERTZ_KEYS if k in balls]
    if "stiffness" in balls:
        if hertz:
            raise ValueError(f"{path}: [balls]: give 'stiffness' or {', '.join(HERTZ_KEYS)}, "
                             f"not both (found {', '.join(hertz)})")
        stiffness = balls["stiffness"]
        if (not isinstance(stiffness, list) or len(stiffness) != per_row
                or not all(isinstance(k, (int, float)) and k > 0 for k in stiffness)):
            raise ValueError(f"{path}: [balls] key 'stiffness': must be {per_row} values "
                             f"(per_row) > 0 in N/m, got {stiffness!r}")
        if np.any(load):
            raise ValueError(f"{path}: [load] needs the Hertz route ({', '.join(HERTZ_KEYS)}): "
                             f"given stiffnesses already hold the load's effect")
        return CarriageCase(path, body, per_row, pitch, tuple(map(float, stiffness)), None, None,
                            load)
    missing = [k for k in HERTZ_KEYS if k not in balls]
    if missing:
        raise ValueError(f"{path}: [balls]: give 'stiffness' or all of {', '.join(HERTZ_KEYS)}; "
                         f"missing {', '.join(missing)}")
    diameter = input_file.number(path, "balls", balls, "diameter", True)
    conformity = input_file.number(path, "balls", balls, "conformity")
    try:
        k_h = hertz_point.ball_constant(hertz_point.BallGroove(diameter, conformity))
    except ValueError as error:
        raise ValueError(f"{path}: [balls] {error}") from None
    return CarriageCase(path, body, per_row, pitch, None, k_h,
                        input_file.number(path, "balls", balls, "preload", True), load)


def analyse(case: CarriageCase) -> dict:
    """Modes of the carriage: ``{"modes": [...], "ball_stiffness": [...], "displacement": {...}}``,
    modes in ascending order, rigid-body modes (frequency 0, label 'rigid') included. Each mode
    has its ``ball_approach`` per row: each ball's approach in the mode shape over the largest
    (0 for a rigid mode, which stretches no ball)."""
    directions = bc.contact_directions(case.body, case.positions())
    if case.stiffness is not None:
        k = np.concatenate([case.stiffness, case.stiffness])
        q = np.zeros(5)
    else:
        balls = bc.HertzBalls(case.body, case.positions(), case.k_h, case.preload)
        try:
            q = balls.equilibrium(case.load)
        except ValueError as error:
            raise ValueError(f"{case.path}: [load]: {error}") from None
        k = balls.ball_stiffness(q)
    found = bc.modes(bc.stiffness_matrix(directions, k), case.body.mass_matrix())
    approach = np.column_stack(directions) @ found.shapes  # ball approach (row) in each mode (column)
    approach = np.where(found.frequencies > 0.0,
                        approach / np.max(np.abs(approach), axis=0, initial=1e-300), 0.0)
    rows = [{"frequency_hz": float(f), "label": found.label(i),
             "participation": dict(zip(bc.DOF, map(float, found.participation[i]))),
             "ball_approach": {"row_1": approach[:case.per_row, i].tolist(),
                               "row_2": approach[case.per_row:, i].tolist()}}
            for i, f in enumerate(found.frequencies)]
    return {"modes": rows, "ball_positions": case.positions().tolist(),
            "ball_stiffness": {"row_1": k[:case.per_row].tolist(),
                               "row_2": k[case.per_row:].tolist()},
            "displacement": dict(zip(bc.DOF, map(float, q)))}


def format_modes(result: dict) -> str:
    """A readable table of :func:`analyse`'s result."""
    lines = [f"{'mode':>4} {'f [Hz]':>10}  {'label':22s} " + " ".join(f"{d:>6s}" for d in bc.DOF)]
    for i, mode in enumerate(result["modes"], 1):
        lines.append(f"{i:4d} {mode['frequency_hz']:10.1f}  {mode['label']:22s} "
                     + " ".join(f"{mode['participation'][d]:6.3f}" for d in bc.DOF))
    lines.append("participation: share of the mode's kinetic energy in each coordinate; "
                 "'rigid': the lateral shift with roll that no ball of two rows resists")
    return "\n".join(lines)
