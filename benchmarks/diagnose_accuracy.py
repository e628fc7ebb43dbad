"""Accuracy and speed of the discrepancy workflow on synthetic runs with hidden effects.

    python benchmarks/diagnose_accuracy.py [--draws 5] [--noise 0.015] [--samples 10000]
                                           [--jobs 2] [--out out/diagnose_accuracy] [--no-emps]

For every effect of diagnose/truth.py and ``draws`` seeds, writes a run, diagnoses it (each in
its own process) and prints the confusion table (expected answer x named effect), the held-out
gap after the named effect over the noise floor, the wall time of each diagnosis (10,000 samples
by default) and, unless --no-emps, the results on the two EMPS records.
"""
from __future__ import annotations

import argparse
import os
import json
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np

from guideway_fmu.diagnose import truth

CHILD = """
import json, sys, time, warnings
import numpy as np
warnings.simplefilter("ignore")
from guideway_fmu.diagnose import truth
from guideway_fmu.diagnose.workflow import diagnose
run, effect, seed, noise, samples, fmus = sys.argv[1:7]
info = truth.make_run(run, effect, np.random.default_rng(int(seed)), noise=float(noise),
                      n_samples=int(samples))
start = time.perf_counter()
d = diagnose(run, run + "_out", fmu_dir=fmus)
print(json.dumps({"expected": info.expected, "named": d["missing_effect"],
                  "gap_before": d["gap_before"], "gap_after": d["gap_after"],
                  "noise_floor": d["noise_floor"], "seconds": time.perf_counter() - start}))
"""
EMPS = """
import json, sys, time, warnings
warnings.simplefilter("ignore")
from guideway_fmu.diagnose.workflow import diagnose
start = time.perf_counter()
d = diagnose(sys.argv[1], sys.argv[2], fmu_dir=sys.argv[3])
d["seconds"] = time.perf_counter() - start
print(json.dumps(d))
"""


def child(script, *args) -> dict:
    done = subprocess.run([sys.executable, "-c", script, *map(str, args)], capture_output=True,
                          text=True)
    if done.returncode != 0:
        return {"error": done.stderr.strip().splitlines()[-1] if done.stderr else "crashed"}
    return json.loads(done.stdout.strip().splitlines()[-1])


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
    from guideway_fmu.components.build import ensure
    from guideway_fmu.components import registry
    ensure(fmus, ["FeedKinematics", "FrictionCoulomb", *registry.names("diagnosis")])

    jobs = [(effect, seed) for seed in range(1, args.draws + 1) for effect in truth.EFFECTS]
    with ThreadPoolExecutor(args.jobs) as pool:
        results = list(pool.map(lambda job: (job, child(
            CHILD, args.out / f"{job[0]}_{job[1]}", job[0], job[1], args.noise, args.samples,
            fmus)), jobs))

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
            d = child(EMPS, Path(args.data) / name, args.out / name, fmus)
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
