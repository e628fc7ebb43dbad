"""Step 6 of the discrepancy workflow, what diagnose writes: diagnosis.json and fit.csv
(docs/measured-run.md), PNG plots and a self-contained report.html (plots inlined as base64).
All of the report's prose is written here, from the numbers the decision and the co-simulation
return."""
from __future__ import annotations

import base64
import html
import json
from pathlib import Path

import numpy as np

from ..output import pages
from . import locate, plots, scoring
from .candidates import CANDIDATES
from .decide import Naming
from .realise import Realisation
from .signals import AMBIGUOUS, SHORT, STANDSTILL, Derivation

FORMAT = "guideway-diagnosis/1"
UNITS = {"time": "s", "position": "m", "velocity": "m/s", "speed": "m/s", "acceleration": "m/s2",
         "time_since_reversal": "s", "displacement_since_reversal": "m", "running_distance": "m"}
_ORDINAL = {1: "first", 2: "second"}


def plain(value) -> str:
    """A number as a plain decimal (no exponent, shortest round trip)."""
    if isinstance(value, (bool, np.bool_)):
        return "true" if value else "false"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    return np.format_float_positional(float(value), unique=True, trim="-")


def to_json(value, indent: int = 0) -> str:
    """JSON text with every number written by :func:`plain` (json.dumps would use exponents)."""
    pad, inner = "  " * indent, "  " * (indent + 1)
    if isinstance(value, dict):
        if not value:
            return "{}"
        items = [f"{inner}{json.dumps(str(k))}: {to_json(v, indent + 1)}" for k, v in value.items()]
        return "{\n" + ",\n".join(items) + f"\n{pad}}}"
    if isinstance(value, (list, tuple)):
        if not value:
            return "[]"
        return "[\n" + ",\n".join(inner + to_json(v, indent + 1) for v in value) + f"\n{pad}]"
    if value is None or isinstance(value, str):
        return json.dumps(value)
    return plain(value)


def write_diagnosis(path: Path, diagnosis: dict) -> Path:
    path.write_text(to_json(diagnosis) + "\n")
    return path


def write_fit(path: Path, time, measured, baseline, augmented) -> Path:
    """fit.csv: time, measured, baseline, augmented on the held-out samples."""
    rows = ["time,measured,baseline,augmented"]
    rows += [",".join(plain(v) for v in row) for row in zip(time, measured, baseline, augmented)]
    path.write_text("\n".join(rows) + "\n")
    return path


def answer_kind(diagnosis: dict) -> str:
    """The kind of answer of ``diagnosis`` in words: a missing effect, a wrong baseline
    parameter, both, no discrepancy beyond noise, or a gap no effect explains."""
    effect, corrected = diagnosis["missing_effect"], bool(diagnosis["baseline_corrections"])
    count = len(diagnosis.get("missing_effects", []))
    said = {"none": "no discrepancy beyond the noise", "unknown": "a gap no candidate effect "
            "explains"}.get(effect, f"{count} missing effects" if count > 1 else "a missing effect")
    if corrected:
        return ("a baseline parameter is wrong" if effect == "none"
                else f"a baseline parameter is wrong, and {said} after its correction")
    return said


def _parameters_text(parameters: dict) -> str:
    return ", ".join(f"{k} = {v:.6g}" if isinstance(v, float) else f"{k} = {v}"
                     for k, v in parameters.items())


def write_html(path: Path, diagnosis: dict, notes: dict, images: list[Path]) -> Path:
    """report.html: the verdict, the numbers, how they were obtained and the plots, inline."""
    d = diagnosis
    verdict = [("answer", answer_kind(d)),
               *((f"baseline {c['parameter']}", f"stated {c['stated']:.6g}, the record shows "
                  f"{c['fitted']:.6g} ({c['interval'][0]:.6g} to {c['interval'][1]:.6g}); "
                  f"refitted before any effect was looked for")
                 for c in d["baseline_corrections"]),
               ("missing effect", " then ".join(e["effect"] for e in d["missing_effects"])
                or d["missing_effect"]), ("confidence", plain(round(d["confidence"], 4))),
               *((f"{k} ({scoring.LEVEL:.0%} interval)", f"{lo:.6g} to {hi:.6g}")
                 for k, (lo, hi) in d["intervals"].items()),
               ("compared channel", d["channel"]), ("gap before (baseline)", plain(round(d["gap_before"], 6))),
               ("gap after", plain(round(d["gap_after"], 6))), ("noise floor", plain(round(d["noise_floor"], 6))),
               ("proposed equation for the residual", d["equation"] or "-")]
    candidates = [(c["effect"], plain(round(c["score"], 2)), plain(round(c["gap_after"], 6)),
                   _parameters_text(c["parameters"])) for c in d["candidates"]]
    steps = [(str(i + 1), step["effect"], plain(round(step["score"], 2)),
              plain(round(step["gap_after"], 6)), _parameters_text(step["parameters"]))
             for i, step in enumerate(d["missing_effects"])]
    parts = [f"<h1>Diagnosis of {html.escape(notes['run'])}</h1>",
             pages.table(verdict, ["", ""])]
    if len(steps) > 1:
        parts += ["<h2>Effects named in turn (each fitted beside those before it, all refitted "
                  "together; the gap after each step is that of the model holding it and those "
                  "before it; the co-simulated model and fit.csv hold the first)</h2>",
                  pages.table(steps, ["step", "effect", "score over the step before",
                                      "held-out gap after", "parameters (joint fit)"])]
    parts += ["<h2>Candidates (scored on held-out samples, cross-validated over 3 folds; "
              "parameters and held-out gap of fold 1)</h2>",
              pages.table(candidates, ["effect", "score", "held-out gap", "parameters"])]
    for title, entries in notes["sections"].items():
        parts.append(f"<h2>{html.escape(title)}</h2>")
        parts.append(pages.table(list(entries.items()), ["", ""]))
    for image in images:
        data = base64.b64encode(image.read_bytes()).decode("ascii")
        parts.append(f"<h3>{html.escape(image.stem.replace('_', ' '))}</h3>"
                     + pages.figure(f"data:image/png;base64,{data}", image.stem))
    path.write_text(pages.page("diagnosis", parts), encoding="utf-8")
    return path


def _filter(d: Derivation) -> str:
    shape = "cubic" if d.order == 3 else f"of order {d.order}"
    text = (f"Savitzky-Golay, {shape}, {d.window} samples ({d.window * d.step:.4g} s), zero phase "
            f"(no delay)")
    return text + ("" if d.uniform else ", on a uniform grid at the median step, cubic splines "
                                        "there and back")


def describe(name: str, d: Derivation | None) -> str:
    """How the signal ``name`` was obtained, in words."""
    if d is None:
        return "not recorded"
    if d.derivative < 0:
        text = f"integrated from {d.source} (trapezoid rule, 0 at the start)"
    elif d.derivative:
        text = f"derived from {d.source}: {_ORDINAL[d.derivative]} derivative, {_filter(d)}"
    elif d.window:
        text = f"measured, smoothed ({_filter(d)})"
    else:
        text = "measured"
    if d.noise_limit is not None:
        text += (f", the shortest window whose noise from {d.source} stays within "
                 f"{d.noise_limit:.4g} m/s2 RMS (at most a quarter of a stroke)")
    if d.output_noise is not None:
        text += f"; it carries {d.output_noise:.4g} m/s2 RMS of that noise"
    if d.noise is not None:
        text += (f", the longest window whose residual stays within the channel's noise "
                 f"({d.noise:.4g} RMS)" if d.window else
                 " (noisy, but even the 5-sample cubic filter takes signal)")
    if d.dequantised:
        text += (": the encoder's count steps are taken out (pre-sliding builds up over a few "
                 "counts)")
    if d.recorded_unused:
        text += f"; the recorded {name} is not used (differenced and smoothed by the rig)"
    if d.gain is not None:
        text += (f"; scaled by {d.gain:.4g}, the least-squares gain of the {SHORT}-sample second "
                 f"derivative of feed_position (first of feed_velocity without it) on it")
    return text


def describe_standstill(speed: float, band: float | None) -> str:
    """When the direction of motion counts as ambiguous, in words."""
    if band is None:
        return f"|feed_velocity| <= {speed:.4g} m/s ({STANDSTILL:.0%} of its maximum)"
    return (f"|feed_velocity| <= {speed:.4g} m/s ({AMBIGUOUS:g} times its noise or the regularised "
            f"sign's width, at most {STANDSTILL:.0%} of its maximum), and the samples next to such "
            f"a rest whose position lies within {band:.4g} m of it (the position has not moved; a "
            f"differenced velocity spreads starts and stops over its window)")


def describe_friction_sign(run) -> str:
    """How the friction_force channel's sign convention was taken, in words."""
    if run.friction_sign is None:
        return "no friction_force channel"
    said = ("as [channels] friction_sign states" if run.friction_sign_stated
            else "found from the data (its level along the direction of motion is "
                 + ("positive" if run.friction_sign == "along_motion" else "negative") + ")")
    what = ("along the motion (the force the sensor feels)" if run.friction_sign == "along_motion"
            else "opposing the motion (the resistance); the workflow turned it along the motion "
                 "and writes fit.csv and the plots back in the record's convention")
    return f"friction_force {what}, {said}"


def _rounded(parameters: dict) -> dict:
    return {k: (round(v, 12) if isinstance(v, float) else v) for k, v in parameters.items()}


def diagnosis_record(naming, realised) -> dict:
    """The content of diagnosis.json, of a horizontal or a vertical run's naming and
    realisation."""
    before, after = realised.gaps(naming)
    return {
        "format": FORMAT, "missing_effect": naming.effect,
        "confidence": round(naming.confidence, 6), "channel": naming.run.channel,
        "gap_before": round(before, 8), "gap_after": round(after, 8),
        "noise_floor": round(naming.noise, 8),
        "candidates": [{"effect": f.effect, "gap_after": round(g, 8), "score": round(float(s), 3),
                        "parameters": _rounded(f.parameters)}
                       for s, f, g in naming.ranked],
        "equation": naming.equation,
        "baseline_corrections": [{k: c[k] for k in ("parameter", "stated", "fitted", "interval")}
                                 for c in naming.corrections],
        "intervals": naming.intervals,
        "missing_effects": [{"effect": step.effect, "gap_after": round(step.gap_after, 8),
                             "score": round(float(step.score), 3),
                             "parameters": _rounded(step.fit.parameters),
                             "intervals": step.intervals} for step in naming.steps],
        "warnings": list(naming.run.warnings),
        **({"separating_experiment": naming.experiment} if naming.experiment is not None else {}),
    }


def _notes(naming: Naming, realised: Realisation, seconds: float) -> dict:
    """The report's tables: how every number was obtained."""
    nm, run, ctx = naming, naming.run, naming.ctx
    motion, y, winner = ctx.motion, ctx.y, naming.winner
    how = {name: describe(name, d) for name, d in motion.how.items()}
    how["standstill"] = describe_standstill(motion.standstill_speed, motion.rest_band)
    return {"run": str(run.path), "sections": {
        "Samples": {"samples": run.time.size, "fit samples": int(nm.fit_mask.sum()),
                    "held-out samples (gap, fit.csv)": int(nm.held.sum()),
                    "left out of fit and gap (standstill, ambiguous direction, record ends where "
                    "the acceleration is extrapolated)": int((~nm.usable).sum()),
                    "split": f"{locate.blocks(run.time.size)} equal blocks of the record, every "
                             f"third held out; scores cross-validated over the {locate.FOLDS} "
                             f"such folds"},
        "Motion driving the model": {**how, "normal_force (laws only)":
                                     describe("normal_force", ctx.load_how)},
        "Gap and noise": {
            "baseline gap (vectorised fit)": f"{nm.gap_base:.6g}",
            "noise floor": f"{nm.noise:.6g}: the larger of the white floor and the RMS of the "
                           "reported model's residual that does not repeat with the feed's state "
                           "(half the square difference to the sample of nearest position, "
                           "velocity and acceleration on another pass, robust), over the "
                           "held-out range of the channel",
            "white noise floor": f"{nm.white_noise:.6g}: robust RMS of second differences of "
                                 "the baseline residual (1.4826 MAD / sqrt 6), the noise's "
                                 "high-frequency part; significance is judged against it",
            "residual autocorrelation (lags 1-5)": f"{nm.white:.4g} "
                                                   f"(noise alone: ~ {1 / np.sqrt(nm.held.sum()):.2g})",
            "cross-validated baseline gap / white noise floor (all usable samples)":
                f"{nm.cross_gap:.4g}",
            "significant": str(nm.significant),
            "residual peaks [Hz]": ", ".join(f"{f:.4g}" for f in nm.where["frequencies"]) or "-"},
        "Share of the baseline residual explained by bins of": {
            k: f"{v:.3f}" for k, v in sorted(nm.where["explained"].items(), key=lambda kv: -kv[1])},
        "Models": {"baseline": f"{nm.baseline.parameters} (FrictionCoulomb, fitted with the "
                               f"vectorised physics: the 'baseline' of fit.csv)",
                   "augmented": f"{winner.parameters} ({winner.fmu}, rig mass "
                                f"{winner.rig_mass:.6g} kg): co-simulated, the 'augmented' of "
                                f"fit.csv" if winner else "= baseline",
                   "scenario": f"{realised.scenario.name} (run it with guideway-fmu run)",
                   "co-simulation": f"FeedKinematics (replay) -> {realised.model.fmu} -> "
                                    f"HorizontalRig, gauss-seidel at the median sample interval; "
                                    f"wall time {realised.wall_time:.2f} s; largest deviation from "
                                    f"the vectorised model {realised.agreement:.3g} of the range",
                   "not told apart from the named effect (the record passes its positions "
                   "once: record strokes back and forth over the same stretch to separate them)":
                       ", ".join(nm.not_told_apart) or "-",
                   "equation (unknown only)": nm.equation or "-",
                   "score of a law in foreign terms (normal force, peak frequencies)":
                       f"{nm.foreign_score:.4g}",
                   "equation held-out gap":
                       f"{locate.gap(y, nm.baseline.prediction + nm.law, nm.held):.6g}"
                       if nm.law is not None else "-"},
        "Sign of friction_force": {"convention": describe_friction_sign(run)},
        "Delay of the compared channel": {
            "delay behind the motion [s]": (f"{run.channel_delay:.6g}: the models are driven by "
                                            f"the motion that long before each sample (the "
                                            f"replay too)" if run.channel_delay
                                            else "none found")},
        "Warnings": {str(i + 1): w for i, w in enumerate(run.warnings)} or {"-": "none"},
        "Confidence held at the doubt level": {str(i + 1): w for i, w in enumerate(nm.doubts)}
                                              or {"-": "no"},
        "Baseline intervals": {f"{k} ({scoring.LEVEL:.0%}, jackknife over the folds)":
                               f"{lo:.6g} to {hi:.6g}"
                               for k, (lo, hi) in nm.baseline_intervals.items()},
        "Timing": {"diagnose wall time [s]": f"{seconds:.2f}"},
    }}


def separating_words(experiment: dict | None) -> str:
    """The separating experiment in words: the record to make and both candidates' predictions."""
    if experiment is None:
        return "-"
    said = "; ".join(f"{effect}: displacement {1e6 * p['displacement_change']:.4g} um, natural "
                     f"frequency {p['natural_frequency']:.5g} Hz"
                     for effect, p in experiment["predictions"].items())
    apart = experiment["displacement_apart_in_noise"]
    return (f"record {experiment['record']}. Predicted: {said}; apart by "
            f"{100 * experiment['frequency_apart']:.3g} % in frequency"
            + (f" and {apart:.3g} noise floors in displacement" if apart is not None else ""))


def write_vertical_report(out: Path, naming, realised, seconds: float) -> dict:
    """diagnosis.json, fit.csv, the plots (time, spectra, ranking) and report.html of a
    vertical run into ``out``; returns the diagnosis."""
    nm, rig, y, held = naming, naming.rig, naming.y, naming.held
    diagnosis = diagnosis_record(nm, realised)
    write_diagnosis(out / "diagnosis.json", diagnosis)
    time = nm.run.time
    write_fit(out / "fit.csv", time[held], y[held], realised.baseline[held],
              realised.augmented[held])
    spectra = {"measured": rig.spectrum(y), "baseline": rig.spectrum(realised.baseline)}
    if nm.winner is not None:
        spectra[f"+ {nm.effect}"] = rig.spectrum(realised.augmented)
    feed = rig.spectrum(rig.motion.v)
    marks = {"feed": float(feed[0][1 + np.argmax(feed[1][1:])]),
             "f_n baseline": rig.natural_frequency(rig.base),
             "free vibration measured": rig.measured_natural_frequency(y)}
    images = [
        plots.plot_comparison(out / "measured_vs_models.png", time, y, realised.baseline,
                              realised.augmented, held, nm.run.channel, nm.effect, rig.unit),
        plots.plot_spectra(out / "spectra.png", spectra, nm.run.channel, rig.unit, marks),
        plots.plot_ranking(out / "candidate_ranking.png", diagnosis["candidates"],
                           diagnosis["gap_before"], nm.noise),
    ]
    notes = {"run": str(nm.run.path), "sections": {
        "Samples": {"samples": time.size, "fit samples": int(nm.fit_mask.sum()),
                    "held-out samples (gap, fit.csv)": int(held.sum()),
                    "split": f"{locate.blocks(time.size)} equal blocks, every third held out"},
        "Model": {"system": "FeedKinematics (replay of the measured motion) -> contact u; "
                            "ForceTable (normal force) -> VerticalDynamics.F_ext; "
                            "VerticalDynamics <-> contact, stabilised coupling",
                  "baseline": f"{rig.base} (calibrated: {nm.baseline.parameters})",
                  "normal force driving it": (
                      f"denoised (noise RMS {rig.load_noise:.4g} N; spectral subtraction "
                      f"keeping {rig.load_kept:.1%} of the short-time Fourier bins)"
                      if rig.load_noise else "as recorded (no noise above its resolution)"),
                  "start": "static equilibrium under gravity and the first normal force"
                           + (" plus the fitted start_force (the first sample's noise)"
                              if "start_force" in nm.baseline.parameters else "")
                           + ", the film steady at the first feed velocity",
                  "fits": f"the monolithic reference at rtol {rig.rtol:.3g}; candidates by one "
                          f"parameter each, started where the model's free vibration matches "
                          f"the record's",
                  "augmented": f"{nm.winner.parameters}" if nm.winner else "= baseline",
                  "not told apart from the named effect (explains the record as well, within "
                  "the naming margin in independent samples; stiffness and mass meet in "
                  "sqrt(k / m))": ", ".join(nm.not_told_apart) or "-",
                  "separating experiment": separating_words(nm.experiment),
                  "scenario": f"{realised.scenario.name} (run it with guideway-fmu run)",
                  "co-simulation": f"wall time {realised.wall_time:.2f} s; largest deviation "
                                   f"from the reference {realised.agreement:.3g} of the range"},
        "Gap and noise": {"baseline gap": f"{nm.gap_base:.6g}", "noise floor": f"{nm.noise:.6g}",
                          "significant": str(nm.significant),
                          "residual peaks [Hz]": ", ".join(f"{f:.4g}" for f in nm.frequencies) or "-",
                          "equation (unknown only)": nm.equation or "-"},
        "Warnings": {str(i + 1): w for i, w in enumerate(nm.run.warnings)} or {"-": "none"},
        "Confidence held at the doubt level": {str(i + 1): w for i, w in enumerate(nm.doubts)}
                                              or {"-": "no"},
        "Timing": {"diagnose wall time [s]": f"{seconds:.2f}"},
    }}
    write_html(out / "report.html", diagnosis, notes, images)
    return diagnosis


def write_report(out: Path, naming: Naming, realised: Realisation, seconds: float) -> dict:
    """diagnosis.json, fit.csv, the plots and report.html into ``out``; returns the diagnosis."""
    nm, run, ctx = naming, naming.run, naming.ctx
    y, held = ctx.y, nm.held
    diagnosis = diagnosis_record(nm, realised)
    write_diagnosis(out / "diagnosis.json", diagnosis)
    sign = run.channel_sign  # back to the record's own convention
    write_fit(out / "fit.csv", run.time[held], sign * y[held], sign * realised.baseline[held],
              sign * realised.augmented[held])
    signal_name = (CANDIDATES[nm.effect].signal if nm.winner is not None
                   else max(nm.where["explained"], key=nm.where["explained"].get))
    signal = locate.signals(ctx)[signal_name]
    images = [
        plots.plot_comparison(out / "measured_vs_models.png", run.time, sign * y,
                              sign * realised.baseline, sign * realised.augmented, held,
                              run.channel, nm.effect),
        plots.plot_residual(out / f"residual_vs_{signal_name}.png", signal, signal_name,
                            UNITS[signal_name], sign * (y - realised.baseline),
                            sign * (y - realised.augmented),
                            held, nm.effect),
        plots.plot_ranking(out / "candidate_ranking.png", diagnosis["candidates"],
                           diagnosis["gap_before"], nm.noise),
    ]
    write_html(out / "report.html", diagnosis, _notes(nm, realised, seconds), images)
    return diagnosis
