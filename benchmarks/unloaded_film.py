"""How the loaded results of Soleimanian et al. (2020) depend on the rule for the film of a
roller whose load vanishes, written to docs/unloaded-film.md.

The model has no such rule any more (physics/film.py, "The film of an unloaded roller"): the
film state of a lifted roller grows at the squeeze relation's limit |u| S_MAX / 132. This
script puts back the floor the project used before (the unsqueezed film held at its value for
loads below a floor F_f) by wrapping RowKernel.film_rate for the run, and compares, over the
first ``--stop`` seconds of the 9000 N / 4500 Hz and 9000 N / 2500 Hz scenarios (monolithic
reference, rtol 1e-10, at the scenario's macro-step grid):

* the RMS change of the upper roller's load and film against the floor-free model, over the
  floor-free RMS of each, for floors of 4 N to 1e-60 N. A floor enters through h / h_s =
  h F_f^m / C (m = 0.045), so the change falls only as F_f^m: at 1e-9 N it is still about half
  that of 0.4 N. Once h F_f^m / C is under 0.01 the squeeze exponent's bound (S_MAX) takes
  over and the floored model is the floor-free one exactly (1e-60 N);
* the co-simulation (stabilised coupling, the scenario's FMUs) at macro steps of 2, 1 and
  0.5 us against the reference: the floor-free model converges with the step.

    python benchmarks/unloaded_film.py [--stop 0.01] [--out docs/unloaded-film.md]
"""
from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import numpy as np

from guideway_fmu import scenarios
from guideway_fmu.components import build
from guideway_fmu.cosim import master, system
from guideway_fmu.physics.guideway import RowKernel
from guideway_fmu.reference import monolithic

ROOT = Path(__file__).resolve().parents[1]
CASES = ("soleimanian2020_9000N_4500Hz", "soleimanian2020_9000N_2500Hz")
FLOORS = (4.0, 0.4, 1e-3, 1e-9, 1e-20, 1e-60)  # N
STEPS = (2e-6, 1e-6, 5e-7)  # s
COLUMNS = ("Contact.F_upper", "Contact.h_upper")


def floored(floor: float):
    """RowKernel.film_rate with the unsqueezed film held at its value for loads below
    ``floor`` [N] (the rule this project used before, at 0.4 N)."""
    free = RowKernel.film_rate

    def rate(self, h, load, speed):
        return free(self, h, max(load, floor), speed)
    return rate


def reference(s, floor: float | None) -> dict:
    original = RowKernel.film_rate
    try:
        if floor is not None:
            RowKernel.film_rate = floored(floor)
        ref = monolithic.simulate(s, rtol=1e-10, columns=list(COLUMNS))
    finally:
        RowKernel.film_rate = original
    return {c: ref.columns[c] for c in COLUMNS} | {"time": ref.time}


def rms(x) -> float:
    return float(np.sqrt(np.mean(np.square(x))))


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--stop", type=float, default=0.01, help="simulated time [s]")
    parser.add_argument("--out", default=str(ROOT / "docs" / "unloaded-film.md"))
    args = parser.parse_args(argv)
    began = time.perf_counter()
    fmus = build.ensure(Path(tempfile.mkdtemp()) / "fmus")
    lines = ["# The film of a roller that lifts off", "",
             f"Written by `python benchmarks/unloaded_film.py --stop {args.stop:g}`; rerun it "
             "after changing the film or the contact.", "",
             "The film law h_s ~ F^-0.045 of Soleimanian et al. (2020) eq. 4 diverges as a "
             "roller's load vanishes. The model follows the squeeze relation to its limit "
             "instead (physics/film.py): a lifted roller keeps its film, which grows at "
             "|u| S_MAX / 132 until the roller lands again. Below, the floor this project used "
             "before (the unsqueezed film held at its value for loads under F_f; 0.4 N) is put "
             "back for comparison. A floor enters through h / h_s = h F_f^m / C (m = 0.045): "
             "the change falls only as F_f^m, and vanishes exactly once that ratio is under "
             "0.01, where the squeeze exponent's bound S_MAX takes over (physics/film.py).", ""]
    for name in CASES:
        s = system.load(scenarios.find(name), fmus).with_changes(stop=args.stop)
        free = reference(s, None)
        lines += [f"## {name} (first {1e3 * args.stop:g} ms)", "",
                  "Change against the floor-free model, RMS over the floor-free RMS of each "
                  "(the last column is F_f^0.045 over 0.4^0.045: the change the floor's share of "
                  "h / h_s predicts, relative to that of 0.4 N):", "",
                  "| floor F_f [N] | upper roller load | upper film | F_f^m / 0.4^m |",
                  "| --- | --- | --- | --- |"]
        for floor in FLOORS:
            run = reference(s, floor)
            load, film = (rms(run[c] - free[c]) / rms(free[c]) for c in COLUMNS)
            lines.append(f"| {floor:g} | {load:.3g} | {film:.3g} | "
                         f"{(floor / 0.4) ** 0.045:.3g} |")
        lines += ["", "Co-simulation (stabilised coupling, the scenario's FMUs) against the "
                  "floor-free reference, RMS over the reference's range of the upper load:", "",
                  "| macro step [us] | error | wall time [s] |", "| --- | --- | --- |"]
        for step in STEPS:
            run = master.simulate(s.with_changes(step=step))
            ref = np.interp(run.recording.time, free["time"], free[COLUMNS[0]])
            error = rms(run.recording.columns[COLUMNS[0]] - ref) / float(np.ptp(ref))
            lines.append(f"| {1e6 * step:g} | {error:.3g} | {run.wall_time:.2f} |")
        lines.append("")
    lines.append(f"Wall time of this script: {time.perf_counter() - began:.0f} s.")
    text = "\n".join(lines) + "\n"
    print(text)
    if args.out != "-":
        Path(args.out).write_text(text)


if __name__ == "__main__":
    main()
