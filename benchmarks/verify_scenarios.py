"""Accuracy of the co-simulation on every shipped scenario, written to docs/accuracy.md.

Each scenario runs through the master at its own step and through the monolithic reference
(LSODA, or RK45 where a model is not smooth; rtol 1e-10) on the same grid (``guideway-fmu verify``); the page lists the RMS error of
Contact.F_upper (or, in a system without it, the scenario's first plotted variable) relative to
its range and the two wall times side by side.

    python benchmarks/verify_scenarios.py [--fmus fmus] [--stop S] [--out docs/accuracy.md] [NAME ...]
"""
from __future__ import annotations

import argparse
from pathlib import Path

from guideway_fmu import scenarios
from guideway_fmu.components.build import ensure
from guideway_fmu.cosim import system
from guideway_fmu.reference.verify import verify

SIGNAL = "Contact.F_upper"
NOTES = """\
Under the default preload reading no roller lifts off except near resonance (9000 N /
5000 Hz, 12000 N / 4500 and 9000 Hz): those cycles are steep in their parameters (a 0.05 %
heavier rail moves the upper load by about 12 % of its range) but deterministic, and the
co-simulation converges to the reference with the step (docs/unloaded-film.md). Under the light
reading (9200 N over all 80 rollers, rows lifting every cycle) four responses are not followed
pointwise by any integrator (`orchestration/reference_sensitivity.py` disturbs the reference's
start and changes its tolerance): dry 9000 N / 2500 Hz is chaotic, and 9000 N / 3000 Hz and
12000 N / 2500 and 3000 Hz move by several per cent with a 1e-10 m start offset; only their
statistics (envelope, spectrum) are meaningful there.

The ball-to-ball friction of `lin2019_ball_to_ball_friction` jumps wherever two balls touch or
part, and held inputs move those instants by a step: its pointwise error is the jumps'; between
them the median error is 1.6e-4 of the range and the mean friction agrees to 0.07 %
(docs/ball-to-ball.md). `wear_preload_loss` follows a running-distance input, which the
reference, integrating in time, cannot model; docs/wear.md says how its Wear FMU is checked.
"""


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("names", nargs="*", help="shipped scenarios (default: all)")
    p.add_argument("--fmus", type=Path, default=Path("fmus"), help="FMU folder (built where missing)")
    p.add_argument("--stop", type=float, default=None, help="shorter runs [s] (default: the scenarios')")
    p.add_argument("--out", type=Path, default=Path(__file__).resolve().parents[1] / "docs" / "accuracy.md")
    args = p.parse_args()
    ensure(args.fmus)
    rows = []
    for name in args.names or scenarios.names():
        s = system.load(scenarios.find(name), args.fmus)
        if args.stop is not None:
            s = s.with_changes(stop=args.stop)
        try:
            r = verify(s)
        except ValueError as refused:  # a component the reference has no model of
            rows.append(f"| {name} | - | {s.experiment.step * 1e6:g} us | not compared: {refused} "
                        f"| | | |")
            print(rows[-1], flush=True)
            continue
        signal = SIGNAL if SIGNAL in r["rms_error"] else s.plots["time"][0]
        rows.append(f"| {name} | {signal} | {s.experiment.step * 1e6:g} us "
                    f"| {100 * r['rms_error'][signal]:.3g} "
                    f"| {r['wall_time_cosim']:.2f} | {r['wall_time_reference']:.2f} "
                    f"| {r['wall_time_cosim'] / r['wall_time_reference']:.2f} |")
        print(rows[-1], flush=True)
    span = "the whole cycle" if args.stop is None else f"{args.stop:g} s"
    args.out.write_text("\n".join([
        "# Co-simulation accuracy on the shipped scenarios", "",
        f"Written by `python benchmarks/verify_scenarios.py{'' if args.stop is None else f' --stop {args.stop:g}'}`"
        "; do not edit.", "",
        f"RMS error of `{SIGNAL}` (or the first plotted variable) over {span}, in % of its range, of the stabilised master at each "
        "scenario's step against the monolithic reference (LSODA, or RK45 where a model is not "
        "smooth such as the lubricated contact; rtol 1e-10), and both wall "
        "times [s] measured in the same run (the machine's load moves them; their ratio less).", "",
        "| scenario | signal | step | error [%] | co-simulation [s] | reference [s] | ratio |",
        "| --- | --- | --- | --- | --- | --- | --- |", *rows, "", NOTES]))
    print(args.out)


if __name__ == "__main__":
    main()
