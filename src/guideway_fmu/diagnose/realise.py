"""Step 5 of the discrepancy workflow: the named model as a co-simulation scenario
(cosim/system.py format), run through the FMUs.

Three FMUs, stepped Gauss-Seidel at the record's nominal sampling interval (signals.sampling_step):
FeedKinematics (profile "replay" of the motion the model is driven with) -> a friction FMU
(FrictionCoulomb for the baseline, the effect's FMU for an augmented model) -> HorizontalRig
(drive_force = m a - F_friction + offset). The outputs are interpolated to the sample times.
"""
from __future__ import annotations

import csv
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..fmu_build import build
from ..cosim import master, system as cosim_system
from . import locate
from .candidates import Context, Fit
from .decide import Naming
from .signals import sampling_step

RIG_FMUS = ("FeedKinematics", "HorizontalRig")
CHUNK = 65536  # rows of the replay table turned into Python floats at a time


def write_replay(m, path: Path) -> Path:
    """The motion ``m`` (signals.Motion) the model is driven with, as the FeedKinematics replay
    table, along its path (Motion.path: a reversal inside a dropout is travelled)."""
    table = np.column_stack(m.path()[:4])
    with path.open("w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(["time", "feed_position", "feed_velocity", "feed_acceleration"])
        for start in range(0, len(table), CHUNK):  # as Python floats a chunk at a time
            writer.writerows(table[start:start + CHUNK].tolist())
    return path


def write_scenario(ctx: Context, fit: Fit, path: Path, replay: Path, fmu_dir: Path, name: str,
                   description: str) -> Path:
    """The scenario TOML of the model ``fit`` (FMU paths relative to the scenario file)."""
    m, channel = ctx.motion, ctx.run.channel
    steps = max(int(round((m.time[-1] - m.time[0]) / sampling_step(m.time))), 1)
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


@dataclass
class Realisation:
    """The named model run through the FMUs: the compared channel of the baseline and of the
    augmented model at the samples (the baseline's where nothing is named), the scenario, the
    co-simulation's wall time [s] and its largest deviation from the vectorised model over the
    held-out range of the channel [-]."""

    baseline: np.ndarray
    augmented: np.ndarray
    scenario: Path
    wall_time: float
    agreement: float
    model: Fit

    def gaps(self, naming: Naming) -> tuple[float, float]:
        """Held-out gaps (before, after) of the baseline and the augmented model."""
        y, held = naming.ctx.y, naming.held
        return locate.gap(y, self.baseline, held), locate.gap(y, self.augmented, held)


def realise(naming: Naming, out: Path, fmu_dir: Path) -> Realisation:
    """Write the replay table and the scenario of the named model (the baseline for none or
    unknown) into ``out``, build the FMUs it needs into ``fmu_dir`` and co-simulate it."""
    ctx, winner = naming.ctx, naming.winner
    model = winner or naming.baseline
    build.ensure(fmu_dir, [*RIG_FMUS, model.fmu])
    replay = write_replay(ctx.motion, out / "replay.csv")
    toml = write_scenario(
        ctx, model, out / ("augmented.toml" if winner else "baseline.toml"), replay, fmu_dir,
        f"augmented_{naming.effect}" if winner else "baseline",
        f"{naming.run.path.name}: baseline" + (f" + {naming.effect}" if winner else ""))
    cosim, wall = cosimulate(ctx, toml)
    agreement = float(np.max(np.abs(cosim - model.prediction)[naming.usable])
                      / np.ptp(ctx.y[naming.held]))
    baseline = naming.baseline.prediction
    return Realisation(baseline, cosim if winner else baseline, toml, wall, agreement, model)
