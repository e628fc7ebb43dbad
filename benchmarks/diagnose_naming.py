"""How often the discrepancy workflow names the hidden effect, over many random draws under the
harder conditions real rigs give (steps 1-4 of the workflow only, no co-simulation: fast).

    python benchmarks/diagnose_naming.py [--draws 24] [--samples 4000] [--jobs 2] [--seed 1000]

Draw i of each effect of diagnose/truth.py: seed SEED + i, effect size 1, 1/2, 1/3 of a clearly
visible one (i mod 3), noise 0.5, 1.0, 1.5 % of the range ((i div 3) mod 3), uneven sampling on
odd i. Prints every wrong answer with its gap and the leading candidates' held-out scores (or
why the workflow refused the record), then the share named right per expected answer.
"""
from __future__ import annotations

import argparse
import tempfile
import warnings
from collections import Counter
from multiprocessing import Pool

import numpy as np

from guideway_fmu.diagnose import truth
from guideway_fmu.diagnose.workflow import name_effect

SIZES = (1.0, 0.5, 1 / 3)
NOISES = (0.005, 0.01, 0.015)


def draw(job):
    effect, i, samples, seed = job
    warnings.simplefilter("ignore")
    size, noise = SIZES[i % 3], NOISES[(i // 3) % 3]
    with tempfile.TemporaryDirectory() as folder:
        info = truth.make_run(f"{folder}/run", effect, np.random.default_rng(seed + i), size=size,
                              noise=noise, uneven=bool(i % 2), n_samples=samples)
        try:
            named = name_effect(f"{folder}/run")
        except ValueError as refusal:  # a record the workflow cannot use (it says why)
            return {"effect": effect, "draw": i, "size": round(size, 3), "noise": noise,
                    "expected": info.expected, "named": "refused", "why": str(refusal)[-160:]}
    return {"effect": effect, "draw": i, "size": round(size, 3), "noise": noise,
            "expected": info.expected, "named": named.effect,
            "gap_over_noise": round(named.gap_base / named.noise, 3),
            "cross_gap_over_noise": round(named.cross_gap, 3),
            "leading": [(f.effect, round(float(s), 1)) for s, f, _ in named.ranked[:3]]}


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--draws", type=int, default=24)
    parser.add_argument("--samples", type=int, default=4000)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--seed", type=int, default=1000, help="seed of draw 0 (default 1000)")
    args = parser.parse_args(argv)
    jobs = [(e, i, args.samples, args.seed) for i in range(args.draws) for e in truth.EFFECTS]
    with Pool(args.jobs) as pool:
        results = pool.map(draw, jobs)
    for r in results:
        if r["named"] != r["expected"]:
            print("wrong:", r)
    count = Counter((r["expected"], r["named"] == r["expected"]) for r in results)
    hidden = [r for r in results if r["expected"] not in ("none", "unknown")]
    for answer in sorted({r["expected"] for r in results}):
        right, total = count[(answer, True)], count[(answer, True)] + count[(answer, False)]
        print(f"{answer:30s} {right:3d}/{total:<3d}")
    right = sum(r["named"] == r["expected"] for r in hidden)
    print(f"hidden effects named right: {right}/{len(hidden)} ({100 * right / len(hidden):.1f} %)")


if __name__ == "__main__":
    main()
