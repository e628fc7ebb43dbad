"""The errors and stiffness of a four-slider ball-guide feed unit from a feed-unit file
(``guideway-fmu feed-unit FEEDUNIT.toml``), with and without the contact-angle change, for one
load or swept over the load, the load point or the contact angle (Zhang, Wang and Le 2019;
physics/ball_guides/feed_unit.py). The file format is in docs/feed-unit.md.
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..physics.ball_guides import feed_unit as fu
from ..physics.ball_guides import hertz_point
from ..physics.papers import zhang2019
from . import input_file

KEYS = {"table": ("half_span_x", "half_span_y"),
        "slider": ("row_spacing_y", "row_spacing_z", "contact_angle_deg"),
        "balls": ("diameter", "conformity", "per_row", "pitch", "preload"),
        "material": ("youngs_modulus", "poisson_ratio"),
        "load": ("force", "point", "moment")}
MODELS = {"angle_change": True, "constant_angle": False}
#: what --sweep varies, its unit and default range (None: from the file)
SWEEPS = {"load": ("fraction of the file's load", (0.0, 1.0)),
          "point_x": ("m", None), "point_y": ("m", None),
          "contact_angle": ("deg", zhang2019.CONTACT_ANGLE_RANGE_DEG)}


@dataclass(frozen=True)
class FeedUnitCase:
    """A feed-unit file's content."""

    path: Path
    layout: fu.Layout
    ball: hertz_point.BallGroove
    preload: float  # N per ball
    force: np.ndarray  # (F_x, F_y, F_z) [N] on the table
    point: np.ndarray  # (x, y, z) [m] where it acts
    moment: np.ndarray  # (M_x, M_y, M_z) [N m]

    def unit(self, angle_change: bool) -> fu.FeedUnit:
        return fu.FeedUnit(self.layout, self.ball, self.preload, angle_change)

    @property
    def load(self) -> np.ndarray:
        return fu.generalized_load(self.force, self.point, self.moment)


def read_feed_unit(path) -> FeedUnitCase:
    """Read and check a feed-unit file; ValueError or FileNotFoundError naming the file, table
    and key."""
    path = Path(path)
    data = input_file.read(path, "feed-unit")
    tables = input_file.tables(path, data, KEYS, optional=("material", "load"))

    def num(table, key, positive=True, default=None):
        return input_file.number(path, table, tables[table], key, positive, default)

    angle = num("slider", "contact_angle_deg")
    load = tables["load"]
    try:
        layout = fu.Layout(num("table", "half_span_x"), num("table", "half_span_y"),
                           num("slider", "row_spacing_y"), num("slider", "row_spacing_z"),
                           np.radians(angle), input_file.whole(path, "balls", tables["balls"],
                                                               "per_row"),
                           num("balls", "pitch"))
    except ValueError as error:
        raise ValueError(f"{path}: {error}") from None
    modulus = num("material", "youngs_modulus", default=hertz_point.STEEL[0])
    poisson = num("material", "poisson_ratio", positive=False, default=hertz_point.STEEL[1])
    try:
        ball = hertz_point.BallGroove(num("balls", "diameter"), num("balls", "conformity"),
                                      modulus, poisson, modulus, poisson)
    except ValueError as error:
        raise ValueError(f"{path}: [balls] or [material]: {error}") from None
    return FeedUnitCase(
        path, layout, ball, num("balls", "preload"),
        input_file.vector(path, "load", load, "force", 3, "[F_x, F_y, F_z] in N", [0, 0, 0]),
        input_file.vector(path, "load", load, "point", 3, "[x, y, z] in m", [0, 0, 0]),
        input_file.vector(path, "load", load, "moment", 3, "[M_x, M_y, M_z] in N m", [0, 0, 0]))


def _solve(case: FeedUnitCase, unit: fu.FeedUnit, start=None) -> fu.Equilibrium:
    try:
        return unit.equilibrium(case.load, start)
    except ValueError as error:
        raise ValueError(f"{case.path}: [load]: {error}") from None


def _model_result(case: FeedUnitCase, unit: fu.FeedUnit, state: fu.Equilibrium) -> dict:
    stiffness = unit.slider_stiffness(state)
    sliders = []
    for m, (sx, sy) in enumerate(fu.SLIDER_SIGNS):
        mine = unit.slider == m
        rows = np.degrees(state.angles[mine]).reshape(4, -1).mean(axis=1)
        sliders.append({"slider": m + 1,
                        "position": [sx * case.layout.half_span_x, sy * case.layout.half_span_y],
                        "stiffness_y": float(stiffness[m, 0]), "stiffness_z": float(stiffness[m, 1]),
                        "max_ball_load": float(state.loads[mine].max()),
                        "min_ball_load": float(state.loads[mine].min()),
                        "balls_out_of_contact": int(np.sum(state.approaches[mine] <= 0.0)),
                        "row_contact_angle_deg": rows.tolist()})
    lateral, vertical = unit.unit_stiffness(state)
    pressure = unit.max_pressure(state)
    point = fu.point_displacement(state.q, case.point)
    return {"errors": state.errors,
            "load_point_displacement": dict(zip(("d_x", "d_y", "d_z"), map(float, point))),
            "unit_stiffness": {"lateral": float(lateral), "vertical": float(vertical)},
            "sliders": sliders, "max_contact_pressure": pressure,
            "above_static_pressure_limit": bool(pressure > fu.PRESSURE_LIMIT)}


def analyse(case: FeedUnitCase) -> dict:
    """The five errors, the load point's displacement and the stiffness of the unit and of each
    slider for the file's load, with (``angle_change``) and without (``constant_angle``) the
    contact-angle change. SI units: m, rad, N/m, N, Pa."""
    out = {"load": {"force": case.force.tolist(), "point": case.point.tolist(),
                    "moment": case.moment.tolist(),
                    "generalized": dict(zip(("F_y", "F_z", "M_x", "M_y", "M_z"),
                                            map(float, case.load)))}}
    for name, change in MODELS.items():
        unit = case.unit(change)
        out[name] = _model_result(case, unit, _solve(case, unit))
    return out


def sweep_values(case: FeedUnitCase, quantity: str, low=None, high=None,
                 points: int = 21) -> np.ndarray:
    """The swept values: ``low``..``high`` in ``points`` steps, by default the quantity's
    range (the load point across the slider spans)."""
    if quantity not in SWEEPS:
        raise ValueError(f"'sweep' must be one of {', '.join(SWEEPS)}, got {quantity!r}")
    if isinstance(points, bool) or not isinstance(points, int) or points < 2:
        raise ValueError(f"'points' must be a whole number >= 2, got {points!r}")
    default = SWEEPS[quantity][1]
    if default is None:
        span = case.layout.half_span_x if quantity == "point_x" else case.layout.half_span_y
        default = (-span, span)
    low = default[0] if low is None else float(low)
    high = default[1] if high is None else float(high)
    if quantity == "contact_angle" and not (0.0 < low < 90.0 and 0.0 < high < 90.0):
        raise ValueError(f"the contact angle range must lie in (0, 90) degrees, got "
                         f"{low:g} to {high:g}")
    return np.linspace(low, high, points)


def _variant(case: FeedUnitCase, quantity: str, value: float) -> FeedUnitCase:
    if quantity == "load":
        return dataclasses.replace(case, force=value * case.force, moment=value * case.moment)
    if quantity in ("point_x", "point_y"):
        point = case.point.copy()
        point["xy".index(quantity[-1])] = value
        return dataclasses.replace(case, point=point)
    layout = dataclasses.replace(case.layout, contact_angle=np.radians(value))
    return dataclasses.replace(case, layout=layout)


def sweep(case: FeedUnitCase, quantity: str, values) -> dict:
    """Both models along the swept values: the five errors [m, rad], the load point's
    displacement [m] and the unit's lateral and vertical stiffness [N/m], one list each."""
    out = {"sweep": quantity, "unit": SWEEPS[quantity][0],
           "values": [float(v) for v in values],
           "force_magnitude": [float(np.linalg.norm(_variant(case, quantity, v).force))
                               for v in values]}
    for name, change in MODELS.items():
        columns: dict[str, list] = {}
        start = None
        for value in values:
            variant = _variant(case, quantity, value)
            unit = variant.unit(change)
            state = _solve(variant, unit, start if quantity != "contact_angle" else None)
            start = state.q
            result = _model_result(variant, unit, state)
            row = {**result["errors"],
                   **{f"load_point_{k}": v for k, v in result["load_point_displacement"].items()},
                   "stiffness_lateral": result["unit_stiffness"]["lateral"],
                   "stiffness_vertical": result["unit_stiffness"]["vertical"],
                   "max_ball_load": max(s["max_ball_load"] for s in result["sliders"])}
            for key, value_ in row.items():
                columns.setdefault(key, []).append(float(value_))
        out[name] = columns
    return out


def format_result(result: dict) -> str:
    """A readable summary of :func:`analyse`'s result."""
    lines = [f"{'':24s} {'angle change':>14s} {'constant angle':>14s}"]
    a, c = result["angle_change"], result["constant_angle"]
    for key in fu.ERRORS:
        unit, scale = ("um", 1e6) if key.startswith("delta") else ("urad", 1e6)
        lines.append(f"{key + ' [' + unit + ']':24s} {a['errors'][key] * scale:14.4f} "
                     f"{c['errors'][key] * scale:14.4f}")
    for key in ("d_x", "d_y", "d_z"):
        lines.append(f"{'load point ' + key + ' [um]':24s} "
                     f"{a['load_point_displacement'][key] * 1e6:14.4f} "
                     f"{c['load_point_displacement'][key] * 1e6:14.4f}")
    for key in ("lateral", "vertical"):
        lines.append(f"{'unit ' + key + ' [N/um]':24s} {a['unit_stiffness'][key] / 1e6:14.1f} "
                     f"{c['unit_stiffness'][key] / 1e6:14.1f}")
    for sa, sc in zip(a["sliders"], c["sliders"]):
        for key in ("stiffness_y", "stiffness_z"):
            label = f"slider {sa['slider']} {key} [N/um]"
            lines.append(f"{label:24s} {sa[key] / 1e6:14.1f} {sc[key] / 1e6:14.1f}")
    lines.append(f"{'max contact pressure [GPa]':24s} {a['max_contact_pressure'] / 1e9:14.3f} "
                 f"{c['max_contact_pressure'] / 1e9:14.3f}")
    if a["above_static_pressure_limit"] or c["above_static_pressure_limit"]:
        lines.append(f"warning: a contact pressure exceeds {fu.PRESSURE_LIMIT / 1e9:.1f} GPa, "
                     f"the static limit behind ISO 76: the load is beyond the guide's rating")
    return "\n".join(lines)


def format_sweep(result: dict) -> str:
    """A readable table of :func:`sweep`'s result: the five errors of both models per value."""
    lines = [f"{result['sweep'] + ' [' + result['unit'] + ']':>18s} "
             + " ".join(f"{key + ' ' + model[0]:>13s}" for key in fu.ERRORS for model in MODELS)]
    for i, value in enumerate(result["values"]):
        lines.append(f"{value:18.6g} " + " ".join(f"{result[model][key][i] * 1e6:13.4f}"
                                                 for key in fu.ERRORS for model in MODELS))
    lines.append("errors in um and urad; a: contact angle changes, c: constant angle")
    return "\n".join(lines)
