"""Diagnose every public measured record and write docs/real-data.md: the workflow's answer beside
the authors' finding.

Usage::

    GUIDEWAY_FMU_DATA=<real records> GUIDEWAY_FMU_REAL_RAW=<raw folders> \
        .venv/bin/python orchestration/real_data/report.py

Inputs, both from the environment or the command line, never a fixed path outside the repository:

- ``--raw`` (default ``GUIDEWAY_FMU_REAL_RAW``): one subfolder of raw files per data set, named by
  the converter's short name (README.md of this folder says where to fetch them); a missing
  subfolder is reported on the page, not an error.
- ``--data`` (default ``GUIDEWAY_FMU_DATA``, the setting the tests read; refused when neither
  is set): the folder holding the converted EMPS runs ``emps-identification/`` and
  ``emps-validation/`` (a folder holding ``real/`` with them is accepted too).

Each record is converted into ``--work`` (default a new temporary folder), diagnosed by
``guideway-fmu diagnose`` in a subprocess, one at a time, on a copy of src/guideway_fmu made
at the start (others may edit it meanwhile), and judged against its authors' finding
by the rules written next to each data set below. The page goes to ``--out`` (default
docs/real-data.md). ``--reuse`` keeps diagnoses already in ``--work`` (for rewording the page).
"""
from __future__ import annotations

import argparse
import hashlib
import importlib.util
import json
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[1]
sys.path.insert(0, str(REPO / "benchmarks"))
import pages  # noqa: E402 - benchmarks/pages.py, the writer of every generated docs/ page

#: code the page depends on beyond the script's imports (loaded by file; pages.py)
INPUTS = ("orchestration/real_data/convert_*.py",)

#: Janot, Gautier & Brunot (2019), inverse dynamic model identified by least squares on EMPS
EMPS_PUBLISHED = {"mass": 95.1, "coulomb": 20.39, "viscous": 203.5, "offset": -3.16}
#: Mnich (2020), output/coeffs_for_friction_model.mat: dry, viscous, hump peak and its speed
MNICH_PUBLISHED = {"coulomb": 10.0, "viscous": 67.4, "peak": 29.6, "peak_speed": 0.0135}
#: agreement rules (stated on the page)
EMPS_CURVE_RMS = 3.0  # N: the workflow's friction over the record's speeds vs Fc + Fv |v|
EMPS_OFFSET = 0.5  # N
SEAL_LEVEL = 0.20  # relative difference of 2 Fc and the authors' friction range


@dataclass
class Record:
    data_set: str
    name: str
    run_dir: Path | None
    note: str = ""  # e.g. the seal's pressure
    diagnosis: dict | None = None
    refusal: str | None = None
    seconds: float = float("nan")
    extra: dict = field(default_factory=dict)


# ---------------------------------------------------------------------------------- inputs


def converter(short_name: str):
    path = HERE / f"convert_{short_name}.py"
    spec = importlib.util.spec_from_file_location(f"convert_{short_name}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def emps_folder(data: Path) -> Path:
    for candidate in (data, data / "real"):
        if (candidate / "emps-identification").is_dir():
            return candidate
    return data


def columns(run_dir: Path) -> dict[str, np.ndarray]:
    table = np.genfromtxt(run_dir / "data.csv", delimiter=",", names=True)
    return {name: np.asarray(table[name], dtype=float) for name in table.dtype.names}


def velocity(cols: dict[str, np.ndarray]) -> np.ndarray:
    if "feed_velocity" in cols:
        return cols["feed_velocity"]
    return np.gradient(cols["feed_position"], cols["time"])


# ---------------------------------------------------------------------------------- diagnosis


def freeze_sources(work: Path, reuse: bool) -> dict:
    """Copy src/guideway_fmu into WORK/src once, so that every diagnosis of the run uses the same
    code while others edit the repository; return its stamp (commit, uncommitted files, hash)."""
    stamp_file = work / "src" / "stamp.json"
    if reuse and stamp_file.is_file():
        return json.loads(stamp_file.read_text())
    target = work / "src" / "guideway_fmu"
    if target.exists():
        shutil.rmtree(target)
    shutil.copytree(REPO / "src" / "guideway_fmu", target,
                    ignore=shutil.ignore_patterns("__pycache__", "*.pyc"))
    digest = hashlib.sha256()
    for path in sorted(target.rglob("*.py")):
        digest.update(path.relative_to(target).as_posix().encode() + path.read_bytes())

    def git(*args):
        done = subprocess.run(["git", "-C", str(REPO), *args], capture_output=True, text=True)
        return done.stdout.strip() if done.returncode == 0 else ""

    changed = [line.split(maxsplit=1)[1] for line in git("status", "--porcelain", "--", "src").splitlines()
               if line.strip()]
    stamp = {"commit": git("rev-parse", "--short", "HEAD") or "unknown", "uncommitted": changed,
             "hash": digest.hexdigest()[:12]}
    stamp_file.write_text(json.dumps(stamp))
    return stamp


def diagnose(record: Record, out: Path, fmus: Path, reuse: bool, env: dict) -> None:
    target = out / record.data_set / record.name
    stored = target / "diagnosis.json"
    refused = target / "refusal.txt"
    if reuse and stored.is_file():
        record.diagnosis = json.loads(stored.read_text())
        record.seconds = float((target / "seconds.txt").read_text()) if (target / "seconds.txt").is_file() else float("nan")
        return
    if reuse and refused.is_file():
        record.refusal = refused.read_text()
        return
    target.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    done = subprocess.run([sys.executable, "-m", "guideway_fmu.cli", "diagnose", str(record.run_dir),
                           "--out", str(target), "--fmus", str(fmus)],
                          capture_output=True, text=True, timeout=1800, env=env)
    record.seconds = time.perf_counter() - start
    (target / "seconds.txt").write_text(f"{record.seconds:.2f}")
    if done.returncode == 0:
        record.diagnosis = json.loads(stored.read_text())
    else:
        lines = [line for line in done.stderr.strip().splitlines() if line.strip()]
        record.refusal = lines[-1] if lines else f"exit code {done.returncode}"
        refused.write_text(record.refusal)


def named(record: Record) -> dict:
    """The named candidate's entry (or the best-scored one for unknown/none), {} if none."""
    d = record.diagnosis or {}
    candidates = d.get("candidates") or []
    for c in candidates:
        if c.get("effect") == d.get("missing_effect"):
            return c
    return candidates[0] if candidates else {}


def fmt(x, digits=3) -> str:
    if x is None or (isinstance(x, float) and not np.isfinite(x)):
        return "-"
    return f"{x:.{digits}g}"


def key_parameters(candidate: dict) -> str:
    """The fitted parameters that matter, by effect, in SI units."""
    p = candidate.get("parameters", {})
    effect = candidate.get("effect")
    parts = [f"Fc {fmt(p.get('coulomb'))} N"]
    if effect == "lubrication":
        parts += [f"Fs {fmt(p.get('static'))} N", f"vs {fmt(p.get('stribeck_velocity'))} m/s",
                  f"cv {fmt(p.get('viscous'))} N(s/m)^{fmt(p.get('viscous_exponent'), 2)}"]
    elif effect == "presliding_hysteresis":
        shares = [1.0 - p.get("second_share", 0) - p.get("third_share", 0),
                  p.get("second_share"), p.get("third_share")]
        dists = [p.get("presliding_distance"), p.get("second_distance"), p.get("third_distance")]
        parts.append("elements " + ", ".join(f"{fmt(s, 2)} over {fmt(d * 1e3 if d else d, 2)} mm"
                                             for s, d in zip(shares, dists) if d is not None))
    elif effect == "position_dependent_friction":
        parts.append(f"factor {fmt(p.get('factor_min'), 2)}-{fmt(p.get('factor_max'), 2)} "
                     f"({p.get('nodes')} nodes)")
    elif effect == "preload_loss":
        parts.append(f"loss {fmt(p.get('loss'), 2)} ({p.get('law')})")
    elif effect == "unmodeled_mass":
        parts.append(f"extra mass {fmt(p.get('extra_mass'))} kg")
    if "offset" in p:
        parts.append(f"offset {fmt(p.get('offset'))} N")
    return ", ".join(parts)


def answer(record: Record) -> str:
    if record.refusal:
        return "refused"
    d = record.diagnosis
    return f"`{d['missing_effect']}` ({fmt(d['confidence'], 2)})"


def gaps(record: Record) -> str:
    if record.refusal:
        return "-"
    d = record.diagnosis
    return f"{d['gap_before']:.4f} → {d['gap_after']:.4f} / {d['noise_floor']:.4f}"


# ---------------------------------------------------------------------------------- EMPS


def stribeck_level(speed, p):
    """The lubrication candidate's friction magnitude at speed > 0 (its law in
    physics/rigs/friction_laws.py: Stribeck plus a power-law viscous term)."""
    return (p["coulomb"] + (p["static"] - p["coulomb"])
            * np.exp(-(speed / p["stribeck_velocity"]) ** p.get("stribeck_exponent", 2.0))
            + p["viscous"] * speed ** p.get("viscous_exponent", 1.0))


def judge_emps(record: Record) -> tuple[str, str]:
    """Agree when the workflow names `lubrication` (the velocity-dependent candidate, which holds
    the viscous term) and its friction over the record's speeds stays within EMPS_CURVE_RMS of
    the published Fc + Fv |v|, its offset within EMPS_OFFSET of the published one."""
    if record.refusal:
        return "disagree", f"refused: {record.refusal}"
    lub = next((c for c in record.diagnosis["candidates"] if c["effect"] == "lubrication"), None)
    effect = record.diagnosis["missing_effect"]
    if lub is None:
        return "disagree", f"named `{effect}`; no lubrication candidate to compare"
    speed = np.abs(velocity(columns(record.run_dir)))
    speed = speed[speed > 0.01]
    ours = stribeck_level(speed, lub["parameters"])
    theirs = EMPS_PUBLISHED["coulomb"] + EMPS_PUBLISHED["viscous"] * speed
    rms = float(np.sqrt(np.mean((ours - theirs) ** 2)))
    offset = lub["parameters"].get("offset", float("nan"))
    record.extra.update(curve_rms=rms, mean_friction=float(np.mean(theirs)), offset=offset)
    curve_ok = rms < EMPS_CURVE_RMS and abs(offset - EMPS_PUBLISHED["offset"]) < EMPS_OFFSET
    reason = (f"friction over the record's speeds {rms:.1f} N RMS from Fc + Fv|v| (mean "
              f"{np.mean(theirs):.0f} N), offset {offset:.2f} N vs {EMPS_PUBLISHED['offset']} N")
    if effect == "lubrication" and curve_ok:
        return "agree", "velocity-dependent friction named; " + reason
    if effect == "lubrication":
        return "partly", "velocity-dependent friction named, but " + reason
    return "disagree", f"named `{effect}` where the authors add viscous friction; " + reason


EMPS_FINDING = (f"inertia {EMPS_PUBLISHED['mass']} kg + Coulomb {EMPS_PUBLISHED['coulomb']} N + "
                f"viscous {EMPS_PUBLISHED['viscous']} N s/m + offset {EMPS_PUBLISHED['offset']} N; "
                "viscous part differs between directions")


# ---------------------------------------------------------------------------------- seals


def authors_range(run_dir: Path) -> float:
    """The authors' dynamic friction force range: the mean of the friction above its mean (the
    retracting strokes) minus the mean of the rest (the extending ones), over the whole file."""
    f = columns(run_dir)["friction_force"]
    return float(np.mean(f[f > f.mean()]) - np.mean(f[f <= f.mean()]))


def even_slope(run_dir: Path) -> float:
    """Slope [N/mm] of the part of the force that does not turn with the motion: least squares
    of F = Fc sgn(v) + offset + k x over the samples faster than 30 % of the top speed."""
    cols = columns(run_dir)
    x, f = cols["feed_position"], cols["friction_force"]
    v = velocity(cols)
    moving = np.abs(v) > 0.3 * np.max(np.abs(v))
    design = np.c_[np.sign(v[moving]), np.ones(moving.sum()), x[moving] * 1e3]
    return float(np.linalg.lstsq(design, f[moving], rcond=None)[0][2])


def level_of(candidate: dict, run_dir: Path) -> float:
    """The candidate's friction level [N]: its Coulomb level, or for the lubrication law its
    friction magnitude averaged over the record's moving samples (there Fc trades off against a
    viscous term, even a negative one)."""
    p = candidate.get("parameters", {})
    if candidate.get("effect") != "lubrication" or "viscous" not in p:
        return p.get("coulomb", float("nan"))
    speed = np.abs(velocity(columns(run_dir)))
    speed = speed[speed > 0.3 * speed.max()]
    return float(np.mean(stribeck_level(speed, p)))


def judge_seal(record: Record) -> tuple[str, str]:
    """The authors report the friction level (their range, about 2 Fc) and its growth with the
    pressure, no missing effect: agree on the level when 2 Fc of the workflow's model is within
    SEAL_LEVEL of their range; the named effect is beyond what they state."""
    r = authors_range(record.run_dir)
    record.extra["range"] = r
    if record.refusal:
        return "disagree", f"refused: {record.refusal}"
    fc = level_of(named(record), record.run_dir)
    record.extra["two_fc"] = 2 * fc
    ratio = 2 * fc / r
    effect = record.diagnosis["missing_effect"]
    level = f"2 Fc = {2 * fc:.1f} N vs range {r:.1f} N" + (
        " (Fc: the law's mean over the strokes)" if named(record).get("effect") == "lubrication" else "")
    if effect == "unknown":
        k = even_slope(record.run_dir)
        record.extra["slope"] = k
        level += f"; a force along the stroke that does not turn with the motion, {k:+.2f} N/mm"
    verdict = "agree" if abs(ratio - 1.0) < SEAL_LEVEL else "disagree"
    return verdict + " (level)", level


SEAL_FINDING = "friction range grows with pressure; no effect beyond the level stated"


# ---------------------------------------------------------------------------------- Mnich


def judge_mnich(record: Record) -> tuple[str, str]:
    """The author's law is velocity dependent (viscous and a velocity-weakening hump), i.e.
    `lubrication` in the workflow's words; a refusal is no answer."""
    if record.refusal:
        return "no answer", "refused: the record is one stroke in one direction"
    effect = record.diagnosis["missing_effect"]
    return ("agree" if effect == "lubrication" else "disagree"), f"named `{effect}`"


MNICH_FINDING = (f"Coulomb {MNICH_PUBLISHED['coulomb']} N + viscous {MNICH_PUBLISHED['viscous']} N s/m "
                 f"+ velocity-weakening hump to {MNICH_PUBLISHED['peak']} N at "
                 f"{MNICH_PUBLISHED['peak_speed']} m/s")


# ---------------------------------------------------------------------------------- page


def pressure_of(name: str) -> float:
    for part in name.split("_"):
        if part.endswith("bar"):
            try:
                return float(part[:-3])
            except ValueError:
                pass
    return float("nan")


def seal_family(name: str) -> str:
    stem = name.split("_")
    if stem[0] in ("rerun", "reconnected"):
        stem = stem[2:]
    return "_".join(p for p in stem if not p.endswith("bar") and p != "tweederun")


def label(record: Record) -> str:
    same = record.extra.get("same_as")
    return f"{record.name} (= {same})" if same else record.name


def write_page(records: list[Record], missing: list[str], out: Path, command: str, wall: float,
               sources: dict[str, str], stamp: dict) -> None:
    emps = [r for r in records if r.data_set == "emps"]
    mnich = [r for r in records if r.data_set == "mnich_rack_pinion"]
    seals = [r for r in records if r.data_set == "tud_pneumatic_seals" and not r.name.startswith(("rerun", "reconnected"))]
    reruns = [r for r in records if r.data_set == "tud_pneumatic_seals" and r.name.startswith(("rerun", "reconnected"))]
    verdicts = {}
    for r in records:
        judge = {"emps": judge_emps, "mnich_rack_pinion": judge_mnich}.get(r.data_set, judge_seal)
        verdicts[r.name] = judge(r)

    def counts(rs):
        tally: dict[str, int] = {}
        for r in rs:
            key = "refused" if r.refusal else r.diagnosis["missing_effect"]
            tally[key] = tally.get(key, 0) + 1
        return ", ".join(f"{v} `{k}`" for k, v in sorted(tally.items(), key=lambda kv: -kv[1]))

    def agreement(rs):
        tally: dict[str, int] = {}
        for r in rs:
            key = verdicts[r.name][0]
            tally[key] = tally.get(key, 0) + 1
        return ", ".join(f"{v} {k}" for k, v in sorted(tally.items(), key=lambda kv: -kv[1]))

    lines = [
        "# Real measured records: the workflow's answers beside their authors' findings",
        "",
        "Each public record of friction in linear motion is converted into a measured run",
        "([measured-run.md](measured-run.md)), diagnosed by `guideway-fmu diagnose` with the",
        "Coulomb baseline its converter states, and set beside what its authors found. Sources,",
        "licences and every conversion assumption: `orchestration/real_data/README.md` and the",
        "converters' docstrings.",
        "",
        f"Wall time {wall / 60:.1f} min for {len(records)} records "
        f"(one diagnosis at a time, {platform.machine()}, {os.cpu_count()} cores).",
        "",
        f"Workflow: `src/guideway_fmu` at commit {stamp['commit']}"
        + (f" with uncommitted changes in {', '.join(f'`{f}`' for f in stamp['uncommitted'])}"
           if stamp["uncommitted"] else "")
        + f", copied once for the run (sources hash {stamp['hash']}), so every record saw the "
        "same code. The answers change with the workflow: rerun the script after changing it.",
        "",
        "Columns: *answer* is the named missing effect (confidence); *gap* is the held-out",
        "range-normalised RMS error before → after adding it, over the noise floor (for `unknown`",
        "the gap stays); the fitted parameters are those of the named candidate (for `unknown`, of",
        "the best-scored candidate), Fc its Coulomb level.",
        "",
        "## Summary",
        "",
        "| data set | records | workflow's answers | authors' finding | agreement |",
        "| --- | --- | --- | --- | --- |",
    ]
    if emps:
        lines.append(f"| EMPS (Janot, Gautier, Brunot 2019) | {len(emps)} | {counts(emps)} | {EMPS_FINDING} | {agreement(emps)} |")
    if mnich:
        lines.append(f"| rack and pinion (Mnich 2020) | {len(mnich)} | {counts(mnich)} | {MNICH_FINDING} | {agreement(mnich)} |")
    if seals:
        lines.append(f"| pneumatic seals (Zillen, Vallery, Smit 2021) | {len(seals)} | {counts(seals)} | {SEAL_FINDING} | {agreement(seals)} |")
    if reruns:
        lines.append(f"| the seals' re-runs (same authors) | {len(reruns)} | {counts(reruns)} | {SEAL_FINDING} | {agreement(reruns)} |")
    for name in missing:
        lines.append(f"| {name} | 0 | raw files not found | - | - |")
    copies = [r for r in records if r.extra.get("same_as")]
    if copies:
        lines += ["", f"{len(copies)} of the {len(records)} records repeat another one byte for byte "
                  "(the data sets ship them under both names): "
                  + ", ".join(f"{r.name} = {r.extra['same_as']}" for r in copies)
                  + ". They are kept, marked (= ...), and counted above; their answers are the same "
                  "as their twins' unless the workflow is not deterministic."]

    if emps:
        lines += ["", "## EMPS positioning axis (screw drive, carriage on a linear guide)", "",
                  f"Authors' finding: {EMPS_FINDING} (the identified inverse dynamic model). "
                  f"Rule: agree when `lubrication` (the candidate holding the viscous term) is named, "
                  f"its friction over the record's speeds is within {EMPS_CURVE_RMS} N RMS of "
                  f"Fc + Fv|v| and its offset within {EMPS_OFFSET} N of theirs.", "",
                  "| record | answer | gap | fitted parameters | verdict | reason |",
                  "| --- | --- | --- | --- | --- | --- |"]
        for r in emps:
            v, why = verdicts[r.name]
            lub = next((c for c in (r.diagnosis or {}).get("candidates", []) if c["effect"] == "lubrication"), named(r))
            lines.append(f"| {r.name} | {answer(r)} | {gaps(r)} | {key_parameters(lub) if lub else '-'} | {v} | {why} |")
        left = [r.diagnosis["gap_after"] / r.diagnosis["noise_floor"] for r in emps if r.diagnosis]
        if left:
            lines += ["", f"After the named effect the gap is still {min(left):.0f}-{max(left):.0f} noise "
                      "floors: the record's force is the controller's command, nearly noise-free, so "
                      "the floor is tiny and any misfit counts."]
        lines += ["", "The workflow's viscous law is one curve for both directions (a power of the "
                  "speed, with a Stribeck term at low speed); the authors' viscous part differs "
                  "between directions, which no candidate can express; that may be part of the gap "
                  "left after the named effect."]

    if mnich:
        lines += ["", "## Rack and pinion (one stroke)", "",
                  f"Author's finding: {MNICH_FINDING} (`lubrication` in the workflow's words).", "",
                  "| record | answer | verdict | reason |", "| --- | --- | --- | --- |"]
        for r in mnich:
            v, why = verdicts[r.name]
            lines.append(f"| {r.name} | {answer(r)} | {v} | {why} |")
        if any(r.refusal for r in mnich):
            lines += ["", "The refusal is by design: with motion in one direction only, the "
                      "Coulomb level and a force offset are the same column of the fit. The "
                      "author separates them by zeroing the load cell at rest before the stroke, "
                      "which the measured-run format does not carry (a sensor offset is always "
                      "calibrated)."]

    if seals:
        lines += ["", "## Pneumatic piston seals (reciprocating strokes at 1-7 bar)", "",
                  "Authors' finding: the dynamic friction force range (mean friction of the "
                  "retracting minus the extending strokes, about 2 Fc) grows with the pressure and "
                  "differs between seals and bore shapes; recomputed here from each converted "
                  "file by their definition. They state no effect beyond that level, so only the "
                  f"level is judged: agree when 2 Fc is within {SEAL_LEVEL:.0%} of their range. "
                  "That is a weak test: their range is a model-free statistic of the same samples "
                  "that a Coulomb fit must reproduce, so agreement shows that the conversion, the "
                  "sign and the fit are sound, not that the named effect is right.", "",
                  "| record | p [bar] | answer | gap | fitted parameters | authors' range [N] | verdict | reason |",
                  "| --- | --- | --- | --- | --- | --- | --- | --- |"]
        for r in seals:
            v, why = verdicts[r.name]
            lines.append(f"| {label(r)} | {fmt(pressure_of(r.name), 2)} | {answer(r)} | {gaps(r)} | "
                         f"{key_parameters(named(r)) if r.diagnosis else '-'} | {r.extra['range']:.1f} | {v} | {why} |")
        lines += ["", "Growth with the pressure, by seal or bore (2 Fc of the workflow's model and the "
                  "authors' range, N; *steps followed*: pressure steps where 2 Fc moves the same way "
                  "as the range):", "",
                  "| seal or bore | pressures [bar] | 2 Fc | authors' range | range grows | steps followed |",
                  "| --- | --- | --- | --- | --- | --- |"]
        families: dict[str, list[Record]] = {}
        for r in seals:
            if r.diagnosis and "tweederun" not in r.name:
                families.setdefault(seal_family(r.name), []).append(r)
        for fam, rs in sorted(families.items()):
            rs = sorted(rs, key=lambda r: pressure_of(r.name))
            ours = [r.extra.get("two_fc", float("nan")) for r in rs]
            theirs = [r.extra["range"] for r in rs]
            grows = "yes" if np.all(np.diff(theirs) > 0) else "no"
            followed = int(np.sum(np.sign(np.diff(ours)) == np.sign(np.diff(theirs))))
            lines.append(f"| {fam} | {', '.join(fmt(pressure_of(r.name), 2) for r in rs)} | "
                         f"{', '.join(f'{x:.1f}' for x in ours)} | {', '.join(f'{x:.1f}' for x in theirs)} | "
                         f"{grows} | {followed} of {len(rs) - 1} |")
        hysteresis = [r for r in seals if r.diagnosis and r.diagnosis["missing_effect"] == "presliding_hysteresis"]
        if hysteresis:
            after = [r.diagnosis["gap_after"] / r.diagnosis["gap_before"] for r in hysteresis]
            floors = [r.diagnosis["gap_after"] / r.diagnosis["noise_floor"] for r in hysteresis]
            longest = [1e3 * max(v for k, v in named(r)["parameters"].items() if k.endswith("distance"))
                       for r in hysteresis]
            lines += ["", f"`presliding_hysteresis` ({len(hysteresis)} records): after each reversal the "
                      "seal's force builds up over a distance (the longest fitted element distance: "
                      f"{min(longest):.2g}-{max(longest):.2g} mm) instead of switching at once, which is what an "
                      "elastomer lip that deforms before it slides would do. The authors do not discuss "
                      "it, so their finding neither confirms nor contradicts it. The named effect "
                      f"leaves {min(after):.0%}-{max(after):.0%} of the gap, {min(floors):.1f}-"
                      f"{max(floors):.1f} noise floors: the build-up is not the whole story."]
        unknown = [r for r in seals if r.diagnosis and r.diagnosis["missing_effect"] == "unknown"]
        if unknown:
            slopes = [r.extra.get("slope", float("nan")) for r in unknown]
            lines += ["", f"The {len(unknown)} `unknown` answers ({', '.join(r.name for r in unknown)}) carry a force "
                      f"along the stroke that does not turn with the direction of motion "
                      f"({min(slopes):+.2f} to {max(slopes):+.2f} N/mm by this script's fit of "
                      "Fc sgn(v) + offset + k x). Friction turns with the motion; a force that does "
                      "not is outside every friction candidate, so `unknown` with a proposed law "
                      "is the right kind of answer. What the force is (the seal's squeeze or the "
                      "pressure force varying along a printed bore) the records do not say."]
            for r in unknown:
                equation = (r.diagnosis.get("equation") or "-")
                lines.append(f"- {r.name}: proposed law `{equation[:160]}{'...' if len(equation) > 160 else ''}`")
    if reruns:
        lines += ["", "## The seals' re-runs", "",
                  "The authors re-ran the O-ring in the 25.7 mm bore at each pressure (folders `rerun` "
                  "and `reconnected`, three trials each) to assess repeatability. The workflow's answers "
                  "on them beside the original file of the same pressure (a stable answer across "
                  "the trials is what one asks of a diagnosis; the authors' repeatability result is "
                  "not restated here):", "",
                  "| record | answer | gap | 2 Fc [N] | authors' range [N] | original's answer |",
                  "| --- | --- | --- | --- | --- | --- |"]
        originals = {r.name: r for r in seals}
        for r in reruns:
            original = originals.get(f"O-ring257_{fmt(pressure_of(r.name), 2)}bar")
            lines.append(f"| {label(r)} | {answer(r)} | {gaps(r)} | {r.extra.get('two_fc', float('nan')):.1f} | "
                         f"{r.extra['range']:.1f} | {answer(original) if original else '-'} |")

    lines += ["", "## Sources", ""]
    for name, text in sources.items():
        lines.append(f"- `{name}`: {text}")
    pages.write(out, "\n".join(lines) + "\n", command, __file__, INPUTS)


SOURCES = {
    "emps": "EMPS benchmark, Janot, Gautier & Brunot (2019), *Data set and reference models of EMPS* "
            "(nonlinear system identification benchmarks); converted runs through GUIDEWAY_FMU_DATA.",
    "mnich_rack_pinion": "<https://github.com/KonradMnich/friction-identification> (commit 8b477df); "
                         "no licence file: fetch it, do not redistribute.",
    "tud_pneumatic_seals": "<https://github.com/EvaZillen/3D-printed-pneumatic-actuator> (commit "
                           "6e0bcb4), CC0 1.0.",
}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--raw", type=Path, default=os.environ.get("GUIDEWAY_FMU_REAL_RAW"),
                        help="raw files, one subfolder per data set (default $GUIDEWAY_FMU_REAL_RAW)")
    parser.add_argument("--data", type=Path, default=os.environ.get("GUIDEWAY_FMU_DATA") or None,
                        help="folder with emps-identification/ and emps-validation/ "
                             "(default $GUIDEWAY_FMU_DATA)")
    parser.add_argument("--work", type=Path, default=None, help="converted runs and diagnoses")
    parser.add_argument("--out", type=Path, default=REPO / "docs" / "real-data.md")
    parser.add_argument("--fmus", type=Path, default=None, help="FMU folder (default WORK/fmus)")
    parser.add_argument("--seals", nargs="*", default=None,
                        help="only these seal files (stems, e.g. O-ring_3bar); default all")
    parser.add_argument("--no-reruns", action="store_true", help="leave out the seals' re-runs")
    parser.add_argument("--reuse", action="store_true", help="keep diagnoses found in --work")
    args = parser.parse_args(argv)
    if args.data is None:
        parser.error("the real records' folder is not given: set GUIDEWAY_FMU_DATA (or --data) "
                     "to the folder holding emps-identification/ and emps-validation/")
    start = time.perf_counter()
    work = args.work or Path(tempfile.mkdtemp(prefix="guideway_real_"))
    fmus = args.fmus or work / "fmus"
    records: list[Record] = []
    missing: list[str] = []

    emps = emps_folder(Path(args.data))
    for name in ("emps-identification", "emps-validation"):
        if (emps / name).is_dir():
            records.append(Record("emps", name, emps / name))
        else:
            missing.append(f"EMPS {name} (not in {emps})")
    raw = Path(args.raw) if args.raw else None
    for short in ("mnich_rack_pinion", "tud_pneumatic_seals"):
        folder = raw / short if raw else None
        if folder is None or not folder.is_dir():
            missing.append(f"{short} (no raw folder{'' if raw else ': GUIDEWAY_FMU_REAL_RAW unset'})")
            continue
        module = converter(short)
        if short == "tud_pneumatic_seals":
            runs = module.convert(folder, work / "runs" / short, repeatability=not args.no_reruns)
            if args.seals:
                runs = [r for r in runs if r.name in args.seals]
        else:
            runs = module.convert(folder, work / "runs" / short)
        records += [Record(short, r.name, r) for r in runs]

    seen: dict[str, str] = {}
    for record in records:
        digest = hashlib.sha256((record.run_dir / "data.csv").read_bytes()).hexdigest()
        if digest in seen:
            record.extra["same_as"] = seen[digest]
        seen.setdefault(digest, record.name)
    stamp = freeze_sources(work, args.reuse)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(work / "src")] + ([os.environ["PYTHONPATH"]] if os.environ.get("PYTHONPATH") else [])))
    for i, record in enumerate(records, 1):
        diagnose(record, work / "out", fmus, args.reuse, env)
        said = record.refusal or record.diagnosis["missing_effect"]
        print(f"[{i}/{len(records)}] {record.data_set}/{record.name}: {said} "
              f"({record.seconds:.1f} s)", flush=True)

    wall = time.perf_counter() - start
    shown = ["python orchestration/real_data/report.py"] + (["--seals", *args.seals] if args.seals else []) + (
        ["--no-reruns"] if args.no_reruns else []) + (["--reuse"] if args.reuse else [])
    command = "GUIDEWAY_FMU_DATA=<real records> GUIDEWAY_FMU_REAL_RAW=<raw folders> " + " ".join(shown)
    write_page(records, missing, args.out, command, wall, SOURCES, stamp)
    print(f"wrote {args.out} ({len(records)} records, {wall / 60:.1f} min); work folder {work}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
