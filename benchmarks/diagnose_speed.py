"""Wall time of the whole discrepancy workflow (``guideway-fmu diagnose``, the Python function
diagnose.workflow.diagnose) against the issue's targets, on a horizontal and a vertical record.

    python benchmarks/diagnose_speed.py [--horizontal presliding_hysteresis] [--seed 1]
                                        [--vertical unmodeled_mass] [--vertical-seed 1]

(i) a first-generator horizontal record (guideway_synthetic/truth.py) of HORIZONTAL_SAMPLES samples,
target HORIZONTAL_TARGET; (ii) a first-generator vertical record (guideway_synthetic/truth_vertical.py)
of VERTICAL_DURATION at VERTICAL_RATE (20,000 samples), target VERTICAL_TARGET. The FMUs are
built once into a temporary folder beforehand (not timed). Prints, per record, the named
effect against the hidden one, the wall time of diagnose split into its decision and its
realisation (the rest: report and plots), and target / measured (above 1: the target is met).
"""
from __future__ import annotations

import argparse
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

from guideway_fmu.fmu_build.build import build
from guideway_fmu.diagnose import workflow
from guideway_synthetic import truth, truth_vertical

# the targets
HORIZONTAL_SAMPLES, HORIZONTAL_TARGET = 10_000, 15.0  # samples, s
VERTICAL_DURATION, VERTICAL_RATE, VERTICAL_TARGET = 0.2, 1e5, 60.0  # s, Hz, s
STEPS = {"decide": ("decide", "decide_vertical"), "realise": ("realise", "realise_vertical")}


def timed_diagnose(run: Path, out: Path, fmus: Path) -> tuple[dict, float, dict]:
    """(diagnosis.json's content, wall time of diagnose [s], {step: wall time [s]}): the steps
    timed by wrapping the workflow's calls to them."""
    spent, originals = {}, {}

    def wrap(step, function):
        def timed(*args, **kwargs):
            started = time.perf_counter()
            try:
                return function(*args, **kwargs)
            finally:
                spent[step] = spent.get(step, 0.0) + time.perf_counter() - started
        return timed

    for step, names in STEPS.items():
        for name in names:
            originals[name] = getattr(workflow, name)
            setattr(workflow, name, wrap(step, originals[name]))
    try:
        started = time.perf_counter()
        diagnosis = workflow.diagnose(run, out, fmu_dir=fmus)
        return diagnosis, time.perf_counter() - started, spent
    finally:
        for name, function in originals.items():
            setattr(workflow, name, function)


def report(label: str, expected: str, diagnosis: dict, wall: float, spent: dict,
           target: float) -> None:
    rest = wall - sum(spent.values())
    print(f"{label}: named {diagnosis['missing_effect']!r} (hidden: {expected!r})")
    print(f"  diagnose {wall:7.1f} s   target {target:5.1f} s   target/measured "
          f"{target / wall:5.2f}")
    print("  " + "   ".join(f"{step} {spent.get(step, 0.0):6.1f} s" for step in STEPS)
          + f"   report {rest:5.1f} s")


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--horizontal", default="presliding_hysteresis",
                        help="effect hidden in the horizontal record (guideway_synthetic/truth.py)")
    parser.add_argument("--seed", type=int, default=1, help="seed of the horizontal record")
    parser.add_argument("--vertical", default="unmodeled_mass",
                        help="effect hidden in the vertical record (guideway_synthetic/truth_vertical.py)")
    parser.add_argument("--vertical-seed", type=int, default=1)
    args = parser.parse_args(argv)
    warnings.simplefilter("ignore")
    with tempfile.TemporaryDirectory() as folder:
        folder = Path(folder)
        fmus = folder / "fmus"
        build(fmus)
        info = truth.make_run(folder / "horizontal", args.horizontal,
                              np.random.default_rng(args.seed), n_samples=HORIZONTAL_SAMPLES)
        diagnosis, wall, spent = timed_diagnose(folder / "horizontal", folder / "out_h", fmus)
        report(f"horizontal, {HORIZONTAL_SAMPLES} samples", info.expected, diagnosis, wall,
               spent, HORIZONTAL_TARGET)
        hidden = truth_vertical.make_run(folder / "vertical", args.vertical,
                                         np.random.default_rng(args.vertical_seed), fmus,
                                         duration=VERTICAL_DURATION, rate=VERTICAL_RATE)
        diagnosis, wall, spent = timed_diagnose(folder / "vertical", folder / "out_v", fmus)
        samples = int(round(VERTICAL_DURATION * VERTICAL_RATE))
        report(f"vertical, {samples} samples ({VERTICAL_DURATION} s at "
               f"{VERTICAL_RATE / 1e3:g} kHz)", hidden.expected, diagnosis, wall, spent,
               VERTICAL_TARGET)


if __name__ == "__main__":
    main()
