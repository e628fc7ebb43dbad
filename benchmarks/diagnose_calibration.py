"""Whether the discrepancy workflow's confidence means what it says, on never-seen draws of both
horizontal generators (steps 1-5 only, no co-simulation).

    python benchmarks/diagnose_calibration.py [--draws 24] [--samples 4000] [--jobs 2]
        [--seed 70000] [--fit-seed 90000 --fit-draws 12] [--page docs/diagnosis-calibration.md]

With ``--fit-seed``, first counts the right answers per evidence bin on ``--fit-draws`` draws
from that seed on and writes them to src/guideway_fmu/diagnose/calibration.json (the table the
stated confidence is read from: diagnose/calibration.py), then reports on the draws from
``--seed``, which the table never saw.

Draws: for each effect of guideway_synthetic/truth.py, ``--draws`` records as
benchmarks/diagnose_naming.py draws them (sizes 1, 1/2, 1/3; noise 0.5-1.5 %; every other one
uneven); for each allowed (effect, record class) pair of guideway_synthetic/second_truth.py,
``--draws`` records as benchmarks/diagnose_second_generator.py draws them; all from seed SEED
on (seeds the workflow's rules were never set on). Writes, and prints:

- the reliability table (records whose confidence a doubt held at 0.5 counted apart): for
  each band of stated confidence, the records in it, their mean
  stated confidence and the share named right (an answer is right where it is the expected one);
  a band is calibrated where the two lie within CALIBRATED of each other, judged where it holds
  at least JUDGED records;
- the naming per expected answer and generator, and the null records (no hidden effect) named
  as an effect, by the gap before over the noise floor.
"""
from __future__ import annotations

import argparse
from collections import defaultdict
from multiprocessing import Pool
from pathlib import Path

import diagnose_naming
import diagnose_second_generator
import pages
from guideway_fmu.diagnose import calibration
from guideway_synthetic import second_truth, truth

BANDS = (0.0, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99, 1.0)
CALIBRATED = 0.05  # largest gap between stated confidence and share right in a band
JUDGED = 20  # records a band needs to be judged
NULL_BANDS = (0.0, 1.0, 1.1, 1.3, 2.0, float("inf"))  # gap before over the noise floor


def run(job):
    generator, *rest = job
    if generator == "first":
        effect, i, samples, seed = rest
        row = diagnose_naming.draw((effect, i, samples, seed))
        return {**row, "generator": "first", "gap_before": row.get("gap_over_noise")}
    row = diagnose_second_generator.draw(tuple(rest))
    return {**row, "generator": "second", "gap_before": row.get("gap_before_over_noise")}


SCRIPT = "benchmarks/diagnose_calibration.py"  # the hash calibration.json records is of its closure


def draw_all(draws: int, samples: int, seed: int, jobs: int) -> list[dict]:
    """The rows of ``draws`` records per effect (first generator) and per effect and class
    (second generator) from ``seed`` on; each with its evidence (gap_ratio, weight)."""
    work = [("first", e, i, samples, seed) for i in range(draws) for e in truth.EFFECTS]
    work += [("second", e, c, seed + i, samples) for e in second_truth.EFFECTS
             for c in second_truth.CLASSES if second_truth.allowed(e, c) for i in range(draws)]
    with Pool(jobs) as pool:
        rows = [r for r in pool.map(run, work, chunksize=4) if "skipped" not in r]
    return [{**r, "gap_ratio": r.get("gap_before")} for r in rows]


def band_of(value: float, edges) -> int:
    return min(next(i for i in range(len(edges) - 1) if value < edges[i + 1] or i == len(edges) - 2),
               len(edges) - 2)


def reliability(rows) -> list[tuple]:
    """(band, records, mean stated confidence, share right, judged, calibrated) per band."""
    out = []
    for k in range(len(BANDS) - 1):
        inside = [r for r in rows if band_of(r["confidence"], BANDS) == k]
        if not inside:
            out.append((k, 0, None, None, False, None))
            continue
        stated = sum(r["confidence"] for r in inside) / len(inside)
        right = sum(r["named"] == r["expected"] for r in inside) / len(inside)
        judged = len(inside) >= JUDGED
        out.append((k, len(inside), stated, right, judged,
                    abs(stated - right) <= CALIBRATED if judged else None))
    return out


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--draws", type=int, default=24)
    parser.add_argument("--samples", type=int, default=4000)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--seed", type=int, default=70000,
                        help="seed of draw 0 (default 70000, never used to set a rule)")
    parser.add_argument("--fit-seed", type=int, default=None,
                        help="count calibration.json on draws from this seed first")
    parser.add_argument("--fit-draws", type=int, default=12)
    parser.add_argument("--page", default=str(Path(__file__).resolve().parents[1] / "docs" /
                                              "diagnosis-calibration.md"),
                        help="Markdown page the results are written to ('-': none)")
    args = parser.parse_args(argv)
    command = (f"python benchmarks/diagnose_calibration.py --draws {args.draws} "
               f"--samples {args.samples} --seed {args.seed}")
    if args.fit_seed is not None:
        fitted = [r for r in draw_all(args.fit_draws, args.samples, args.fit_seed, args.jobs)
                  if r["named"] != "refused"]
        calibration.write(calibration.count(fitted), pages.content_hash(SCRIPT),
                          f"python benchmarks/diagnose_calibration.py --fit-seed {args.fit_seed} "
                          f"--fit-draws {args.fit_draws} --samples {args.samples}")
        command += f" --fit-seed {args.fit_seed} --fit-draws {args.fit_draws}"
    rows = draw_all(args.draws, args.samples, args.seed, args.jobs)
    rows = [r for r in rows if r["named"] != "refused"] + [
        {**r, "confidence": 0.0} for r in rows if r["named"] == "refused"]
    # a confidence held at scoring.DOUBT by a doubt says "as likely noise", by design, not a
    # share of right answers: those records are shown apart, not judged
    held = [r for r in rows if r.get("held")]
    bands = reliability([r for r in rows if not r.get("held")])
    naming = defaultdict(lambda: [0, 0])
    for r in rows:
        naming[(r["generator"], r["expected"])][0] += r["named"] == r["expected"]
        naming[(r["generator"], r["expected"])][1] += 1
    nulls = defaultdict(lambda: [0, 0])
    for r in rows:
        if r["effect"] == "none" and r.get("gap_before") is not None:
            k = band_of(r["gap_before"], NULL_BANDS)
            nulls[k][0] += r["named"] not in ("none", "unknown")
            nulls[k][1] += 1
    lines = ["| stated confidence | records | mean stated | share right | calibrated |",
             "|---|---|---|---|---|"]
    for k, count, stated, right, judged, ok in bands:
        label = f"{BANDS[k]:g}-{BANDS[k + 1]:g}"
        lines.append(f"| {label} | {count} | {'-' if stated is None else f'{stated:.3f}'} | "
                     f"{'-' if right is None else f'{right:.3f}'} | "
                     f"{'-' if ok is None else ('yes' if ok else 'no')} |")
    lines += ["", "| generator | expected answer | named right |", "|---|---|---|"]
    lines += [f"| {g} | `{e}` | {a} / {b} |" for (g, e), (a, b) in sorted(naming.items())]
    lines += ["", "| gap before / noise floor | null records | named as an effect |", "|---|---|---|"]
    lines += [f"| {NULL_BANDS[k]:g}-{NULL_BANDS[k + 1]:g} | {b} | {a} |"
              for k, (a, b) in sorted(nulls.items())]
    wrong = [r for r in rows if r["named"] != r["expected"]]
    text = "\n".join(lines)
    print(text)
    for r in wrong:
        print("wrong:", {k: r.get(k) for k in ("generator", "effect", "class", "draw", "seed",
                                                 "named", "confidence", "gap_before", "leading",
                                                 "why")})
    if args.page != "-":
        judged = [b for b in bands if b[4]]
        good = sum(bool(b[5]) for b in judged)
        intro = [
            "# Whether the diagnosis's confidence means what it says", "",
            f"Never-seen draws of both horizontal generators, {args.draws} per effect "
            f"(`guideway_synthetic/truth.py`, as [diagnosis.md](diagnosis.md) draws them) and "
            f"{args.draws} per effect and record class (`guideway_synthetic/second_truth.py`, as "
            f"[diagnosis-second-generator.md](diagnosis-second-generator.md) draws them), "
            f"{args.samples} samples each, from seed {args.seed} on; steps 1-5 only "
            f"(`diagnose/decide.py`). {len(rows)} records. An answer is right where it is the "
            f"expected one; a refused record counts as wrong at confidence 0.", "",
            f"Reliability: {good} of the {len(judged)} bands holding at least {JUDGED} records "
            f"have a share of right answers within {CALIBRATED:.0%} of their mean stated "
            f"confidence. The table leaves out the {len(held)} records whose confidence a doubt "
            f"held at 0.5 (a gap within 1.3 noise floors, a fitted setting at the end of its "
            f"search: the report says which), of which "
            f"{sum(r['named'] == r['expected'] for r in held)} were named right: that cap says "
            f"\"as likely noise of another colour\", which synthetic noise never is, so it is "
            f"not judged against them.", ""]
        tail = ["", "Wrong answers:", ""] + [
            f"- {r['generator']} `{r['effect']}`"
            + (f" ({r['class']})" if r.get("class") else "")
            + f" seed {r.get('seed', args.seed + r.get('draw', 0))}: named `{r['named']}` at "
              f"confidence {r['confidence']}; gap before {r.get('gap_before')} noise floors"
            for r in wrong] if wrong else []
        pages.write(Path(args.page), "\n".join(intro + [text]) + "\n" + "\n".join(tail) + "\n",
                    command, __file__)


if __name__ == "__main__":
    main()
