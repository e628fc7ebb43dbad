"""Ball-to-ball contact of two balls in a four-point contact linear ball bearing from a case
file (``guideway-fmu ball-to-ball CASE.toml``), by the analytical and the low-order numerical
model of Lin, Duan and Okwudire (2019); physics/ball_guides/ball_to_ball.py. The format is in
docs/ball-to-ball.md.
"""
from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
from tqdm import tqdm

from ..output.progress import stages
from ..physics.ball_guides import ball_to_ball as bb
from . import input_file

KEYS = {"ball": ("radius", "conformity"), "material": ("E", "nu", "friction"),
        "contact": ("nominal_angle_deg", *bb.CONTACTS), "load": ("normal", "side_ratio"),
        "motion": ("velocity",)}
BALLS = 2
SIDE_SPAN = 0.95  # side ratios of the sweep: within this share of the two-point limit tan(beta_0)
SWEEP_POINTS = 39


def _deviation(path, table: dict, key: str) -> list[float]:
    """One contact's deviation [deg] for each ball: a number for both, or a list of two."""
    value = table.get(key, 0.0)
    values = value if isinstance(value, list) else [value] * BALLS
    if (len(values) != BALLS or not all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                         and np.isfinite(v) for v in values)):
        raise ValueError(f"{path}: [contact] key {key!r}: must be a deviation in degrees or a "
                         f"list of {BALLS} (ball 1 behind, ball 2 in front), got {value!r}")
    return [float(v) for v in values]


def read_case(path) -> bb.TwoBallCase:
    """Read and check a case file; ValueError or FileNotFoundError naming file, table and key."""
    path = Path(path)
    data = input_file.read(path, "ball-to-ball case")
    tables = input_file.tables(path, data, KEYS)

    def num(table, key, positive=True):
        return input_file.number(path, table, tables[table], key, positive)

    columns = [_deviation(path, tables["contact"], key) for key in bb.CONTACTS]
    deviations = tuple(tuple(np.radians([c[ball] for c in columns])) for ball in range(BALLS))
    try:
        bearing = bb.Bearing(num("ball", "radius"), num("ball", "conformity"),
                             num("material", "E"), num("material", "nu", False),
                             num("material", "friction"),
                             np.radians(num("contact", "nominal_angle_deg")),
                             num("motion", "velocity"))
    except ValueError as error:
        raise ValueError(f"{path}: {error}") from None
    return bb.TwoBallCase(bearing, deviations, num("load", "normal"),
                          num("load", "side_ratio", False))


def analyse(case: bb.TwoBallCase, source="case", progress: bool = False) -> dict:
    """``{"analytical": {...}, "numerical": {...}}`` (SI units; epsilon as fractions); errors
    name ``source``. ``progress``: a bar of the steps on stderr (the friction maps take most
    of the time)."""
    try:
        with stages(f"ball-to-ball {Path(source).name}", total=3, enabled=progress) as begin:
            begin(f"friction maps of the contact ellipse b/a = {case.bearing.aspect:.3g}")
            case.bearing.maps
            begin("analytical model")
            analytical = bb.analytical(case)
            begin("numerical model")
            numerical = bb.numerical(case)
    except ValueError as error:
        raise ValueError(f"{source}: {error}") from None
    return {"analytical": analytical, "numerical": numerical,
            "hertz": {"psi": case.bearing.psi, "aspect_b_over_a": case.bearing.aspect}}


def side_ratio_sweep(case: bb.TwoBallCase, points: int = SWEEP_POINTS,
                     progress: bool = False) -> dict:
    """Both models over the side ratio rho in [-SIDE_SPAN, SIDE_SPAN] tan(beta_0), the case's
    deviations, normal load and speed held: ``{"side_ratio": [...], "analytical": {...},
    "numerical": {...}}`` with the contact force [N] and the ball-to-ball loss [W] of each
    (the numerical groove loss [W] too), None where a ball leaves four-point contact.
    ``progress``: a bar of the points on stderr."""
    limit = SIDE_SPAN * np.tan(case.bearing.nominal_angle)
    ratios = np.linspace(-limit, limit, points)
    out = {"side_ratio": ratios.tolist(),
           "analytical": {"contact_force": [], "friction_loss": []},
           "numerical": {"contact_force": [], "friction_loss": [], "groove_loss": []}}
    for rho in tqdm(ratios, desc="ball-to-ball over the side ratio", unit="point",
                    disable=not progress):
        moved = replace(case, side_ratio=float(rho))
        for model, solve in (("analytical", bb.analytical), ("numerical", bb.numerical)):
            try:
                result = solve(moved)
            except ValueError:  # out of four-point contact: no value
                result = {}
            for key, values in out[model].items():
                values.append(result.get(key))
    return out


def format_result(result: dict) -> str:
    """A readable summary of :func:`analyse`'s result."""
    lines = [f"{'':28s} {'analytical':>12s} {'numerical':>12s}"]
    a, n = result["analytical"], result["numerical"]
    for i in range(BALLS):
        lines.append(f"{f'epsilon ball {i + 1} [%]':28s} {100 * a['epsilon'][i]:12.4f} "
                     f"{100 * n['epsilon'][i]:12.4f}")
    lines.append(f"{'contact force [N]':28s} {a['contact_force']:12.4f} {n['contact_force']:12.4f}")
    lines.append(f"{'ball-to-ball loss [mW]':28s} {1e3 * a['friction_loss']:12.4f} "
                 f"{1e3 * n['friction_loss']:12.4f}")
    lines.append(f"{'groove loss [mW]':28s} {'':12s} {1e3 * n['groove_loss']:12.4f}")
    lines.append(f"k_f = {a['k_f']:.4f} (from the friction map), Psi = "
                 f"{result['hertz']['psi']:.4e} (m^2/N)^(1/3), b/a = "
                 f"{result['hertz']['aspect_b_over_a']:.4f}")
    return "\n".join(lines)
