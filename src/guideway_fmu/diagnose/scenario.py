"""The rig model as a co-simulation scenario (cosim/system.py format) and its run through the FMUs.

Three FMUs, stepped Gauss-Seidel at the record's median sampling interval:
FeedKinematics (profile "replay" of the motion the model is driven with) -> a friction FMU
(FrictionCoulomb for the baseline, the effect's FMU for an augmented model) -> HorizontalRig
(drive_force = m a - F_friction + offset). The outputs are interpolated to the sample times.
"""
from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from ..components.build import build
from ..cosim import master, system as cosim_system
from .candidates import Context, Fit

RIG_FMUS = ("FeedKinematics", "HorizontalRig")


def _toml_value(value) -> str:
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(value, (int, np.integer)) and not isinstance(value, bool):
        return str(int(value))
    return repr(float(value))


def _inline(params: dict) -> str:
    return "{ " + ", ".join(f"{k} = {_toml_value(v)}" for k, v in params.items()) + " }"


def write_replay(ctx: Context, path: Path) -> Path:
    """The motion the model is driven with, as the FeedKinematics replay table."""
    m = ctx.motion
    with path.open("w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(["time", "feed_position", "feed_velocity", "feed_acceleration"])
        writer.writerows(np.column_stack([m.time, m.x, m.v, m.a]).tolist())
    return path


def ensure_fmus(fmu_dir: Path, names) -> Path:
    """Build the FMUs among ``names`` that ``fmu_dir`` lacks."""
    missing = [n for n in dict.fromkeys(names) if not (fmu_dir / f"{n}.fmu").is_file()]
    if missing:
        build(fmu_dir, missing)
    return fmu_dir


def write_scenario(ctx: Context, fit: Fit, path: Path, replay: Path, fmu_dir: Path, name: str,
                   description: str) -> Path:
    """The scenario TOML of the model ``fit`` (FMU paths relative to the scenario file)."""
    m, channel = ctx.motion, ctx.run.channel
    steps = max(int(round((m.time[-1] - m.time[0]) / np.median(np.diff(m.time)))), 1)
    step = (m.time[-1] - m.time[0]) / steps
    fmus = {n: Path(fmu_dir).resolve() / f"{n}.fmu" for n in (*RIG_FMUS, fit.fmu)}
    try:
        rel = {n: p.relative_to(path.parent.resolve()).as_posix() for n, p in fmus.items()}
    except ValueError:
        rel = {n: p.as_posix() for n, p in fmus.items()}
    offset = "drive_offset" if channel == "drive_force" else "friction_offset"
    rig = {"mass": fit.rig_mass, offset: fit.offset}
    lines = [f"name = {_toml_value(name)}", f"description = {_toml_value(description)}", "",
             "[experiment]", f"start = {_toml_value(m.time[0])}", f"stop = {_toml_value(m.time[-1])}",
             f"step = {_toml_value(step)}", 'algorithm = "gauss-seidel"', "",
             "[components.Feed]", f"fmu = {_toml_value(rel['FeedKinematics'])}",
             f"parameters = {_inline({'profile': 'replay', 'table_file': str(replay.resolve())})}",
             "", "[components.Friction]", f"fmu = {_toml_value(rel[fit.fmu])}",
             f"parameters = {_inline(fit.fmu_parameters)}", "",
             "[components.Rig]", f"fmu = {_toml_value(rel['HorizontalRig'])}",
             f"parameters = {_inline(rig)}", ""]
    connections = [("Feed.u", "Friction.u"), ("Feed.a", "Rig.a"),
                   ("Friction.F_friction", "Rig.F_friction")]
    if fit.uses_position:
        connections.insert(1, ("Feed.x", "Friction.x"))
    for source, target in connections:
        lines += ["[[connections]]", f'from = "{source}"', f'to = "{target}"']
    lines += ["", "[record]", f'variables = ["Rig.{channel}"]',
              "", "[plots]", f'time = ["Rig.{channel}", "Friction.F_friction"]', ""]
    path.write_text("\n".join(lines))
    return path


def cosimulate(ctx: Context, scenario: Path) -> tuple[np.ndarray, float]:
    """Run the scenario through the FMUs; (compared channel at the sample times, wall time [s])."""
    system = cosim_system.load(scenario)
    result = master.simulate(system)
    rec = result.recording
    values = rec.columns[f"Rig.{ctx.run.channel}"]
    return np.interp(ctx.motion.time, rec.time, values), result.wall_time
