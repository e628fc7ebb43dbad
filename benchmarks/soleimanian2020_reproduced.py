"""Soleimanian et al. (2020) reproduced: every number and trend the paper states about its own
results that the model can compute, under each reading of its preload
(analysis/soleimanian2020.py), side by side, written to docs/soleimanian2020-reproduced.md with
its figures in docs/figures/.

Every shipped scenario of the paper (the unloaded rig, 6000/9000/12000 N at the paper's
excitation frequencies, dry against lubricated at 9000 N) runs once per reading through the
co-simulation master and the FMUs, one 0.2 s feed cycle each, in ``--jobs`` worker processes;
the explicit EHL solutions are steady ones of analysis/ehl.py at the instants named. Spectral
and envelope figures skip the first 10 ms (the start's transient).

    python benchmarks/soleimanian2020_reproduced.py [--jobs 2] [--out docs/soleimanian2020-reproduced.md]
"""
from __future__ import annotations

import argparse
import tempfile
import time
import warnings
from multiprocessing import Pool
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from guideway_fmu import scenarios  # noqa: E402
from guideway_fmu.analysis import ehl  # noqa: E402
from guideway_fmu.analysis import soleimanian2020 as paper  # noqa: E402
from guideway_fmu.fmu_build import build  # noqa: E402
from guideway_fmu.cosim import master, system  # noqa: E402
from guideway_fmu.numerics.spectrum import spectrum  # noqa: E402
from guideway_fmu.physics.roller_guide import four_rows  # noqa: E402
from guideway_fmu.physics.roller_guide.film import LineContact  # noqa: E402

import pages  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
LOAD_CASES = {6000: (2500, 3000, 4500, 5000, 9000), 9000: (2500, 3000, 4500, 5000, 9000),
              12000: (2500, 3000, 4000, 4500, 9000, 9500)}
DRY = (2500, 4500)
SKIP = 0.01  # s of the start left out of spectra, envelopes and statistics
KEEP = ("Carriage.y", "Contact.F_upper", "Contact.F_lower", "Contact.h_upper", "Feed.u",
        "Friction.F_friction")  # the friction where the scenario has it (the unloaded rig)


#: Why a statement disagrees where it does (measured in the table; a cause not yet checked by a
#: separate run says so)
CAUSES = {
    "S44": "Eq. 4's film (its extrapolated law at the squeeze bracket's 0.25) and the explicit "
           "central film differ by more than 20 %: the law's load exponent (-0.045) is flatter "
           "than the explicit solution's, so the ratio grows with the load. The paper's "
           "explicit runs follow the recorded load with the squeeze term; ours are steady at "
           "one instant.",
    "S45": "The load per roller: the explicit central pressure follows the Hertz pressure of "
           "the roller load, 0.43 GPa at Q0 = 115 N and 0.61 GPa at 230 N; 0.8-1.0 GPa needs "
           "about 460 N per roller, the groove reading.",
    "S49": "As S45: the explicit central pressure follows the Hertz pressure of the largest "
           "roller load of the cycle, which the lighter preload keeps lower.",
    "S38 (2500 Hz)": "The film adds to each roller's approach (eq. 3) and so stiffens the rows: "
                     "it moves the loaded resonance as well as adding load, and where the "
                     "excitation lies on the falling side of that resonance the peak load drops "
                     "(measured; the mechanism is our reading of the runs).",
    "S38 (4500 Hz)": "The film adds to each roller's approach (eq. 3) and so stiffens the rows: "
                     "it moves the loaded resonance as well as adding load. 4500 Hz lies close to "
                     "the loaded resonance of the lighter preloads, where that shift lowers the "
                     "peak load (measured; the mechanism is our reading of the runs).",
    "S36": "Half of it holds under every reading: the feed's share of the film's variation "
           "falls from 9000 to 12000 N. Where the share above 1 kHz does not grow with it, the "
           "mean over the four frequencies is carried by the one nearest the loaded resonance, "
           "which the load and the preload move (our reading of the table; not checked "
           "frequency by frequency).",
    "S21": "The start excites a free vibration at the natural frequency that the undamped "
           "model (eqs. 1-5 have no damping) carries over the whole cycle, 2-4 orders above the "
           "feed's line; the feed's film change enters both rows alike and cancels in the net "
           "force except through their load difference. The paper does not say how its runs "
           "start or whether a transient was removed.",
    "C5 (4500 Hz)": "At 4500 Hz the runs sit near the loaded resonance, where the excitation's "
                    "share swamps the feed's (0.1-0.3 %) for every load: the paper itself says "
                    "resonance reduces the coupling further (conclusion 6).",
}


def names() -> list[str]:
    out = ["soleimanian2020_unloaded"]
    out += [f"soleimanian2020_{a}N_{f}Hz" for a, fs in LOAD_CASES.items() for f in fs]
    return out + [f"soleimanian2020_9000N_{f}Hz_dry" for f in DRY]


def one_run(job) -> tuple:
    """(reading, scenario, columns) of one co-simulation."""
    warnings.simplefilter("ignore")
    reading, name, fmus = job
    s = system.load(scenarios.find(name), fmus).with_changes(parameters=reading.parameters())
    rec = master.simulate(s).recording
    return reading.name, name, {"time": rec.time,
                                **{c: rec.columns[c] for c in KEEP if c in rec.columns}}


def steady(run) -> dict:
    keep = run["time"] >= SKIP
    return {k: v[keep] for k, v in run.items()}


def roller(load: float, speed: float, entrainment: float = 0.5):
    """The EHL line contact of one roller (Tables 2-3) at ``load`` [N] and feed speed [m/s],
    entrained at ``entrainment`` times the feed speed (a half: a roller between a raceway moving
    at the feed speed and one at rest)."""
    c = LineContact()
    return ehl.roller_contact(load=load / c.length, velocity=entrainment * abs(speed),
                              radius=c.radius, e_reduced=c.e_reduced, viscosity=c.viscosity,
                              pressure_viscosity=c.pressure_viscosity)


def explicit(load: float, speed: float, entrainment: float = 0.5) -> dict:
    """The steady explicit EHL solution of one roller at ``load`` [N] and feed speed [m/s]
    (``entrainment`` as :func:`roller`): central film [m], central and peak pressure [Pa], and
    the distributions."""
    result, out = ehl.solve_roller(roller(load, speed, entrainment))
    central = float(np.interp(0.0, result.x, result.p))
    return {"h_c": out["h_c"], "p_c": central, "p_max": out["p_max"], "x": result.x,
            "p": result.p, "h": result.h}


def statements(readings, runs, solutions: dict) -> list[dict]:
    """Each published statement: id, source, what the paper says, our value per reading and
    whether it agrees, with the reason. The explicit EHL solutions it makes go into
    ``solutions`` ("unloaded", "loaded": reading -> solution) for the figures."""
    rows = []

    def add(sid, source, said, values, agree, why):
        rows.append({"id": sid, "source": source, "said": said, "values": values,
                     "agree": agree, "why": why})

    def run(r, name):
        return steady(runs[r.name, name])

    # S14: natural frequency
    add("S14", "text after Fig. 14", "unloaded natural frequency 6590 Hz",
        {r.name: f"{paper.natural_frequency(r.guideway(), r.mass):.0f} Hz" for r in readings},
        {r.name: True for r in readings},
        "the rail mass is not published: each reading's mass is fitted to it (not a test)")
    # S18: sub-micron film
    films = {r.name: float(np.max(run(r, "soleimanian2020_unloaded")["Contact.h_upper"]))
             for r in readings}
    add("S18", "Fig. 18", "the upper row's film stays sub-micron (mixed EHL), unloaded",
        {k: f"max {1e6 * v:.3f} um" for k, v in films.items()},
        {k: v < 1e-6 for k, v in films.items()}, "largest film over the feed cycle")
    # S25: film 2-3 orders stiffer than the solids
    ratios = {r.name: paper.film_to_solid_stiffness(r.guideway()) for r in readings}
    add("S25", "text to Fig. 23", "the film is two to three orders of magnitude stiffer than "
        "the contacting solids", {k: f"{v:.0f}x" for k, v in ratios.items()},
        {k: 100.0 <= v < 1e4 for k, v in ratios.items()},
        "at rest, unloaded, 0.29 m/s: 9 delta / (10 m h) of the steady film in series")
    # S44, S45: explicit EHL of the unloaded rig at its mean upper load and peak feed speed
    explicit_unloaded, same_speed = {}, {}
    for r in readings:
        u = run(r, "soleimanian2020_unloaded")
        i = int(np.argmax(np.abs(u["Feed.u"])))
        load, speed = float(np.mean(u["Contact.F_upper"])), float(u["Feed.u"][i])
        explicit_unloaded[r.name] = (explicit(load, speed), float(u["Contact.h_upper"][i]))
        same_speed[r.name] = explicit(load, speed, entrainment=1.0)["h_c"]
    solutions["unloaded"] = {k: e for k, (e, _) in explicit_unloaded.items()}
    add("S44", "Fig. 33, conclusion 2", "the implicit (eq. 4) and explicit central films agree, "
        "unloaded", {k: f"implicit / explicit {h / same_speed[k]:.2f} (entrained at u/2: "
                     f"{h / e['h_c']:.2f})" for k, (e, h) in explicit_unloaded.items()},
        {k: abs(h / same_speed[k] - 1.0) <= 0.2 for k, (_, h) in explicit_unloaded.items()},
        "at the peak feed speed and the cycle's mean upper load, the explicit film entrained at "
        "the feed speed u as eq. 5's U = mu0 u / (E' R) has it (a roller between a raceway at u "
        "and one at rest is entrained at u/2: both shown); within 20 % taken as agreement")
    add("S45", "Fig. 33", "unloaded central pressure 0.8-1.0 GPa (spikes to 1.1 GPa)",
        {k: f"{e['p_c'] / 1e9:.2f} GPa (peak {e['p_max'] / 1e9:.2f})"
         for k, (e, _) in explicit_unloaded.items()},
        {k: 0.7e9 <= e["p_c"] <= 1.1e9 for k, (e, _) in explicit_unloaded.items()},
        "explicit EHL at the cycle's mean upper load; 0.7-1.1 GPa taken as agreement")
    # S49: loaded 9000 N / 9000 Hz central pressure up to 1.1 GPa (spikes 1.3)
    loaded = {}
    for r in readings:
        u = run(r, "soleimanian2020_9000N_9000Hz")
        i = int(np.argmax(u["Contact.F_upper"]))
        loaded[r.name] = explicit(float(u["Contact.F_upper"][i]), max(abs(float(u["Feed.u"][i])), 0.01))
    solutions["loaded"] = loaded
    add("S49", "Fig. 35", "9000 N at 9000 Hz: central pressure up to 1.1 GPa (spikes to 1.3)",
        {k: f"{e['p_c'] / 1e9:.2f} GPa (peak {e['p_max'] / 1e9:.2f})" for k, e in loaded.items()},
        {k: 0.9e9 <= e["p_c"] <= 1.3e9 for k, e in loaded.items()},
        "explicit steady EHL at the largest upper load of the cycle; 0.9-1.3 GPa taken as agreement")
    # S38: the film raises the contact load (9000 N, 2500 and 4500 Hz)
    for f in DRY:
        change = {}
        for r in readings:
            lub = run(r, f"soleimanian2020_9000N_{f}Hz")["Contact.F_upper"]
            dry = run(r, f"soleimanian2020_9000N_{f}Hz_dry")["Contact.F_upper"]
            change[r.name] = float(np.max(lub) / np.max(dry) - 1.0)
        add(f"S38 ({f} Hz)", f"Figs. {30 if f == 2500 else 31}", "including the film increases "
            f"the contact load (9000 N, {f} Hz)", {k: f"peak {100 * v:+.1f} %" for k, v in change.items()},
            {k: v > 0.0 for k, v in change.items()}, "largest upper roller load, lubricated over dry")
    # S23, S28, S35: envelopes peak at resonance
    for amplitude, freqs in LOAD_CASES.items():
        peaks = {r.name: [float(np.max(run(r, f"soleimanian2020_{amplitude}N_{f}Hz")["Contact.F_upper"]))
                          for f in freqs] for r in readings}
        fig = {6000: 22, 9000: 25, 12000: 28}[amplitude]
        add(f"S{ {6000: 23, 9000: 28, 12000: 35}[amplitude]}", f"Fig. {fig}",
            f"{amplitude} N: the contact-load envelope peaks at resonance",
            {k: f"largest at {freqs[int(np.argmax(v))]} Hz" for k, v in peaks.items()},
            {k: 0 < int(np.argmax(v)) < len(freqs) - 1 for k, v in peaks.items()},
            "a peak inside the paper's frequencies (not at either end) taken as a resonance")
    # S24: film insensitive to the load change (6000 N)
    spread = {}
    for r in readings:
        cases = [run(r, f"soleimanian2020_6000N_{f}Hz") for f in LOAD_CASES[6000]]
        load_peaks = np.array([np.max(c["Contact.F_upper"]) for c in cases])
        film_means = np.array([np.mean(c["Contact.h_upper"]) for c in cases])
        spread[r.name] = (np.ptp(film_means) / np.mean(film_means),
                          np.ptp(load_peaks) / np.mean(load_peaks))
    add("S24", "Fig. 23", "6000 N: the upper film is almost insensitive to the load change over "
        "the excitation frequencies", {k: f"film {100 * a:.1f} %, load {100 * b:.0f} %"
                                       for k, (a, b) in spread.items()},
        {k: a < 0.25 * b for k, (a, b) in spread.items()},
        "spread of the mean film against that of the peak load over the five frequencies")
    # S26: the 5 Hz feed dominates the film's variation (6000 N)
    share = {r.name: float(np.mean([paper.band_share(c["time"], c["Contact.h_upper"], 0.0, 100.0)
                                    for c in (run(r, f"soleimanian2020_6000N_{f}Hz")
                                              for f in LOAD_CASES[6000])])) for r in readings}
    add("S26", "Fig. 23", "6000 N: the feed frequency (5 Hz) makes the largest contribution to "
        "the film's variation", {k: f"{100 * v:.0f} % below 100 Hz" for k, v in share.items()},
        {k: v > 0.5 for k, v in share.items()}, "share of the film's variance below 100 Hz")
    # S33, S36: with the load, the film's variation at the excitation and natural frequencies
    # gains weight and the feed's loses it (Figs. 23, 26, 29)
    weight = {}
    common = sorted(set.intersection(*(set(f) for f in LOAD_CASES.values())))
    for r in readings:
        for amplitude, freqs in LOAD_CASES.items():
            cases = [run(r, f"soleimanian2020_{amplitude}N_{f}Hz") for f in freqs]
            shared = [c for f, c in zip(freqs, cases) if f in common]
            film_means = np.array([np.mean(c["Contact.h_upper"]) for c in cases])
            load_peaks = np.array([np.max(c["Contact.F_upper"]) for c in cases])
            weight[r.name, amplitude] = (
                float(np.mean([paper.band_share(c["time"], c["Contact.h_upper"], 1000.0, 2e4)
                               for c in shared])),
                float(np.mean([paper.band_share(c["time"], c["Contact.h_upper"], 0.0, 100.0)
                               for c in shared])),
                float(np.ptp(film_means) / np.mean(film_means)),
                float(np.ptp(load_peaks) / np.mean(load_peaks)))
    at = f"mean over {', '.join(map(str, common))} Hz, the frequencies run at every load"
    add("S33", "Fig. 26", "9000 N: the film's overall range stays insensitive to the load change; "
        "its variation at the natural frequency gains significance (against 6000 N)",
        {r.name: f"film {100 * weight[r.name, 9000][2]:.1f} %, load "
                 f"{100 * weight[r.name, 9000][3]:.0f} %; above 1 kHz "
                 f"{100 * weight[r.name, 6000][0]:.2g} % -> {100 * weight[r.name, 9000][0]:.2g} %"
         for r in readings},
        {r.name: weight[r.name, 9000][2] < 0.25 * weight[r.name, 9000][3]
         and weight[r.name, 9000][0] > weight[r.name, 6000][0] for r in readings},
        "spread of the mean film against that of the peak load over the frequencies (as S24); "
        f"share of the film's variance above 1 kHz (excitation and natural frequency), {at}")
    add("S36", "Fig. 29", "12000 N: the natural frequency's effect on the film grows further and "
        "the feed's shrinks (against 9000 N)",
        {r.name: f"above 1 kHz {100 * weight[r.name, 9000][0]:.2g} % -> "
                 f"{100 * weight[r.name, 12000][0]:.2g} %; below 100 Hz "
                 f"{100 * weight[r.name, 9000][1]:.3g} % -> {100 * weight[r.name, 12000][1]:.3g} %"
         for r in readings},
        {r.name: weight[r.name, 12000][0] > weight[r.name, 9000][0]
         and weight[r.name, 12000][1] < weight[r.name, 9000][1] for r in readings},
        f"shares of the film's variance above 1 kHz and below 100 Hz, {at}")
    # S21: 9000 N / 3000 Hz, the 5 Hz effect more pronounced than the natural frequency in y
    lines = {}
    for r in readings:
        c = run(r, "soleimanian2020_9000N_3000Hz")
        fn = paper.natural_frequency(r.guideway(), r.mass)
        lines[r.name] = (paper.spectrum_peak(c["time"], c["Carriage.y"], 2.0, 60.0)[1],
                         paper.spectrum_peak(c["time"], c["Carriage.y"], 0.7 * fn, 1.3 * fn)[1])
    add("S21", "Fig. 19b", "9000 N, 3000 Hz: the feed frequency shows more than the natural "
        "frequency in the displacement's spectrum",
        {k: f"feed {1e9 * a:.2g} nm, natural {1e9 * b:.2g} nm" for k, (a, b) in lines.items()},
        {k: a > b for k, (a, b) in lines.items()},
        "largest lines of y within 2-60 Hz and within 30 % of f_n")
    # C5 / S32: coupling more pronounced at lower loads
    for f in (2500, 4500):
        shares = {r.name: [paper.band_share(run(r, f"soleimanian2020_{a}N_{f}Hz")["time"],
                                            run(r, f"soleimanian2020_{a}N_{f}Hz")["Contact.F_upper"],
                                            0.0, 100.0) for a in LOAD_CASES] for r in readings}
        add(f"C5 ({f} Hz)", "conclusion 5, S30-S32", "the feed's coupling is more pronounced at "
            f"lower loads ({f} Hz)", {k: " > ".join(f"{100 * s:.1f} %" for s in v)
                                      for k, v in shares.items()},
            {k: v[0] > v[1] > v[2] for k, v in shares.items()},
            "share of the upper load's variance below 100 Hz at 6000, 9000, 12000 N")
    # S3, S4: quasi-static, the lower row unloads and K(y) changes course
    y = np.linspace(0.0, 2e-5, 401)
    course = {}
    for r in readings:
        g = r.guideway()
        k = four_rows.quasi_static_stiffness(g, y, paper.RIG_SPEED)
        lower = four_rows.quasi_static_state(g, y, paper.RIG_SPEED)[1]
        turn = int(np.argmin(k))
        course[r.name] = (float(lower[-1] / g.preload_per_roller), 0 < turn < y.size - 1, y[turn])
    add("S3-S4", "Fig. 3", "the lower rows unload and past it the stiffness K(y) changes course "
        "and rises", {k: f"lower load {v[0]:.0e} Q0; K least at {1e6 * v[2]:.1f} um"
                      for k, v in course.items()},
        {k: v[0] < 1e-6 and v[1] for k, v in course.items()},
        "quasi-static, lubricated, 0.29 m/s, y from 0 to 20 um")
    # S13 / C4: the unloaded spectrum holds the natural and the feed frequency
    both = {}
    resolution = 1.0 / float(np.ptp(run(readings[0], "soleimanian2020_unloaded")["time"]))
    for r in readings:
        c = run(r, "soleimanian2020_unloaded")
        fn = paper.natural_frequency(r.guideway(), r.mass)
        f_peak, _ = paper.spectrum_peak(c["time"], c["Carriage.y"], 0.5 * fn, 1.5 * fn)
        f_feed, _ = paper.spectrum_peak(c["time"], c["Carriage.y"], 2.0, 60.0)
        both[r.name] = (f_peak, f_feed)
    add("S13, C4", "Fig. 14, conclusion 4", "unloaded: the displacement's spectrum shows the "
        "natural frequency and the feed frequency",
        {k: f"lines at {a:.0f} Hz and {b:.0f} Hz" for k, (a, b) in both.items()},
        {k: abs(a / paper.PAPER_NATURAL_FREQUENCY - 1) < 0.1
         and abs(b - 5.0 * round(b / 5.0)) <= resolution for k, (a, b) in both.items()},
        "largest lines within 50 % of f_n and within 2-60 Hz (a multiple of 5 Hz within the "
        "spectrum's resolution, 1 / the run's length)")
    return rows


def figures(readings, runs, solutions, out: Path) -> list[str]:
    """Envelopes against frequency (Figs. 22, 25, 28), dry against lubricated (Figs. 30-31),
    the upper films (Figs. 23, 26, 29), the friction (Figs. 11-13), the displacement's spectra
    (Figs. 14, 19b) and the explicit EHL pressures and films (``solutions``: "unloaded" and
    "loaded" by reading; Figs. 33, 35), per reading; returns the markdown image lines."""
    out.mkdir(parents=True, exist_ok=True)
    lines = []
    fig, axes = plt.subplots(1, len(readings), figsize=(5 * len(readings), 3.8), sharey=True)
    for ax, r in zip(np.atleast_1d(axes), readings):
        for amplitude, freqs in LOAD_CASES.items():
            peaks = [np.max(steady(runs[r.name, f"soleimanian2020_{amplitude}N_{f}Hz"])
                            ["Contact.F_upper"]) for f in freqs]
            ax.plot(freqs, peaks, "o-", label=f"{amplitude} N")
        ax.set(title=f"reading '{r.name}' (Q0 = {r.preload_per_roller:.0f} N)",
               xlabel="excitation frequency [Hz]", ylabel="largest upper roller load [N]")
        ax.grid(alpha=0.3)
    np.atleast_1d(axes)[0].legend()
    fig.tight_layout()
    fig.savefig(out / "soleimanian2020_envelopes.png", dpi=110)
    plt.close(fig)
    lines.append("![Contact-load envelopes against excitation frequency (cf. Figs. 22, 25, 28)]"
                 "(figures/soleimanian2020_envelopes.png)")
    fig, axes = plt.subplots(len(DRY), len(readings), figsize=(5 * len(readings), 6.5),
                             squeeze=False)
    for row, f in enumerate(DRY):
        for ax, r in zip(axes[row], readings):
            for label, name in (("lubricated", f"soleimanian2020_9000N_{f}Hz"),
                                ("dry", f"soleimanian2020_9000N_{f}Hz_dry")):
                c = runs[r.name, name]
                window = (c["time"] >= 0.05) & (c["time"] <= 0.05 + 4.0 / f)
                ax.plot(1e3 * c["time"][window], c["Contact.F_upper"][window], label=label)
            ax.set(title=f"9000 N, {f} Hz, reading '{r.name}'", xlabel="time [ms]",
                   ylabel="upper roller load [N]")
            ax.grid(alpha=0.3)
    axes[0][0].legend()
    fig.tight_layout()
    fig.savefig(out / "soleimanian2020_dry_vs_lubricated.png", dpi=110)
    plt.close(fig)
    lines.append("![Upper roller load, dry against lubricated, four load cycles (cf. Figs. 30-31)]"
                 "(figures/soleimanian2020_dry_vs_lubricated.png)")
    fig, axes = plt.subplots(len(LOAD_CASES), len(readings),
                             figsize=(5 * len(readings), 3.3 * len(LOAD_CASES)), squeeze=False)
    for row, (amplitude, freqs) in enumerate(LOAD_CASES.items()):
        for ax, r in zip(axes[row], readings):
            for f in freqs:
                c = runs[r.name, f"soleimanian2020_{amplitude}N_{f}Hz"]
                ax.plot(c["time"][::25], 1e9 * c["Contact.h_upper"][::25], lw=0.8,
                        label=f"{f} Hz")
            ax.set(title=f"{amplitude} N, reading '{r.name}'", xlabel="time [s]",
                   ylabel="upper roller film [nm]")
            ax.grid(alpha=0.3)
        axes[row][0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "soleimanian2020_films.png", dpi=110)
    plt.close(fig)
    lines.append("![Upper roller film over the feed cycle at 6000, 9000 and 12000 N (cf. Figs. "
                 "23, 26, 29)](figures/soleimanian2020_films.png)")
    fig, axes = plt.subplots(1, 3, figsize=(15, 3.8))
    t = np.linspace(0.0, 0.2, 2001)
    u, mu = paper.hess_soom_friction(t)
    axes[0].plot(u, mu)
    axes[0].set(title="one roller, 250 N, Table 1 surface (cf. Fig. 11)",
                xlabel="sliding velocity [m/s]", ylabel="friction coefficient [-]")
    for r in readings:
        c = runs[r.name, "soleimanian2020_unloaded"]
        axes[1].plot(c["time"], c["Friction.F_friction"], lw=0.8, label=f"'{r.name}'")
        axes[2].plot(c["Feed.u"], c["Friction.F_friction"], lw=0.8, label=f"'{r.name}'")
    axes[1].set(title="unloaded rig (cf. Fig. 12)", xlabel="time [s]",
                ylabel="friction force on the rail [N]")
    axes[2].set(title="unloaded rig (cf. Fig. 13)", xlabel="feed velocity [m/s]",
                ylabel="friction force on the rail [N]")
    axes[1].legend(fontsize=8)
    for ax in axes:
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(out / "soleimanian2020_friction.png", dpi=110)
    plt.close(fig)
    lines.append("![Mixed-EHL friction: the Hess and Soom test and the unloaded rig's friction "
                 "against time and feed velocity (cf. Figs. 11-13)]"
                 "(figures/soleimanian2020_friction.png)")
    fig, axes = plt.subplots(1, 2, figsize=(11, 3.8))
    for ax, name, title in ((axes[0], "soleimanian2020_unloaded", "unloaded (cf. Fig. 14)"),
                            (axes[1], "soleimanian2020_9000N_3000Hz", "9000 N, 3000 Hz (cf. Fig. 19b)")):
        for r in readings:
            c = steady(runs[r.name, name])
            f, amplitude = spectrum(c["time"], c["Carriage.y"])
            keep = (f > 0) & (f < 20000)
            ax.loglog(f[keep], 1e9 * amplitude[keep], lw=0.7, label=f"'{r.name}'")
        ax.axvline(5.0, color="grey", ls=":")
        ax.axvline(paper.PAPER_NATURAL_FREQUENCY, color="grey", ls="--")
        ax.set(title=f"displacement spectrum, {title}", xlabel="frequency [Hz]",
               ylabel="displacement amplitude [nm]")
        ax.grid(alpha=0.3, which="both")
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "soleimanian2020_spectra.png", dpi=110)
    plt.close(fig)
    lines.append("![Spectra of the rail's displacement, the feed (5 Hz, dotted) and the published "
                 "natural frequency (dashed) marked (cf. Figs. 14, 19b)]"
                 "(figures/soleimanian2020_spectra.png)")
    fig, axes = plt.subplots(2, 2, figsize=(11, 6.5), sharex="col")
    for col, (key, title) in enumerate((("unloaded", "unloaded, mean upper load (cf. Fig. 33)"),
                                        ("loaded", "9000 N, 9000 Hz, largest upper load "
                                                   "(cf. Fig. 35)"))):
        for r in readings:
            e = solutions[key][r.name]
            axes[0][col].plot(1e6 * e["x"], e["p"] / 1e9, lw=0.9, label=f"'{r.name}'")
            axes[1][col].plot(1e6 * e["x"], 1e9 * e["h"], lw=0.9)
        central = max(solutions[key][r.name]["h_c"] for r in readings)
        axes[0][col].set(title=title, ylabel="pressure [GPa]", xlim=(-150.0, 100.0))
        axes[1][col].set(xlabel="distance from the contact centre [um]", ylabel="film [nm]",
                         ylim=(0.0, 4e9 * central))
        for ax in axes[:, col]:
            ax.grid(alpha=0.3)
    axes[0][0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "soleimanian2020_pressures.png", dpi=110)
    plt.close(fig)
    lines.append("![Explicit (steady, numerical) EHL pressure and film of the upper roller "
                 "(cf. Figs. 33, 35)](figures/soleimanian2020_pressures.png)")
    return lines


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--out", default=str(ROOT / "docs" / "soleimanian2020-reproduced.md"))
    args = parser.parse_args(argv)
    began = time.perf_counter()
    fmus = build.ensure(Path(tempfile.mkdtemp()) / "fmus")
    readings = paper.readings()
    jobs = [(r, n, fmus) for r in readings for n in names()]
    with Pool(args.jobs) as pool:
        runs = {(r, n): cols for r, n, cols in pool.imap_unordered(one_run, jobs)}
    solutions: dict = {}
    rows = statements(readings, runs, solutions)
    count = {r.name: sum(row["agree"][r.name] for row in rows) for r in readings}
    default = max(readings, key=lambda r: count[r.name])
    out = Path(args.out)
    lines = ["# Soleimanian et al. (2020) reproduced", "",
             f"Wall time {(time.perf_counter() - began) / 60:.1f} min.", "",
             "Every number and trend the paper states about its own results that the model "
             "computes, under each reading of the published preload (9200 N, Table 2, shared "
             "over what the paper does not say; analysis/soleimanian2020.py). Each reading's rail "
             "mass puts the unloaded natural frequency at the published 6590 Hz. All runs are "
             "the shipped scenarios through the co-simulation master and the FMUs, one 0.2 s "
             "feed cycle each, the first 10 ms left out.", "",
             "| reading | preload shared by | Q0 per roller [N] | Hertz peak pressure at Q0 "
             "[GPa] | F0 of the contact FMUs [N] | rail mass [kg] | statements reproduced |",
             "|---|---|---|---|---|---|---|"]
    for r in readings:
        lines.append(f"| `{r.name}` | {80 // paper.SHARES[r.name]} rollers | "
                     f"{r.preload_per_roller:.0f} | "
                     f"{roller(r.preload_per_roller, paper.RIG_SPEED).hertz_pressure / 1e9:.2f} | "
                     f"{r.preload:.0f} | {r.mass:.3f} | {count[r.name]} / {len(rows)} |")
    shipped = next((r.name for r in readings
                    if abs(r.preload - four_rows.Guideway().preload) < 1e-9), "none of them")
    lines += ["", f"Most statements reproduced: `{default.name}`. The FMUs' defaults and the "
              f"shipped scenarios follow `{shipped}`; any reading is a parameter set of a "
              "scenario (`Reading.parameters()`: the contact's `preload`, the carriage's "
              "`mass`).", "",
              "## Statements", "",
              "| id | source | the paper says | " + " | ".join(f"`{r.name}`" for r in readings)
              + " | how we compute it |", "|---|---|---|" + "---|" * len(readings) + "---|"]
    for row in rows:
        cells = [f"{row['values'][r.name]} ({'agrees' if row['agree'][r.name] else 'disagrees'})"
                 for r in readings]
        lines.append(f"| {row['id']} | {row['source']} | {row['said']} | " + " | ".join(cells)
                     + f" | {row['why']} |")
    lines += ["", "## Why the disagreements", ""]
    for row in rows:
        against = [r.name for r in readings if not row["agree"][r.name]]
        if against:
            lines.append(f"- **{row['id']}** (disagrees under {', '.join(against)}): "
                         f"{CAUSES.get(row['id'], 'no cause stated yet')}")
    lines += ["", "Plotted, not compared: the friction of Figs. 11-13 (the paper sets its model "
              "beside Hess and Soom's and its own measurements, which exist only as figures; "
              "ours are in the last figure). Not compared: the EHL solver against Masjedi and "
              "Khonsari (Figs. 9-10: docs/ehl-validation.md); the odd harmonics of the rig's "
              "measured response (Fig. 8: a measurement).", "", "## Figures", ""]
    lines += figures(readings, runs, solutions, out.parent / "figures")
    text = "\n".join(lines) + "\n"
    print(text)
    pages.write(out, text, f"python benchmarks/soleimanian2020_reproduced.py --jobs {args.jobs}",
                __file__, (f"{pages.SCENARIOS}/soleimanian2020_*.toml",))


if __name__ == "__main__":
    main()
