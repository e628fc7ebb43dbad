"""How often the discrepancy workflow names both effects of a record hiding two, on records of
the second, independent generator (guideway_synthetic/second_truth.py, ``draw(..., also=...)``),
by pair and by record class, on seeds it was never tuned on (steps 1-5, no co-simulation).

    python benchmarks/diagnose_two_effects.py [--draws 4] [--samples 4000] [--jobs 2]
        [--seed 68000] [--page docs/diagnosis-two-effects.md]

For every pair of PAIRS and every record class both effects may appear in, ``--draws`` records
of size 1 (each effect's visible part 8 times the noise on its own) from seed SEED + i. Prints
every answer that misses an effect, then per pair and per class: both named (as the first two
steps), both and nothing more, and the median held-out gap after each step over the generator's
own noise (its RMS over the range: the yardstick no fit has seen); writes them to the page.
"""
from __future__ import annotations

import argparse
import sys
import tempfile
import warnings
from collections import defaultdict
from multiprocessing import Pool
from pathlib import Path

import numpy as np

from guideway_synthetic import second_truth
from guideway_fmu.diagnose.decide import decide

import pages

#: (first, second) hidden effects: the issue's examples (a Stribeck curve with a position
#: ripple, preload loss with pre-sliding) and the pairs of effects that share the samples they
#: show on (reversals, accelerations)
PAIRS = (("lubrication", "position_dependent_friction"),
         ("preload_loss", "presliding_hysteresis"),
         ("presliding_hysteresis", "unmodeled_mass"),
         ("lubrication", "presliding_hysteresis"),
         ("position_dependent_friction", "unmodeled_mass"),
         ("preload_loss", "lubrication"))


def draw(job):
    pair, record_class, seed, samples = job
    warnings.simplefilter("ignore")
    row = {"pair": pair, "class": record_class, "seed": seed}
    with tempfile.TemporaryDirectory() as folder:
        try:
            truth = second_truth.draw(f"{folder}/run", pair[0], record_class, seed,
                                      also=pair[1], n_samples=samples)
        except ValueError as refusal:  # the generator cannot reach the size on this draw
            return {**row, "skipped": str(refusal)}
        try:
            named = decide(f"{folder}/run")
        except ValueError as refusal:
            return {**row, "named": ["refused"], "why": str(refusal)[-200:]}
    noise = truth.noise_rms / float(np.ptp(named.ctx.y[named.held]))
    return {**row, "named": [s.effect for s in named.steps] or [named.effect],
            "gaps": [named.gap_base / noise] + [s.gap_after / noise for s in named.steps]}


def _median(values) -> str:
    return f"{np.median(values):.3g}" if values else "-"


def table(rows: list[dict], key, title: str) -> list[str]:
    groups = defaultdict(list)
    for row in rows:
        groups[key(row)].append(row)
    lines = [f"| {title} | both named | both, nothing more | gap before | after step 1 | "
             f"after step 2 |", "|---|---|---|---|---|---|"]
    for name in sorted(groups):
        group = groups[name]
        both = [r for r in group if set(r["named"][:2]) == set(r["pair"])]
        exact = [r for r in both if len(r["named"]) == 2]
        gaps = [[r["gaps"][k] for r in both] for k in range(3)]
        lines.append(f"| {name} | {len(both)} / {len(group)} | {len(exact)} / {len(group)} | "
                     + " | ".join(_median(g) for g in gaps) + " |")
    return lines


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--draws", type=int, default=4)
    parser.add_argument("--samples", type=int, default=4000)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--seed", type=int, default=68000,
                        help="seed of draw 0 (default 68000; 61000-67999 served development)")
    parser.add_argument("--page", default=str(Path(__file__).resolve().parents[1] / "docs" /
                                              "diagnosis-two-effects.md"))
    args = parser.parse_args(argv)
    jobs = [(pair, record_class, args.seed + i, args.samples)
            for pair in PAIRS for record_class in second_truth.CLASSES
            if all(second_truth.allowed(e, record_class) for e in pair)
            for i in range(args.draws)]
    with Pool(args.jobs) as pool:
        rows = pool.map(draw, jobs, chunksize=1)
    skipped = [r for r in rows if "skipped" in r]
    rows = [r for r in rows if "skipped" not in r]
    missed = [r for r in rows if set(r["named"][:2]) != set(r["pair"])]
    for row in missed:
        print(row, file=sys.stderr)
    both = len(rows) - len(missed)
    command = (f"python benchmarks/diagnose_two_effects.py --draws {args.draws} "
               f"--samples {args.samples} --seed {args.seed}")
    lines = ["# Two hidden effects at once", "",
             "Records of `guideway_synthetic/second_truth.py` hiding two effects "
             "(`draw(..., also=...)`: each effect drawn from a stream of its own and scaled to "
             f"a visible part 8 times the noise on its own), {args.draws} draws per pair and "
             f"record class, {args.samples} samples each, on seeds the workflow was never tuned "
             "on. Steps 1-5 (`diagnose/decide.py`, `diagnose/more_effects.py`). \"Both named\": "
             "the first two effects named are the two hidden ones, in either order. Gaps are "
             "medians over the records with both named, in units of the generator's own noise "
             "(its RMS over the range), which no fit has seen: 1 is the best a model can do.", "",
             *table(rows, lambda r: " + ".join(f"`{e}`" for e in r["pair"]), "hidden pair"), "",
             *table(rows, lambda r: f"`{r['class']}`", "record class"), "",
             f"Both named: {both} / {len(rows)}. Draws the generator could not make at this "
             f"size: {len(skipped)}.", "", "## Answers that miss an effect", ""]
    lines += [f"- {' + '.join(r['pair'])} on `{r['class']}` (seed {r['seed']}): "
              f"{', then '.join(r['named'])}" + (f": {r['why']}" if "why" in r else "")
              for r in missed] or ["none"]
    text = "\n".join(lines) + "\n"
    print(text)
    pages.write(args.page, text, command, __file__)


if __name__ == "__main__":
    main()
