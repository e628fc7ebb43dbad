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

from ..cosim import master, system as cosim_system
from .candidates import Context, Fit

RIG_FMUS = ("FeedKinematics", "HorizontalRig")


def write_replay(ctx: Context, path: Path) -> Path:
    """The motion the model is driven with, as the FeedKinematics replay table."""
    m = ctx.motion
    with path.open("w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(["time", "feed_position", "feed_velocity", "feed_acceleration"])
        writer.writerows(np.column_stack([m.time, m.x, m.v, m.a]).tolist())
    return path


def write_scenario(ctx: Context, fit: Fit, path: Path, replay: Path, fmu_dir: Path, name: str,
                   description: str) -> Path:
    """The scenario TOML of the model ``fit`` (FMU paths relative to the scenario file)."""
    m, channel = ctx.motion, ctx.run.channel
    steps = max(int(round((m.time[-1] - m.time[0]) / np.median(np.diff(m.time)))), 1)
    fmus = Path(fmu_dir).resolve()
    offset = "drive_offset" if channel == "drive_force" else "friction_offset"
    b = cosim_system.Builder(name, description).experiment(
        start=float(m.time[0]), stop=float(m.time[-1]),
        step=float((m.time[-1] - m.time[0]) / steps), algorithm="gauss-seidel")
    b.component("Feed", fmus / "FeedKinematics.fmu", profile="replay",
                table_file=str(replay.resolve()))
    b.component("Friction", fmus / f"{fit.fmu}.fmu", **fit.fmu_parameters)
    b.component("Rig", fmus / "HorizontalRig.fmu", mass=fit.rig_mass, **{offset: fit.offset})
    b.connect("Feed.u", "Friction.u")
    if fit.uses_position:
        b.connect("Feed.x", "Friction.x")
    b.connect("Feed.a", "Rig.a").connect("Friction.F_friction", "Rig.F_friction")
    b.record([f"Rig.{channel}"]).plots(time=[f"Rig.{channel}", "Friction.F_friction"])
    return cosim_system.dump(b.system(check_fmus=False), path)


def cosimulate(ctx: Context, scenario: Path) -> tuple[np.ndarray, float]:
    """Run the scenario through the FMUs; (compared channel at the sample times, wall time [s])."""
    system = cosim_system.load(scenario)
    result = master.simulate(system)
    rec = result.recording
    values = rec.columns[f"Rig.{ctx.run.channel}"]
    return np.interp(ctx.motion.time, rec.time, values), result.wall_time
