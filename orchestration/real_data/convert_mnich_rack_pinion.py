"""Convert Konrad Mnich's friction-identification record of a rack-and-pinion mechanism (Lodz
University of Technology, 2020; github.com/KonradMnich/friction-identification) into a measured
run.

Usage::

    python orchestration/real_data/convert_mnich_rack_pinion.py RAW_DIR OUT_DIR

RAW_DIR is the repository as fetched (or any folder holding it): the two acquisition files
``a3NI.csv`` (National Instruments card: load-cell voltage) and ``a3MR.csv`` (the servo
amplifier's monitor: motor speed) are looked for below it. One run directory is written,
``OUT_DIR/a3/`` with rig.toml and data.csv in the format of docs/measured-run.md. The converted
run belongs in a scratch folder (e.g. /tmp/real_runs/mnich_rack_pinion), not in the repository.

What the record is (the repository's README and its MATLAB scripts acquisition.m,
conditioning.m, extraction.m): the author's test rig for friction in a rack-and-pinion mechanism;
a servo motor moves it (its speed converts to the linear speed at 20 mm per motor revolution) and
a load cell measures the force that moves it. The rig's layout beyond that is described in the
author's article linked from the README, which was not available here. One point-to-point
stroke of about 0.15 m: the moving part accelerates at about 3 m/s^2 to about 0.65 m/s and
decelerates back to rest, in one direction only, in about half a second.

Conversion (every assumption, the constants being the author's, from his scripts):

- Load cell (a3NI.csv: header of 4 lines, then time [s], voltage [V], time, second channel;
  2 kHz): force = -200 N/V * (U - mean of the first 10 samples of U), the author's calibration
  (200 N/V), sign (his minus) and zero (the rest before the motion).
- Motor speed (a3MR.csv: header of 5 lines, then time [ms] and "Servo motor speed" [rpm] among
  other monitor channels; 0.667 ms): feed velocity = -speed * 20 mm / 60 s per rpm, the author's
  conversion (20 mm of travel per motor revolution) and sign. The speed is an integer number of
  rpm: steps of 0.33 mm/s.
- The load-cell clock lags the servo monitor by 4 ms (the author's time shift); the force is
  shifted by it and interpolated linearly onto the monitor's samples where both overlap (the
  author also resamples onto the monitor's time base); samples outside the overlap are dropped.
- ``feed_position`` = the cumulative trapezoidal integral of that velocity from 0 (the author's
  distance); it is written as a column but not listed as an input, the measured velocity is.
- ``drive_force`` = the load-cell force: the force the drive applies to the mechanism, along the
  positive direction of the velocity.
- ``[rig] moving_mass = 24.7`` kg: the author's reduced mass of the moving parts (extraction.m).
- No [guideway] (a rack and pinion, no rolling guide the format describes); ``[model]
  friction = "coulomb"``. The author's filter (2nd-order Butterworth at 30 Hz) is not applied:
  the record is converted, not conditioned.

The author's finding (output/coeffs_for_friction_model.mat, fitted by his friction_model.m to the
force minus 24.7 kg times the acceleration): dry friction 10.0 N, viscous 67.4 N s/m, and a
velocity-weakening hump reaching 29.6 N at 0.0135 m/s, i.e. F(v) = 10.0 + 67.4 v
+ (29.6 - 10.0) (v / 0.0135) e^(1 - v / 0.0135) for v >= 0.

The record moves one way only, which the workflow refuses (it needs strokes in both directions
to tell the Coulomb level from a force offset); converting it is still useful: the refusal is a
finding.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np
from scipy.integrate import cumulative_trapezoid

SHORT_NAME = "mnich_rack_pinion"
SOURCE = "https://github.com/KonradMnich/friction-identification"
LOAD_CELL = 200.0  # N/V
MM_PER_REV = 20.0  # mm of travel per motor revolution
LAG = 0.004  # s, the load-cell clock behind the servo monitor
REDUCED_MASS = 24.7  # kg
ZERO_SAMPLES = 10


def _find(raw_dir: Path, name: str) -> Path:
    hits = sorted(Path(raw_dir).rglob(name))
    if not hits:
        raise FileNotFoundError(f"{raw_dir}: no {name} below it (expected the repository "
                                f"{SOURCE} as fetched)")
    return hits[0]


def _numbers(path: Path, skip: int, columns: tuple[int, ...]) -> np.ndarray:
    rows = []
    with path.open(encoding="utf-8", errors="replace") as handle:
        for i, line in enumerate(handle):
            if i < skip or not line.strip():
                continue
            cells = line.strip().split(",")
            try:
                rows.append([float(cells[c]) for c in columns])
            except (ValueError, IndexError):
                raise ValueError(f"{path}: row {i + 1}: expected numbers in columns "
                                 f"{[c + 1 for c in columns]}") from None
    return np.array(rows)


def convert(raw_dir, out_dir) -> list[Path]:
    """Convert the record under ``raw_dir`` into ``out_dir``/a3/; return [that directory]."""
    raw_dir, out_dir = Path(raw_dir), Path(out_dir)
    ni = _numbers(_find(raw_dir, "a3NI.csv"), 4, (0, 1))
    mr = _numbers(_find(raw_dir, "a3MR.csv"), 5, (0, 1))
    t_force = ni[:, 0] + LAG
    force = -LOAD_CELL * (ni[:, 1] - np.mean(ni[:ZERO_SAMPLES, 1]))
    t = mr[:, 0] / 1000.0
    velocity = -mr[:, 1] * MM_PER_REV / 1000.0 / 60.0
    inside = (t >= t_force[0]) & (t <= t_force[-1])
    t, velocity = t[inside], velocity[inside]
    force = np.interp(t, t_force, force)
    position = cumulative_trapezoid(velocity, t, initial=0.0)
    if np.any(np.diff(t) <= 0.0):
        raise ValueError(f"{raw_dir}: the servo monitor's time does not increase strictly")
    run_dir = out_dir / "a3"
    run_dir.mkdir(parents=True, exist_ok=True)
    with (run_dir / "data.csv").open("w", encoding="utf-8", newline="\n") as out:
        out.write("time,feed_velocity,feed_position,drive_force\n")
        for row in zip(t, velocity, position, force):
            out.write("{:.7f},{:.6e},{:.6e},{:.4f}\n".format(*row))
    description = (
        "Mnich (Lodz University of Technology 2020), rack-and-pinion friction identification "
        "record a3: one point-to-point stroke (about 0.15 m, up to 0.65 m/s). feed_velocity = "
        "-(motor speed [rpm]) * 20 mm / 60 s; feed_position = its integral; drive_force = "
        "-200 N/V * (load-cell voltage - its rest value), shifted by 4 ms and interpolated onto "
        f"the monitor's samples. Constants and reduced mass from the author's scripts. Source "
        f"{SOURCE} (no license file).")
    (run_dir / "rig.toml").write_text(
        'format = "guideway-measured-run/1"\n\n'
        "[rig]\n"
        'kind = "horizontal_drive"\n'
        f"description = {_toml_string(description)}\n"
        f"moving_mass = {REDUCED_MASS}\n\n"
        "[model]\n"
        'friction = "coulomb"\n\n'
        "[channels]\n"
        'inputs = ["feed_velocity"]\n'
        'outputs = ["drive_force"]\n', encoding="utf-8")
    return [run_dir]


def _toml_string(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("raw_dir", type=Path, help="the repository as fetched")
    parser.add_argument("out_dir", type=Path, help="where the run directory goes")
    args = parser.parse_args(argv)
    try:
        runs = convert(args.raw_dir, args.out_dir)
    except (OSError, ValueError) as exc:
        print(f"convert_{SHORT_NAME}: error: {exc}", file=sys.stderr)
        return 2
    for run in runs:
        print(run)
    return 0


if __name__ == "__main__":
    sys.exit(main())
