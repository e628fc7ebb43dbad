"""Raceway wear and preload loss of a linear ball guide over its running distance from a case
file (``guideway-fmu wear CASE.toml --distance 5000``), by the fractal-creep model of Zhang, Wang
and Jiang; physics/wear/raceway_wear.py. The format is in docs/wear.md.
"""
from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np

from ..physics.wear import fractal, raceway_wear
from . import input_file

KEYS = {"guide": ("ball_diameter", "conformity", "balls_per_row", "contact_angle_deg",
                  "preload_deformation", "spacing_ratio"),
        "material": ("E", "nu", "yield_strength", "hardness"),
        "surface": ("fractal_dimension", "scale", "profile", "shortest_lag", "longest_lag"),
        "wear": ("coefficient", "friction", "hysteresis", "tangential_ratio", "lateral_ratio"),
        "load": ("vertical",)}
#: case key -> Guide field, for the plain numbers
FIELDS = {("guide", "ball_diameter"): "ball_diameter", ("guide", "conformity"): "conformity",
          ("guide", "preload_deformation"): "preload_deformation",
          ("guide", "spacing_ratio"): "spacing_ratio", ("material", "E"): "youngs_modulus",
          ("material", "nu"): "poisson_ratio", ("material", "yield_strength"): "yield_strength",
          ("material", "hardness"): "hardness", ("surface", "fractal_dimension"):
          "fractal_dimension", ("surface", "scale"): "fractal_scale",
          ("wear", "coefficient"): "wear_coefficient", ("wear", "friction"): "friction",
          ("wear", "hysteresis"): "hysteresis", ("wear", "tangential_ratio"): "tangential_ratio",
          ("wear", "lateral_ratio"): "lateral_ratio"}


@dataclasses.dataclass(frozen=True)
class WearCase:
    """A guide, the vertical load F [N] on its slider, and the profile fit that gave its fractal
    parameters (None: given in the file or the defaults)."""

    guide: raceway_wear.Guide
    load: float
    fit: fractal.StructureFit | None = None


def read_profile(path: Path) -> tuple[np.ndarray, float]:
    """(z [m], spacing [m]) of a profile CSV with a header and columns x, z [m], x equally
    spaced; errors name the file and the row."""
    try:
        data = np.genfromtxt(path, delimiter=",", names=True)
    except (OSError, ValueError) as error:
        raise ValueError(f"{path}: cannot be read as a CSV profile with columns x, z: "
                         f"{error}") from None
    if data.dtype.names is None or not {"x", "z"} <= set(data.dtype.names):
        raise ValueError(f"{path}: needs a header with the columns x and z [m]")
    x, z = np.atleast_1d(data["x"]), np.atleast_1d(data["z"])
    bad = np.flatnonzero(~(np.isfinite(x) & np.isfinite(z)))
    if bad.size:
        raise ValueError(f"{path}: row {int(bad[0]) + 2}: x and z must be finite numbers")
    if x.size < 20:
        raise ValueError(f"{path}: {x.size} samples; a structure-function fit needs at least 20")
    steps = np.diff(x)
    spacing = float(np.mean(steps))
    if not spacing > 0 or np.max(np.abs(steps - spacing)) > 1e-6 * spacing:
        row = int(np.argmax(np.abs(steps - spacing))) + 3
        raise ValueError(f"{path}: x must increase in equal steps (row {row} breaks them)")
    return z, spacing


def read_case(path) -> WearCase:
    """Read and check a case file; ValueError or FileNotFoundError naming file, table and key.
    Every table but [load] is optional: the LG20 of the paper's Table 1 fills in."""
    path = Path(path)
    data = input_file.read(path, "wear case")
    tables = input_file.tables(path, data, KEYS,
                               optional=("guide", "material", "surface", "wear"))
    values = {}
    for (table, key), name in FIELDS.items():
        if key in tables[table]:
            values[name] = input_file.number(path, table, tables[table], key)
    guide_table = tables["guide"]
    if "balls_per_row" in guide_table:
        values["balls_per_row"] = input_file.whole(path, "guide", guide_table, "balls_per_row")
    if "contact_angle_deg" in guide_table:
        values["contact_angle"] = math.radians(
            input_file.number(path, "guide", guide_table, "contact_angle_deg"))
    surface, fit = tables["surface"], None
    if "profile" in surface:
        if {"fractal_dimension", "scale"} & set(surface):
            raise ValueError(f"{path}: [surface] give either profile or fractal_dimension and "
                             f"scale, not both")
        profile = surface["profile"]
        if not isinstance(profile, str):
            raise ValueError(f"{path}: [surface] key 'profile': must be a file name, got "
                             f"{profile!r}")
        profile_path = (path.parent / profile)
        if not profile_path.is_file():
            raise FileNotFoundError(f"{path}: [surface] key 'profile': no such file "
                                    f"{profile_path}")
        z, spacing = read_profile(profile_path)
        lags = {key: int(round(input_file.number(path, "surface", surface, key, positive=True)
                               / spacing))
                for key in ("shortest_lag", "longest_lag") if key in surface}
        try:
            fit = fractal.fit_structure_function(
                z, spacing, shortest=max(lags.get("shortest_lag", 1), 1),
                longest=lags.get("longest_lag"))
        except ValueError as error:
            raise ValueError(f"{profile_path}: {error}") from None
        values.update(fractal_dimension=fit.dimension + 1, fractal_scale=fit.scale)
    elif {"shortest_lag", "longest_lag"} & set(surface):
        raise ValueError(f"{path}: [surface] shortest_lag and longest_lag need a profile")
    try:
        guide = raceway_wear.Guide(**values)
    except ValueError as error:
        raise ValueError(f"{path}: {error}") from None
    load = input_file.number(path, "load", tables["load"], "vertical")
    return WearCase(guide, load, fit)


def contact_summary(guide: raceway_wear.Guide, load: float) -> dict:
    """A ball's contact in each row of the new guide under F [N] (SI units)."""
    _, *ball_loads = guide.settle(load, guide.preload_deformation, guide.preload_deformation)
    out = {}
    for row, q in zip(("upper", "lower"), ball_loads):
        if q <= 0.0:
            out[row] = {"ball_load": 0.0}
            continue
        c = guide.contact(q)
        out[row] = {"ball_load": q, "along": c.along, "across": c.across,
                    "mean_pressure": c.pressure, "rolling_friction": c.rolling_friction,
                    "tangential_ratio": c.tangential_ratio,
                    "adhesion_ratio": c.creep.adhesion_along, "creep_rate": c.creep.creep_along,
                    "slip_area": c.creep.slip_area, "wear_rate": guide.wear_rate(q)}
    return out


def analyse(case: WearCase, distance: float, points: int = 101) -> dict:
    """The slider over ``distance`` [m] (> 0), reported at ``points`` (>= 2) distances: the keys
    of the wear JSON and more (SI units)."""
    if not (math.isfinite(distance) and distance > 0):
        raise ValueError(f"'distance' must be a running distance > 0 m, got {distance}")
    if points < 2:
        raise ValueError(f"'points' must be >= 2, got {points}")
    g = case.guide
    history = raceway_wear.simulate(g, case.load, distance, points)
    c = history.columns
    z = c["vertical_displacement"]
    surface = {"fractal_dimension": g.fractal_dimension, "scale": g.fractal_scale,
               "critical_area": g.surface.critical_area}
    if case.fit is not None:
        surface["fit"] = {"profile_dimension": case.fit.dimension, "r_squared":
                          case.fit.r_squared, "lags": case.fit.lags.tolist(),
                          "structure_function": case.fit.values.tolist()}
    return {"distance": history.distance.tolist(), "wear_depth": c["wear_depth"].tolist(),
            "preload_deformation": c["preload_deformation"].tolist(),
            "vertical_displacement": z.tolist(), "preload_lost_at": history.preload_lost_at,
            "wear_displacement": (z - z[0]).tolist(), "preload": c["preload"].tolist(),
            "rows": {"upper": {"ball_load": c["ball_load_upper"].tolist(),
                               "wear_depth": c["wear_upper"].tolist()},
                     "lower": {"ball_load": c["ball_load_lower"].tolist(),
                               "wear_depth": c["wear_lower"].tolist()}},
            "load": case.load, "contact": contact_summary(g, case.load), "surface": surface,
            "guide": {f.name: getattr(g, f.name) for f in dataclasses.fields(g) if f.init}}


def format_result(result: dict) -> str:
    """A readable summary of :func:`analyse`'s result, a table over the distance."""
    up = result["contact"]["upper"]
    lines = [f"vertical load {result['load']:g} N: upper balls {up['ball_load']:.4g} N, "
             f"lower balls {result['contact']['lower']['ball_load']:.4g} N"]
    if "creep_rate" in up:
        lines.append(f"upper contact: a = {1e6 * up['along']:.2f} um, b = "
                     f"{1e6 * up['across']:.1f} um, mean pressure {up['mean_pressure'] / 1e9:.3f} "
                     f"GPa, rolling friction {up['rolling_friction']:.4f}, creep rate "
                     f"{up['creep_rate']:.3e}, wear rate {up['wear_rate']:.3e} m/m")
    s = result["surface"]
    lines.append(f"surface: D = {s['fractal_dimension']:.4f}, G = {s['scale']:.4g} m, A_c = "
                 f"{s['critical_area']:.4g} m^2" + (f" (fitted to the profile, r^2 = "
                                                    f"{s['fit']['r_squared']:.4f})"
                                                    if "fit" in s else ""))
    lines.append(f"{'distance [m]':>14s} {'wear [nm]':>12s} {'preload def. [um]':>18s} "
                 f"{'preload [N]':>12s} {'z [um]':>10s} {'z - z0 [nm]':>12s}")
    n = len(result["distance"])
    for i in sorted({int(round(k * (n - 1) / 10)) for k in range(11)}):
        lines.append(f"{result['distance'][i]:14.6g} {1e9 * result['wear_depth'][i]:12.5g} "
                     f"{1e6 * result['preload_deformation'][i]:18.6f} "
                     f"{result['preload'][i]:12.5g} {1e6 * result['vertical_displacement'][i]:10.5f} "
                     f"{1e9 * result['wear_displacement'][i]:12.5g}")
    lost = result["preload_lost_at"]
    lines.append("preload lost at " + (f"{lost:.6g} m" if lost is not None
                                       else "no point within the distance"))
    return "\n".join(lines)


def load_sweep(case: WearCase, distance: float, loads) -> dict:
    """Fig. 14: the slider's displacement [m] at 0 and after ``distance`` [m] under each vertical
    load [N]: elastic (new guide), total (worn) and the part wear adds."""
    new, worn = [], []
    for load in loads:
        run = raceway_wear.simulate(case.guide, float(load), distance, 2).columns["vertical_displacement"]
        new.append(float(run[0]))
        worn.append(float(run[-1]))
    return {"load": [float(v) for v in loads], "elastic": new, "total": worn,
            "wear": [b - a for a, b in zip(new, worn)]}


def creep_cases(case: WearCase, distance: float, points: int = 51) -> list[dict]:
    """Figs. 15-16: the slider over ``distance`` [m] at three tangential-force ratios P_x/(mu Q)
    (half, once and twice that of the case's upper balls at the start, below 1), each labelled
    by its upper balls' creep rate."""
    base = contact_summary(case.guide, case.load)["upper"].get("tangential_ratio")
    if base is None:
        raise ValueError("the upper balls carry no load: no creep to vary")
    out = []
    for ratio in sorted({min(f * base, 0.95) for f in (0.5, 1.0, 2.0)}):
        guide = dataclasses.replace(case.guide, tangential_ratio=ratio)
        run = raceway_wear.simulate(guide, case.load, distance, points)
        z = run.columns["vertical_displacement"]
        out.append({"tangential_ratio": ratio,
                    "creep_rate": contact_summary(guide, case.load)["upper"]["creep_rate"],
                    "distance": run.distance.tolist(), "total": z.tolist(),
                    "wear": (z - z[0]).tolist()})
    return out
