"""Wall time and accuracy of the co-simulation algorithms against the monolithic reference.

Soleimanian et al. (2020) at 9000 N / 4500 Hz over one feed cycle (0.2 s), all measured in one run:

(a) our stabilised master at the scenario's step;
(b) our Jacobi and Gauss-Seidel at the largest stable step of STEPS (stable: the upper-row load
    stays within twice the reference's peak over the first PROBE seconds), run over the cycle;
(c) libcosim on the exported SSP (Jacobi) at the largest step of STEPS reaching 1 % RMS error
    over PROBE seconds, run over the whole cycle (or reported as not reached);

each with its wall time and the RMS error of Contact.F_upper relative to its range, then the
ratios: stabilised / monolithic, libcosim / stabilised, and the stabilised master's own
overhead per macro step against the time spent in its FMI calls.

    python benchmarks/cosim_speed.py [--stop 0.2] [--fmus fmus]
"""
from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import numpy as np

from guideway_fmu import scenarios
from guideway_fmu.reference import monolithic
from guideway_fmu.cosim import master, ssp, system
from guideway_fmu.reference.verify import compare

SCENARIO = scenarios.find("soleimanian2020_9000N_4500Hz")
STEPS = (2e-6, 1e-6, 5e-7, 2.5e-7, 1.25e-7)  # s, candidate macro steps for (b) and (c)
PROBE = 0.01  # s, horizon of the libcosim step search
SIGNAL = "Contact.F_upper"


def error(time_, values, reference) -> float:
    rms, _ = compare(time_, {SIGNAL: values}, reference)
    return rms[SIGNAL]


def ours(scenario, reference, **changes):
    """(result, RMS error, stable); a run whose FMU gave up (the film collapsing under a
    diverging load, say) counts as unstable."""
    try:
        result = master.simulate(scenario.with_changes(**changes))
    except master.SimulationError as exc:
        return exc.result, np.inf, False
    rec = result.recording
    peak = float(np.max(np.abs(rec.columns[SIGNAL])))
    stable = np.all(np.isfinite(rec.columns[SIGNAL])) and peak < 2 * np.max(reference.columns[SIGNAL])
    return result, error(rec.time, rec.columns[SIGNAL], reference), stable


def libcosim(scenario, step: float, stop: float, reference):
    with tempfile.TemporaryDirectory() as tmp:
        package = ssp.export_ssp(scenario.with_changes(algorithm="jacobi", step=step, stop=stop),
                                 Path(tmp) / "case.ssp")
        steps = round(stop / step)
        t0 = time.perf_counter()
        try:
            t, cols = ssp.run_libcosim(package, [SIGNAL], steps)
        except RuntimeError:  # an FMU gave up (the film collapsing under a diverging load)
            return time.perf_counter() - t0, np.inf
        wall = time.perf_counter() - t0
    values = cols[SIGNAL]
    ok = np.all(np.isfinite(values))
    return wall, error(t, values, reference) if ok else np.inf


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--stop", type=float, default=0.2)
    parser.add_argument("--fmus", type=Path, default=Path("fmus"))
    args = parser.parse_args()
    scenario = system.load(SCENARIO, args.fmus).with_changes(stop=args.stop)
    grid = np.linspace(0.0, args.stop, round(args.stop / min(STEPS)) + 1)
    reference = monolithic.simulate(scenario, times=grid)
    print(f"{scenario.name}, {args.stop} s; reference {reference.method} rtol {reference.rtol:g}: "
          f"{reference.wall_time:.2f} s")

    stab, stab_err, _ = ours(scenario, reference)
    print(f"(a) stabilised, step {scenario.experiment.step:g} s: {stab.wall_time:.2f} s, "
          f"RMS error {stab_err:.2e}, {stab.steps} steps")

    probe = scenario.with_changes(stop=PROBE)
    probe_ref = monolithic.simulate(probe, times=grid[grid <= PROBE + 1e-12])
    for alg in ("jacobi", "gauss-seidel"):
        step = next((h for h in STEPS if ours(probe, probe_ref, algorithm=alg, step=h)[2]), None)
        if step is None:
            print(f"(b) {alg}: unstable at every step down to {STEPS[-1]:g} s within {PROBE} s")
            continue
        res, err, stable = ours(scenario, reference, algorithm=alg, step=step)
        print(f"(b) {alg}: largest stable step {step:g} s: {res.wall_time:.2f} s, RMS error "
              f"{err:.2e}{'' if stable else ' (diverged later in the cycle)'}")

    lc_step = next((s for s in STEPS if libcosim(scenario, s, PROBE, probe_ref)[1] <= 0.01), None)
    if lc_step is None:
        wall, lc_err = libcosim(scenario, STEPS[-1], PROBE, probe_ref)
        per_step = wall / round(PROBE / STEPS[-1])
        print(f"(c) libcosim: 1 % not reached at any step down to {STEPS[-1]:g} s over {PROBE} s "
              f"(error {lc_err:.2e}); {per_step * 1e6:.0f} us per macro step")
        lc_wall = per_step * args.stop / STEPS[-1]
        print(f"    a cycle at {STEPS[-1]:g} s would take at least {lc_wall:.0f} s")
    else:
        lc_wall, lc_err = libcosim(scenario, lc_step, args.stop, reference)
        print(f"(c) libcosim at {lc_step:g} s: {lc_wall:.2f} s, RMS error {lc_err:.2e}")

    overhead = stab.wall_time - stab.fmi_time
    print("ratios:")
    print(f"  stabilised / monolithic wall time:   {stab.wall_time / reference.wall_time:.2f} (target <= 1.0)")
    print(f"  libcosim / stabilised wall time:     {lc_wall / stab.wall_time:.1f} (target >= 10)")
    print(f"  master overhead / FMI call time:     {overhead / stab.fmi_time:.2f} (target <= 1.5); "
          f"{overhead / stab.steps * 1e6:.1f} us vs {stab.fmi_time / stab.steps * 1e6:.1f} us per step")


if __name__ == "__main__":
    main()
