"""Convert the friction tests of Zillen, Vallery and Smit's 3D-printed pneumatic actuators (TU Delft,
2021; github.com/EvaZillen/3D-printed-pneumatic-actuator, CC0 1.0) into measured runs.

Usage::

    python orchestration/real_data/convert_tud_pneumatic_seals.py RAW_DIR OUT_DIR [--repeatability]

RAW_DIR is the repository as fetched (or any folder holding it): every ``*.csv`` under a
``data/friction`` folder is converted, the repeatability re-runs (under ``data/repeatability``)
only with ``--repeatability``. One run directory per file, named after it
(``O-ring_3bar.csv`` -> ``OUT_DIR/O-ring_3bar/``), each with rig.toml and data.csv in the format
of docs/measured-run.md. The converted runs belong in a scratch folder (e.g.
/tmp/real_runs/tud_pneumatic_seals), not in the repository.

What the record is (the repository's README, results README and friction notebook):
a piston with one seal (O-ring, NAPN, NAP310, PK, KDN, X-ring; or an O-ring in a 3D-printed
cylinder of non-circular cross-section: Circle, Stadium, Kidney, ``_lc`` = 0.2 mm instead of
0.5 mm clearance) in a 3D-printed cylinder held at a constant pressure (1 to 7 bar) is pushed in
and out about ten times over about 40 mm by a linear test drive at roughly 10 mm/s; a laser
measures the piston position, a load cell the force on the piston rod, a transducer the pressure.
Each file is whitespace separated, no header, seven columns: time [ms], laser [V], pressure [V],
force [V], laser [mm], pressure [bar], force [N].

Conversion (every assumption):

- ``time`` = column 1 / 1000 [s]. Sampling is about 100 Hz with pauses (up to a few seconds at
  the start); the format allows uneven sampling. The first 15 samples are dropped, as the authors
  do ("deviating starting values"); after that each file was checked to increase strictly.
- ``feed_position`` = column 5 / 1000 [m], the laser distance as recorded (its zero and direction
  are the laser's: it grows while the piston retracts, see the sign below). Single-sample laser
  glitches of a few tenths of a millimetre are left in: the record is converted, not cleaned.
- ``friction_force`` = force [N] - pressure [bar] * 1e5 * A, the authors' friction force
  (their report's eq. 3): the rod force minus the pressure force on the piston area
  A = pi (D/2)^2 with the bore D = 25 mm, or D = 25.7 mm for the ``O-ring257``/``X-ring257``
  cylinders, as in their notebook. It keeps the constant offset the pressure calibration leaves
  (a few newtons); the workflow calibrates a sensor offset itself.
- Sign: the authors take the part above the mean as the retracting stroke (the drive pushes the
  piston in against the pressure and the friction, so the rod force exceeds p A by the friction);
  in the records that part is the one where the laser distance grows. The channel is therefore the
  force the drive applies against the friction, along the motion:
  ``[channels] friction_sign = "along_motion"``.
- ``[rig] moving_mass = 0``: the friction force is derived by the rig itself (pressure force
  taken off), and the strokes run at nearly constant speed (the inertia of a piston of a few tens
  of grams at the reversals is far below a newton).
- The pressure is not a channel of the format's vocabulary (it is not a normal force on a guide),
  so it is stated in the description (its mean over the file) and not written as a column; the
  seal's normal load grows with it, which is what the authors study.
- No ``[guideway]``: there is no rolling guide; the contact is an elastomer seal sliding in a
  printed bore. ``[model] friction = "coulomb"`` is the baseline; no contact component.

Published finding: the thesis' friction notebook plots, against the pressure, the "dynamic
friction force range" of each seal and bore shape: the mean friction of the retracting strokes
minus that of the extending strokes (about twice the sliding friction). Recomputed from these
files with that definition over each whole file, it grows with the pressure: O-ring 7.8, 10.9,
13.8, 15.6 N at 1, 3, 5, 7 bar; NAPN 6.7, 13.7, 19.0, 23.2 N; PK 5.2, 7.1, 10.7, 12.9 N; X-ring
(25.7 mm) 9.0, 12.9, 17.0, 29.7 N. Note: ``Circle_1bar``,
``Circle_3bar``, ``Circle_5bar`` and ``Circle_7bar`` are byte-identical to the ``O-ring`` files of
the same pressure in the repository (the circular bore is the O-ring model of the 25 mm set).
"""
from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

import numpy as np

SHORT_NAME = "tud_pneumatic_seals"
SOURCE = "https://github.com/EvaZillen/3D-printed-pneumatic-actuator"
DROP = 15  # leading samples the authors drop
BORE = 25.0e-3  # m
LARGE_BORE = 25.7e-3  # m, the O-ring257 / X-ring257 cylinders


def friction_files(raw_dir: Path, repeatability: bool = False) -> list[Path]:
    """The friction-test files under ``raw_dir``: ``*/data/friction/*.csv`` (and, with
    ``repeatability``, the re-runs under ``data/repeatability``), sorted."""
    raw_dir = Path(raw_dir)
    found = [p for p in raw_dir.rglob("*.csv")
             if p.parent.name == "friction" and p.parent.parent.name == "data"]
    if repeatability:
        found += [p for p in raw_dir.rglob("*.csv")
                  if p.parent.name == "friction" and "repeatability" in p.parts]
    return sorted(set(found))


def run_name(path: Path, raw_dir: Path) -> str:
    """Run directory name: the file's stem, prefixed by the re-run folders for repeatability
    files (``repeatability/rerun/friction/1_O-ring257_3bar.csv`` -> ``rerun_1_O-ring257_3bar``)."""
    if "repeatability" in path.parts:
        return f"{path.parent.parent.name}_{path.stem}"
    return path.stem


def convert_file(path: Path, run_dir: Path) -> Path:
    """Write one run directory from one friction-test file; return it."""
    raw = np.loadtxt(path)
    if raw.ndim != 2 or raw.shape[1] != 7:
        raise ValueError(f"{path}: expected 7 whitespace-separated columns, got shape {raw.shape}")
    raw = raw[DROP:]
    time = raw[:, 0] / 1000.0
    keep = np.ones(time.size, dtype=bool)
    keep[1:] = np.diff(time) > 0.0
    if not keep.all():  # not seen in the published files; refuse rather than guess
        bad = int(np.flatnonzero(~keep)[0]) + DROP
        raise ValueError(f"{path}: row {bad + 1}: time does not increase")
    position = raw[:, 4] / 1000.0
    pressure_bar, rod_force = raw[:, 5], raw[:, 6]
    bore = LARGE_BORE if "257" in path.stem else BORE
    area = math.pi * (bore / 2.0) ** 2
    friction = rod_force - pressure_bar * 1e5 * area
    run_dir.mkdir(parents=True, exist_ok=True)
    with (run_dir / "data.csv").open("w", encoding="utf-8", newline="\n") as out:
        out.write("time,feed_position,friction_force\n")
        for t, x, f in zip(time, position, friction):
            out.write(f"{t:.3f},{x:.6e},{f:.5f}\n")
    description = (
        f"Zillen, Vallery, Smit (TU Delft 2021), 3D-printed pneumatic actuator friction test "
        f"{path.name}: piston seal in a printed cylinder at {np.mean(pressure_bar):.2f} bar "
        f"(mean), pushed in and out by a test drive; feed_position = laser [mm]/1000; "
        f"friction_force = rod force - p * A, A = pi/4 * ({bore * 1e3:.1f} mm)^2; first {DROP} "
        f"samples dropped as by the authors. Source {SOURCE} (CC0 1.0).")
    (run_dir / "rig.toml").write_text(
        'format = "guideway-measured-run/1"\n\n'
        "[rig]\n"
        'kind = "horizontal_drive"\n'
        f"description = {_toml_string(description)}\n"
        "moving_mass = 0.0\n\n"
        "[model]\n"
        'friction = "coulomb"\n\n'
        "[channels]\n"
        'inputs = ["feed_position"]\n'
        'outputs = ["friction_force"]\n'
        'friction_sign = "along_motion"\n', encoding="utf-8")
    return run_dir


def convert(raw_dir, out_dir, repeatability: bool = False) -> list[Path]:
    """Convert every friction-test file under ``raw_dir`` into ``out_dir``/<name>/; return the
    run directories. Raises FileNotFoundError when ``raw_dir`` holds none."""
    raw_dir, out_dir = Path(raw_dir), Path(out_dir)
    files = friction_files(raw_dir, repeatability)
    if not files:
        raise FileNotFoundError(f"{raw_dir}: no data/friction/*.csv files (expected the "
                                f"repository {SOURCE} as fetched)")
    return [convert_file(p, out_dir / run_name(p, raw_dir)) for p in files]


def _toml_string(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("raw_dir", type=Path, help="the repository as fetched")
    parser.add_argument("out_dir", type=Path, help="where the run directories go")
    parser.add_argument("--repeatability", action="store_true",
                        help="also convert the re-runs under data/repeatability")
    args = parser.parse_args(argv)
    try:
        runs = convert(args.raw_dir, args.out_dir, args.repeatability)
    except (OSError, ValueError) as exc:
        print(f"convert_{SHORT_NAME}: error: {exc}", file=sys.stderr)
        return 2
    for run in runs:
        print(run)
    return 0


if __name__ == "__main__":
    sys.exit(main())
