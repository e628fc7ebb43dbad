"""The wear model's figures for the LG20 of Zhang, Wang and Jiang (Table 1), written to
docs/wear-figures.md with its plot in docs/figures/.

Under 2 kN (the load of the paper's Figs. 15-17): the wear against the running distance up to
the loss of preload, the analogues of Figs. 14-17 for 5 km, and how the wear after 5 km moves
with the parameters the paper does not state or that a user would vary (fractal dimension,
Carter's friction coefficient, tangential force, wear coefficient, load).

    python benchmarks/wear_figures.py [--out docs/wear-figures.md]
"""
from __future__ import annotations

import argparse
import dataclasses
from pathlib import Path

from guideway_fmu.analysis import wear as wa
from guideway_fmu.analysis.wear_plots import plot_figures
from guideway_fmu.physics.wear import raceway_wear

import pages

ROOT = Path(__file__).resolve().parents[1]
CASE = ROOT / "src" / "guideway_fmu" / "examples" / "ball_guides" / "zhang_wear_lg20_2kN.toml"
INPUTS = (CASE.relative_to(ROOT).as_posix(),)  # data the page is computed from (pages.py)
SENSITIVITY = (("fractal_dimension", (2.2, 2.4, 2.6, 2.8)), ("friction", (0.05, 0.1, 0.2)),
               ("tangential_ratio", (0.05, 0.2, 0.5)), ("wear_coefficient", (5e-5, 5e-4, 5e-3)))


def _distance_table(case: wa.WearCase) -> tuple[list[str], float | None]:
    """Wear against distance, to past the preload loss, at logarithmic distances."""
    run = raceway_wear.simulate(case.guide, case.load, 5e8, 3)
    lost = run.preload_lost_at
    lines = ["| distance [km] | wear depth [nm] | preload deformation [um] | preload [N] "
             "| upper ball load [N] | slider displacement [um] | added by wear [nm] |",
             "| --- | --- | --- | --- | --- | --- | --- |"]
    distances = [0.0, 1.0, 5.0, 50.0, 500.0, 5e3, 5e4, 1e5, 2e5, 5e5]
    z0 = None
    for km in distances:
        h = case.guide.advance(case.load, (0.0, 0.0), km * 1e3)
        s = case.guide.state(case.load, h)
        z0 = s["vertical_displacement"] if z0 is None else z0
        lines.append(f"| {km:g} | {1e9 * s['wear_depth']:.4g} | "
                     f"{1e6 * s['preload_deformation']:.4f} | {s['preload']:.3f} | "
                     f"{s['ball_load_upper']:.2f} | {1e6 * s['vertical_displacement']:.4f} | "
                     f"{1e9 * (s['vertical_displacement'] - z0):.4g} |")
    return lines, lost


def _sensitivity(case: wa.WearCase) -> list[str]:
    lines = ["| parameter | value | wear depth after 5 km [nm] | upper creep rate | "
             "preload lost at [km] |", "| --- | --- | --- | --- | --- |"]
    rows = [(name, v) for name, values in SENSITIVITY for v in values]
    rows += [("load [N]", v) for v in (500.0, 2000.0, 5000.0)]
    for name, value in rows:
        if name == "load [N]":
            guide, load = case.guide, value
        else:
            guide, load = dataclasses.replace(case.guide, **{name: value}), case.load
        depth = raceway_wear.simulate(guide, load, 5000.0, 2).columns["wear_depth"][-1]
        lost = raceway_wear.simulate(guide, load, 1e10, 2).preload_lost_at
        creep = wa.contact_summary(guide, load)["upper"]["creep_rate"]
        lines.append(f"| {name} | {value:g} | {1e9 * depth:.4g} | {creep:.3e} | "
                     + (f"{lost / 1e3:.4g} |" if lost is not None else "not within 1e7 km |"))
    return lines


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--out", type=Path, default=ROOT / "docs" / "wear-figures.md")
    args = p.parse_args()
    case = wa.read_case(CASE)
    figures = args.out.parent / "figures"
    figures.mkdir(parents=True, exist_ok=True)
    result = wa.analyse(case, 5000.0, 51)
    png = plot_figures(case, result, figures / "wear_lg20_2kN.png")
    table, lost = _distance_table(case)
    up = result["contact"]["upper"]
    text = [
        "# Wear of the LG20 guide: figures", "",
        "The model and the case file are in [wear.md](wear.md).", "",
        f"LG20 of the paper's Table 1 (`{CASE.relative_to(ROOT)}`) under {case.load:g} N: the "
        f"upper balls carry {up['ball_load']:.1f} N (mean Hertz pressure "
        f"{up['mean_pressure'] / 1e9:.3f} GPa), roll with the friction coefficient "
        f"{up['rolling_friction']:.4f} and creep at {up['creep_rate']:.3e}; their row wears "
        f"{up['wear_rate']:.3e} m per metre run.", "",
        "## Wear against the running distance", "", *table, "",
        f"The preload is lost at {lost / 1e3:.4g} km." if lost is not None else
        "The preload is not lost within 5e5 km.", "",
        "The wear rate falls as the upper rows' interference wears away: their balls unload "
        "towards the share of the external load alone (Fig. 15's slowing growth).", "",
        "## Analogues of Figs. 14-17 (5 km)", "", f"![wear figures](figures/{png.name})", "",
        "## Sensitivity of the wear after 5 km", "",
        "One parameter changed at a time from the case above (the tangential-force ratio "
        "replaces the rolling resistance's, about 0.1 here).", "", *_sensitivity(case), ""]
    pages.write(args.out, "\n".join(text), "python benchmarks/wear_figures.py", __file__, INPUTS)
    print(args.out)


if __name__ == "__main__":
    main()
