"""Accuracy and speed of the discrepancy workflow on synthetic runs with hidden effects.

    python benchmarks/diagnose_accuracy.py [--draws 5] [--noise 0.015] [--samples 10000]
                                           [--jobs 2] [--out out/diagnose_accuracy] [--no-emps]

For every effect of guideway_synthetic/truth.py and ``draws`` seeds, writes a run, diagnoses it (each in
its own process) and prints the confusion table (expected answer x named effect), the held-out
gap after the named effect over the noise floor, the wall time of each diagnosis (10,000 samples
by default) and, unless --no-emps, the results on the two EMPS records.
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np

from guideway_synthetic import truth
from guideway_synthetic.trials import run_batch



def diagnose_trial(out, fmus, effect, seed, noise, samples) -> dict:
    """One synthetic trial in its own process; {"error": last line} if it fails."""
    try:
        return run_batch(out, fmus, [{"name": f"{effect}_{seed}", "effect": effect, "seed": seed,
                                      "noise": noise, "n_samples": samples}])[0]
    except RuntimeError as failure:
        return {"error": str(failure).strip().splitlines()[-1]}


def diagnose_record(run, out, fmus) -> dict:
    """The diagnosis of a recorded run through the command line, with its wall time [s]."""
    started = time.perf_counter()
    done = subprocess.run([sys.executable, "-m", "guideway_fmu.cli", "diagnose", str(run),
                           "--out", str(out), "--fmus", str(fmus)], capture_output=True, text=True)
    if done.returncode != 0:
        return {"error": done.stderr.strip().splitlines()[-1] if done.stderr else "crashed"}
    return {**json.loads((Path(out) / "diagnosis.json").read_text()),
            "seconds": time.perf_counter() - started}


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--draws", type=int, default=5)
    parser.add_argument("--noise", type=float, default=0.015)
    parser.add_argument("--samples", type=int, default=10000)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--out", type=Path, default=Path("out/diagnose_accuracy"))
    parser.add_argument("--no-emps", action="store_true")
    parser.add_argument("--data", type=Path, default=os.environ.get("GUIDEWAY_FMU_DATA"),
                        help="folder holding emps-identification/ and emps-validation/ "
                             "(default: $GUIDEWAY_FMU_DATA; without it the EMPS records are skipped)")
    args = parser.parse_args(argv)
    fmus = args.out / "fmus"
    from guideway_fmu.fmu_build.build import ensure
    from guideway_fmu.components import registry
    ensure(fmus, ["FeedKinematics", "FrictionCoulomb", *registry.names("diagnosis")])

    jobs = [(effect, seed) for seed in range(1, args.draws + 1) for effect in truth.EFFECTS]
    with ThreadPoolExecutor(args.jobs) as pool:
        results = list(pool.map(lambda job: (job, diagnose_trial(
            args.out, fmus, job[0], job[1], args.noise, args.samples)), jobs))

    answers = sorted(set(truth.EXPECTED.values()))
    columns = answers + ["error"]
    table = {e: {c: 0 for c in columns} for e in truth.EFFECTS}
    ratios, seconds, wrong = [], [], []
    for (effect, seed), r in results:
        named = r.get("named", "error")
        table[effect][named if named in columns else "error"] += 1
        if "seconds" in r:
            seconds.append(r["seconds"])
        if named == r.get("expected") and named not in ("none", "unknown"):
            ratios.append(r["gap_after"] / r["noise_floor"])
        if named != r.get("expected", truth.EXPECTED[effect]):
            wrong.append(f"{effect}_{seed}: named {named} {r.get('error', '')}")
    width = max(len(e) for e in truth.EFFECTS) + 2
    print(f"confusion table: {args.draws} draws per effect, noise {args.noise:.3g} of the range, "
          f"{args.samples} samples (rows: hidden effect, columns: named)")
    print(" " * width + " ".join(f"{c[:10]:>10s}" for c in columns))
    for effect in truth.EFFECTS:
        print(f"{effect:{width}s}" + " ".join(f"{table[effect][c]:10d}" for c in columns))
    right = sum(table[e][truth.EXPECTED[e]] for e in truth.EFFECTS)
    print(f"right: {right} / {len(jobs)}")
    if wrong:
        print("wrong:\n  " + "\n  ".join(wrong))
    if ratios:
        print(f"held-out gap after / noise floor (named runs): median {np.median(ratios):.3f}, "
              f"max {np.max(ratios):.3f}, share <= 1.3: {np.mean(np.array(ratios) <= 1.3):.2f}")
    if seconds:
        print(f"diagnose wall time per {args.samples}-sample run ({args.jobs} jobs on the machine): "
              f"median {np.median(seconds):.1f} s, max {np.max(seconds):.1f} s")
    if not args.no_emps and args.data is not None:
        for name in ("emps-identification", "emps-validation"):
            d = diagnose_record(Path(args.data) / name, args.out / name, fmus)
            if "error" in d:
                print(f"{name}: {d['error']}")
                continue
            best = d["candidates"][0]
            print(f"{name}: named {d['missing_effect']} (confidence {d['confidence']:.2f}); gap "
                  f"before {d['gap_before']:.4f}, after {d['gap_after']:.4f}, noise floor "
                  f"{d['noise_floor']:.5f}; best candidate {best['effect']} (held-out gap "
                  f"{best['gap_after']:.4f}, {best['parameters']}); {d['seconds']:.1f} s")


if __name__ == "__main__":
    main()
