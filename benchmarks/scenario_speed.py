"""Wall time of the co-simulation, with each FMU edition, against the monolithic reference on
every shipped scenario, written to docs/speed.md.

Each scenario runs through the master at its own step (or ``--step``, for a convergence study)
with the FMU cache's python set, then its native set (``guideway-fmu build --edition native``:
compiled C where a component has a native edition), and through the reference on the recorded
grid, one after the other in this process. All
times are of the whole call, as a user makes it: ``master.simulate`` (instantiating the FMUs,
stepping, recording) and ``monolithic.simulate`` (assembling, integrating, evaluating every
output at the recorded times). The error is the RMS error of the signal
``verify`` judges, relative to its range (reference/verify.py; the criterion, which the
reference's predictability chooses, is docs/accuracy.md's). The FMI time of each instance per
macro step and the master's own overhead say where the co-simulation's time goes.

    python benchmarks/scenario_speed.py [--stop S] [--step H] [--out docs/speed.md] [NAME ...]
"""
from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from guideway_fmu import scenarios
from guideway_fmu.cosim import master, system
from guideway_fmu.fmu_build import build, cache
from guideway_fmu.cosim.observers import Observer
from guideway_fmu.reference import monolithic
from guideway_fmu.reference.verify import compare, judged_signals

import pages

TARGET, STRETCH = 1.0, 0.5  # co-simulation over reference wall time
NOTES = """\
With the native edition a component's FMI calls cost what its C physics costs plus fmpy's ctypes
call (about 1 us); the master's own part (bus, coupling, recording, in Python) is then most of
a step: the compiled stepping loop is the next step (issue 41). The paragraphs below were
measured with the python edition.

Where the co-simulation's time goes (profiles of 0.01-0.02 s runs, cProfile and the time of
each FMI call). A Soleimanian scenario makes 8 FMI calls a macro step: each
instance's inputs (one batched call per instance and type; the feed has none), its doStep and
its outputs (one batched call; where every step is recorded the recorded-only loads and films
are read in that call too); `soleimanian2020_unloaded` adds the friction FMU's inputs, doStep
and output. The master calls the FMUs' C functions directly (fmpy's Python wrapper cost about
0.4 us a call); pythonfmu's passage from C into the component's Python still costs 1.5-3 us a
call before the component does anything. Inside: the carriage's RK4 substeps (omega h <= 0.1,
two in a 4 us step, about 2 us each), the contact's film integration (Heun substeps) and
evaluation, the feed's two sines. The master's own part (bus, recording) is about 8-9 us a
step. Against the previous measurement (50.6 and 62.1 us a 4 us step of the dry and the
lubricated 9000 N / 2500 Hz runs) a step now costs about 40 and 51 us: 3 us from the direct
calls, 1.5-2 us from the master (one call fewer, no tangent bookkeeping without step control),
5 us from the carriage's substeps. The friction FMU feeds nothing back; it computes only when
its recorded output is read, about 65 us an evaluation (parabolic-cylinder functions, both rows
at once), at every 4 us record point, as the reference evaluates it at every recorded time:
half of either run's time.

The carriage's substeps, a convergence study (the error against the reference over the whole
cycle, the limit omega h <= 0.05 / 0.1 / 0.2 rad, i.e. 4 / 2 / 1 substeps in a 4 us step):
9000 N / 2500 Hz dry 0.0011 / 0.017 / 0.25 %, 9000 N / 4500 Hz dry 0.0004 / 0.017 / 0.93 %,
9000 N / 2500 Hz 0.0051 / 0.011 / 0.17 %, 12000 N / 4500 Hz (2 us) 0.26 / 0.071 / 0.071 %,
12000 N / 9500 Hz 0.076 / 0.073 / 0.066 %, 6000 N / 9000 Hz 0.021 / 0.018 / 0.013 %, 9000 N /
5000 Hz (1 us: one substep under every limit) 0.20 %. RK4's phase error, (omega h)^4 / 120 per
radian, accumulates in the undamped dry responses over the cycle's 8000 rad: 0.2 rad costs
them up to 0.9 %, 0.1 rad 0.017 %, far inside 1 % (tests/physics/roller_guide/test_carriage.py has
the study on the law itself: fourth order, 4e-6 of the range over 2 ms at 0.1 rad).

The step the accuracy needs (`--step 4e-6` against each scenario's, whole cycle, measured
with omega h <= 0.05): 0.005-0.03 % of the range for the lubricated responses that had 1 and
2 us steps before (chosen under an earlier model), 0.001 % for the dry ones (the contact's force law makes the coupling exact;
what is left is the reference's own error); only the near-resonant lift-off cycles need shorter
steps: 12000 N / 4500 Hz 0.63 % at 4 us (2 us: 0.26 %), 9000 N / 5000 Hz 5.8 % at 4 us, 2.6 %
at 2 us (1 us: 0.20 %). At 1 us that cycle costs about as much as its reference, and so does
the unloaded rig with its friction: both sit at the target, within the machine's noise.

Where the ratio is the wrong yardstick. The dry scenarios: the coupling is exact and the
reference integrates two smooth states with LSODA (1.1-1.7 s, 1.8-2.3 s with the outputs at
50 001 times); the co-simulation cannot take fewer than one macro step per record point, and a
step costs its 8 FMI calls, the carriage's two RK4 substeps and the master's bookkeeping, about
40 us: 2 s over the cycle at the 4 us record interval. `zhang2019_feed_unit_milling` has no
states: the reference integrates nothing and evaluates the same algebraic models (the feed
unit's equilibrium, about 0.5 ms in Python) at the same 10 001 times as the co-simulation, which
with the python edition can only add its calls and bookkeeping; the native edition computes the
equilibrium in C (about 0.13 ms). In both the python edition's ratio measures the FMUs' call
overhead, not the coupling; the criterion for them is the master's and the calls' cost per
communication point (the last columns), set against the components' own computation.
"""


class FmiTimes(Observer):
    """FMI time [s] of each instance over the stepping loop."""

    def started(self, system, bus):
        self.instances = bus.instances
        self.start = {n: i.fmi_time for n, i in bus.instances.items()}

    def finished(self, result):
        self.spent = {n: i.fmi_time - self.start[n] for n, i in self.instances.items()}


def cosimulate(s: system.System) -> dict:
    """The co-simulation's wall time [s], its recording and its costs per macro step [us]."""
    fmi = FmiTimes()
    t0 = time.perf_counter()
    result = master.simulate(s, observers=(fmi,))
    wall = time.perf_counter() - t0
    per_step = 1e6 / result.steps
    return {"wall": wall, "result": result, "steps": result.steps,
            "loop": result.wall_time * per_step,
            "overhead": (result.wall_time - result.fmi_time) * per_step,
            "fmi": {n: t * per_step for n, t in fmi.spent.items()}}


def measure(editions: dict[str, system.System]) -> dict:
    """Each edition's co-simulation, the reference's wall time [s] and method, the judged
    signal's RMS error / range (python edition) and the largest relative difference of any
    recorded column between the editions; raises ValueError where the reference cannot model
    the system."""
    python = editions["python"]
    monolithic.check(python)
    runs = {edition: cosimulate(s) for edition, s in editions.items()}
    rec = runs["python"]["result"].recording
    t0 = time.perf_counter()
    reference = monolithic.simulate(python, times=rec.time)
    whole = time.perf_counter() - t0
    rms, _ = compare(rec.time, rec.columns, reference)
    signal, _ = judged_signals(python, rms)
    native = runs["native"]["result"].recording
    differ = max(float(np.max(np.abs(np.asarray(native.columns[c]) - np.asarray(v)))
                       / max(float(np.max(np.abs(v))), 1e-300)) for c, v in rec.columns.items())
    native_rms, _ = compare(native.time, native.columns, reference)
    return {"runs": runs, "reference": whole, "method": reference.method, "signal": signal,
            "error": rms[signal], "native_error": native_rms[signal], "differ": differ}


def row(name: str, s: system.System, m: dict, native: list[str]) -> str:
    py, nat = m["runs"]["python"], m["runs"]["native"]
    costs = ", ".join(f"{n} {t:.1f}" for n, t in nat["fmi"].items())
    return (f"| {name} | {s.experiment.step * 1e6:g} us | {py['steps']} | "
            f"{', '.join(native) or 'none'} | {m['reference']:.2f} ({m['method']}) | "
            f"{py['wall']:.2f} | {py['wall'] / m['reference']:.2f} | {nat['wall']:.2f} | "
            f"{nat['wall'] / m['reference']:.2f} | {py['wall'] / nat['wall']:.1f} | {m['signal']} "
            f"| {100 * m['error']:.3g} | {100 * m['native_error']:.3g} | {m['differ']:.1e} "
            f"| {py['loop']:.1f} | {nat['loop']:.1f} "
            f"| {nat['overhead']:.1f} | {costs} |")


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("names", nargs="*", help="shipped scenarios (default: all)")
    p.add_argument("--stop", type=float, default=None, help="shorter runs [s] (default: the scenarios')")
    p.add_argument("--step", type=float, default=None, help="macro step [s] for every scenario "
                   "(default: each scenario's)")
    p.add_argument("--out", type=Path, default=Path(__file__).resolve().parents[1] / "docs" / "speed.md")
    args = p.parse_args()
    folders = {edition: cache.folder(edition) for edition in build.EDITIONS}
    rows, ratios, errors = [], {e: [] for e in folders}, []
    for name in args.names or scenarios.names():
        editions = {e: system.load(scenarios.find(name), folder).with_changes(
            **({} if args.stop is None else {"stop": args.stop}),
            **({} if args.step is None else {"step": args.step})) for e, folder in folders.items()}
        s = editions["python"]
        native = [c.name for c in s.components.values()
                  if build.edition_of(Path(c.fmu).stem, "native") == "native"]
        try:
            m = measure(editions)
        except ValueError as refused:  # a component the reference has no model of
            rows.append(f"| {name} | {s.experiment.step * 1e6:g} us | | {', '.join(native)} | | "
                        f"| | | | | not compared: {refused} | | | | | | | |")
        else:
            rows.append(row(name, s, m, native))
            for edition in folders:
                ratios[edition].append(m["runs"][edition]["wall"] / m["reference"])
            errors += [m["error"], m["native_error"]]
        print(rows[-1], flush=True)
    options = "".join(f" --{k} {getattr(args, k):g}" for k in ("stop", "step")
                      if getattr(args, k) is not None) + "".join(f" {n}" for n in args.names)
    if not errors:
        raise SystemExit("no scenario compared: the reference models none of them (rows above)")
    summary = " ".join(
        f"{edition.capitalize()} edition: largest ratio {max(r):.2f} (target {TARGET:g}, "
        f"stretch {STRETCH:g}), {sum(x <= TARGET for x in r)} of {len(r)} compared scenarios at "
        f"most {TARGET:g}, {sum(x <= STRETCH for x in r)} at most {STRETCH:g}."
        for edition, r in ratios.items()) + f" Largest error {100 * max(errors):.3g} %."
    print(summary)
    pages.write(args.out, "\n".join([
        "# Co-simulation speed on the shipped scenarios", "",
        "Each scenario runs through the master (the stabilised coupling at its step) with the "
        "python edition of the FMUs, then the native edition (`guideway-fmu build --edition "
        "native`: compiled C for the components listed, python for the others), and through "
        "the monolithic reference (LSODA, or RK45 where a model is not smooth; rtol 1e-10) on "
        "the recorded grid, one after the other in one process on a shared machine (the load "
        "moves the times, their ratios less). All are whole calls: the co-simulation "
        "instantiates its FMUs, steps and records; the reference assembles the system, "
        "integrates and evaluates every output at the recorded times (a system without states, "
        "such as zhang2019_feed_unit_milling, integrates nothing: its cost is the outputs). The "
        "error is the RMS error of the signal `verify` judges relative to its range, with each "
        "edition ([accuracy.md](accuracy.md) has the criterion and verdicts); the editions' difference "
        "is the largest difference of any recorded column relative to its largest value. Per "
        "macro step [us]: the stepping loop with each edition, and with the native edition the "
        "master's own part of it and each instance's FMI calls.", "",
        "| scenario | step | steps | native components | reference [s] | python co-simulation [s] "
        "| ratio | native co-simulation [s] | ratio | speed-up | signal | python error [%] | "
        "native error [%] | editions differ by | python loop / step | native loop / step | "
        "master / step | FMI / step by instance |",
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- "
        "| --- | --- | --- |", *rows, "",
        summary, "", NOTES]), f"python benchmarks/scenario_speed.py{options}", __file__,
        (f"{pages.SCENARIOS}/*.toml",))
    print(args.out)


if __name__ == "__main__":
    main()
