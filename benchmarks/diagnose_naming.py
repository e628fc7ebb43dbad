"""How often the discrepancy workflow names the hidden effect, over many random draws under the
harder conditions real rigs give (steps 1-5 of the workflow only, no co-simulation: fast).

    python benchmarks/diagnose_naming.py [--draws 24] [--samples 4000] [--jobs 2] [--seed 1000]
                                         [--page docs/diagnosis.md]

Draw i of each effect of guideway_synthetic/truth.py: seed SEED + i, effect size 1, 1/2, 1/3 of a clearly
visible one (i mod 3), noise 0.5, 1.0, 1.5 % of the range ((i div 3) mod 3), uneven sampling on
odd i. Prints every wrong answer with its gap and the leading candidates' held-out scores (or
why the workflow refused the record), then the share named right per expected answer, and
writes both to the page (docs/diagnosis.md unless --page says otherwise; --page - writes none).
"""
from __future__ import annotations

import argparse
import tempfile
import warnings
from collections import Counter
from multiprocessing import Pool
from pathlib import Path

import numpy as np

from guideway_synthetic import truth
from guideway_fmu.diagnose.decide import decide

import pages

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
            named = decide(f"{folder}/run")
        except ValueError as refusal:  # a record the workflow cannot use (it says why)
            return {"effect": effect, "draw": i, "size": round(size, 3), "noise": noise,
                    "expected": info.expected, "named": "refused", "why": str(refusal)[-160:]}
    return {"effect": effect, "draw": i, "size": round(size, 3), "noise": noise,
            "expected": info.expected, "named": named.effect,
            "confidence": round(named.confidence, 4), "weight": named.weight,
            "held": bool(named.doubts), "gap_over_noise": round(named.gap_base / named.noise, 3),
            "cross_gap_over_noise": round(named.cross_gap, 3),
            "leading": [(f.effect, round(float(s), 1)) for s, f, _ in named.ranked[:3]]}


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--draws", type=int, default=24)
    parser.add_argument("--samples", type=int, default=4000)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--seed", type=int, default=1000, help="seed of draw 0 (default 1000)")
    parser.add_argument("--page", default=str(Path(__file__).resolve().parents[1] / "docs" /
                                              "diagnosis.md"),
                        help="Markdown page the results are written to ('-': none)")
    args = parser.parse_args(argv)
    jobs = [(e, i, args.samples, args.seed) for i in range(args.draws) for e in truth.EFFECTS]
    with Pool(args.jobs) as pool:
        results = pool.map(draw, jobs)
    wrong = [r for r in results if r["named"] != r["expected"]]
    count = Counter((r["expected"], r["named"] == r["expected"]) for r in results)
    hidden = [r for r in results if r["expected"] not in ("none", "unknown")]
    rows = []
    for answer in sorted({r["expected"] for r in results}):
        right, total = count[(answer, True)], count[(answer, True)] + count[(answer, False)]
        rows.append((answer, right, total))
    right = sum(r["named"] == r["expected"] for r in hidden)
    for r in wrong:
        print("wrong:", r)
    for answer, named, total in rows:
        print(f"{answer:30s} {named:3d}/{total:<3d}")
    print(f"hidden effects named right: {right}/{len(hidden)} ({100 * right / len(hidden):.1f} %)")
    if args.page != "-":
        command = (f"python benchmarks/diagnose_naming.py --draws {args.draws} "
                   f"--samples {args.samples} --seed {args.seed}")
        write_page(Path(args.page), command, args, rows, right, len(hidden), wrong)


def write_page(path: Path, command: str, args, rows, right: int, hidden: int, wrong: list) -> None:
    """The naming figures as a Markdown page."""
    lines = [
        "# How often the discrepancy workflow names the hidden effect", "",
        f"Synthetic runs of `guideway_synthetic/truth.py`, {args.draws} draws per hidden effect of "
        f"{args.samples} samples from seed {args.seed} on; effect size 1, 1/2 or 1/3 of a clearly "
        f"visible one, noise 0.5, 1.0 or 1.5 % of the force range, every other draw unevenly "
        f"sampled. The truth laws differ in form from the candidates' laws. Steps 1-5 only "
        f"(`diagnose/decide.py`, no co-simulation). The generator is the project's own: these "
        f"figures test the workflow against its own assumptions about rigs and effects, not "
        f"against real records ([real-data.md](real-data.md) has public measured ones).", "",
        "| expected answer | named right |", "|---|---|",
        *(f"| `{answer}` | {named} / {total} |" for answer, named, total in rows), "",
        f"Hidden effects named right: {right} / {hidden} ({100 * right / max(hidden, 1):.1f} %).", "",
    ]
    if wrong:
        lines += ["Wrong answers (draw, size, noise, named, leading held-out scores):", ""]
        lines += [f"- `{r['effect']}` draw {r['draw']} (size {r['size']}, noise {r['noise']}): "
                  f"named `{r['named']}`; {r.get('leading', r.get('why'))}" for r in wrong]
        lines.append("")
    pages.write(path, "\n".join(lines), command, __file__)

if __name__ == "__main__":
    main()
