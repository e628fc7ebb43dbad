"""Synthetic vertical_response runs with a hidden effect, from the workflow's own vertical model
(diagnose/vertical.py: the reference's models fused, reference/vertical.py, at rtol 1e-9): the
first generator's vertical records. They test the vertical workflow against its own
assumptions; the second generator (second_truth.py) tests it against others.

A roller rig (4 rows, 14-26 rollers each, radius 2-3.5 mm, length 6-10 mm, preload 4-12 kN, a
moving mass of 1.5-5 kg, [lubricant] of the paper) with the feed of the paper's rig (5 Hz,
0.1-0.3 m/s with a third harmonic) under a normal force of a static part (0-2 kN) plus a
harmonic one (0.1-0.6 of the preload at 2-8 kHz). The rig file states the user's model; the
record comes from the truth:

* ``none``: the stated model;
* ``lubricant_film``: stated dry_hertz, the truth lubricated (ehl) with the stated lubricant;
* ``preload_loss``: the truth's preload 0.3-0.8 of the stated one;
* ``unmodeled_mass``: the truth's mass 1.2-2 times the stated one;
* ``structural_mode`` (outside the vocabulary, expected ``unknown``): a lightly damped mode of
  the rig's frame at 300-1500 Hz excited by the normal force adds to the displacement.

The compared channel is vertical_displacement (with a sensor offset) or vertical_acceleration
(with a small bias), white noise of 0.5-1.5 % of its range, sampled at ``rate`` with an optional
jitter.
"""
from __future__ import annotations

import dataclasses
import math
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.signal import lfilter

from guideway_fmu.physics.papers import soleimanian2020
from guideway_fmu.physics.roller_guide.film import LineContact
from guideway_fmu.diagnose.run_io import FORMAT, load_run
from guideway_fmu.diagnose.vertical import VerticalRig

EFFECTS = {"none": "none", "lubricant_film": "lubricant_film", "preload_loss": "preload_loss",
           "unmodeled_mass": "unmodeled_mass", "structural_mode": "unknown"}


@dataclass(frozen=True)
class VerticalTruth:
    """What a vertical record hides: effect, expected answer, channel and truth parameters."""

    effect: str
    expected: str
    channel: str
    parameters: dict
    noise_rms: float


def _rig_toml(path: Path, mass, guideway, contact, channel) -> None:
    rows = [f'format = "{FORMAT}"', "", "[rig]", 'kind = "vertical_response"',
            'description = "synthetic vertical run (guideway_synthetic/truth_vertical.py)"',
            f"moving_mass = {mass!r}", "", "[guideway]", 'type = "roller"']
    rows += [f"{k} = {v!r}" for k, v in guideway.items()]
    rows += ["", "[lubricant]", f"viscosity = {LineContact.viscosity!r}",
             f"pressure_viscosity = {LineContact.pressure_viscosity!r}", "", "[model]",
             'friction = "coulomb"', f'contact = "{contact}"', "", "[channels]",
             'inputs = ["feed_position", "feed_velocity", "normal_force"]',
             f'outputs = ["{channel}"]']
    path.write_text("\n".join(rows) + "\n", encoding="utf-8")


def _write_csv(path: Path, columns: dict) -> None:
    names = list(columns)
    np.savetxt(path, np.column_stack([columns[n] for n in names]), delimiter=",",
               header=",".join(names), comments="", fmt="%.12g")


def _truth(rig: VerticalRig, effect: str, rng, mass: float) -> tuple[np.ndarray, dict]:
    """The clean compared channel of the truth behind ``effect`` and its parameters."""
    truth, parameters = rig.base, {}
    if effect == "lubricant_film":
        truth = dataclasses.replace(truth, contact="ehl")
    elif effect == "preload_loss":
        parameters["preload_factor"] = float(rng.uniform(0.3, 0.8))
        truth = dataclasses.replace(truth, preload=truth.preload * parameters["preload_factor"])
    elif effect == "unmodeled_mass":
        parameters["extra_mass"] = float(rng.uniform(0.2, 1.0)) * mass
        truth = dataclasses.replace(truth, mass=mass + parameters["extra_mass"])
    return rig.predict(truth), parameters


def make_run(out_dir, effect: str, rng: np.random.Generator, fmu_dir, *, duration: float = 0.05,
             rate: float = 1e5, noise: float = 0.01, channel: str = "vertical_displacement",
             jitter: bool = False) -> VerticalTruth:
    """Draw and write one vertical run hiding ``effect`` into ``out_dir``; its truth. The FMUs
    the model needs are taken from (or built into) ``fmu_dir``."""
    if effect not in EFFECTS:
        raise ValueError(f"effect must be one of {list(EFFECTS)}, got {effect!r}")
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    n = int(round(duration * rate))
    t = (np.arange(n) + (rng.uniform(0, 0.5, n) if jitter else 0.0)) / rate
    v_max, phase = rng.uniform(0.1, 0.3), rng.uniform(0, 2 * math.pi)
    w = 2 * math.pi * soleimanian2020.FEED_FREQUENCY
    u = v_max * (np.sin(w * t + phase) + 0.06 * np.sin(3 * w * t + 0.6 * phase))
    x = v_max * ((np.cos(phase) - np.cos(w * t + phase)) / w
                 + 0.06 * (np.cos(0.6 * phase) - np.cos(3 * w * t + 0.6 * phase)) / (3 * w))
    guideway = {"rows": 4, "elements_per_row": int(rng.integers(14, 27)),
                "element_radius": round(float(rng.uniform(2e-3, 3.5e-3)), 5),
                "roller_length": round(float(rng.uniform(6e-3, 10e-3)), 5),
                "contact_angle_deg": 45.0, "preload": round(float(rng.uniform(4e3, 12e3)), 0)}
    mass = round(float(rng.uniform(1.5, 5.0)), 3)
    load = (rng.uniform(0, 2e3) + rng.uniform(0.1, 0.6) * guideway["preload"]
            * np.sin(2 * math.pi * rng.uniform(2e3, 8e3) * t + rng.uniform(0, 2 * math.pi)))
    stated = "dry_hertz" if effect == "lubricant_film" else str(rng.choice(["dry_hertz", "ehl"]))
    # the record's inputs first: the rig draws its model's systems from them
    _rig_toml(out / "rig.toml", mass, guideway, stated, channel)
    _write_csv(out / "data.csv", {"time": t, "feed_position": x, "feed_velocity": u,
                                  "normal_force": load, channel: np.zeros(n)})
    with tempfile.TemporaryDirectory() as folder:
        rig = VerticalRig(load_run(out), Path(folder), fmu_dir)
        rig.rtol = 1e-9
        clean, parameters = _truth(rig, effect, rng, mass)
    if effect == "structural_mode":  # a mode of the frame, driven by the load, in the reading
        f_mode, zeta = float(rng.uniform(300, 1500)), 0.02
        r, theta = math.exp(-zeta * 2 * math.pi * f_mode / rate), 2 * math.pi * f_mode / rate
        mode = lfilter([1.0], [1.0, -2 * r * math.cos(theta), r * r], load - load.mean())
        parameters.update(mode_frequency=f_mode)
        clean = clean + rng.uniform(0.2, 0.5) * np.ptp(clean) * mode / np.ptp(mode)
    noise_rms = noise * float(np.ptp(clean))
    offset = (rng.uniform(-0.5, 0.5) if channel == "vertical_displacement" else
              rng.uniform(-0.02, 0.02)) * float(np.ptp(clean))
    measured = clean + offset + noise_rms * rng.standard_normal(n)
    _write_csv(out / "data.csv", {"time": t, "feed_position": x, "feed_velocity": u,
                                  "normal_force": load, channel: measured})
    return VerticalTruth(effect, EFFECTS[effect], channel,
                         {"moving_mass": mass, "stated_contact": stated, **parameters}, noise_rms)
