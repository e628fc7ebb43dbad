"""Run a scenario through guideway_fmu's Python API: load, simulate, write CSV and plots.

The same as `guideway-fmu run`, spelled out; compare drive_with_fmpy.py for what the master does.

    python run_scenario.py                                  # 9000 N at 4500 Hz, 0.01 s
    python run_scenario.py soleimanian2020_unloaded --stop 0.05     # a shipped scenario or a file
"""
import argparse
from pathlib import Path

from guideway_fmu import scenarios
from guideway_fmu.cosim import master, plots, system
from guideway_fmu.cosim.interrupts import exit_without_finalising

HERE = Path(__file__).resolve().parent

p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
p.add_argument("scenario", nargs="?", default="soleimanian2020_9000N_4500Hz")
p.add_argument("--stop", type=float, default=0.01, help="simulated time [s] (default 0.01)")
p.add_argument("--out", type=Path, default=HERE.parent / "out/run_scenario", help="output folder")
p.add_argument("--fmus", type=Path, default=HERE.parent / "fmus",
               help="take the FMUs from this folder by file name (default: the repository's fmus/)")
args = p.parse_args()

s = system.load(scenarios.find(args.scenario), args.fmus)  # checked against every FMU's modelDescription
s = s.with_changes(stop=args.stop)  # also step=... [s], algorithm="gauss-seidel", ...
args.out.mkdir(parents=True, exist_ok=True)
csv = args.out / "results.csv"  # written as the run goes, + results.units.json
result = master.simulate(s, progress=True, results=csv)  # raises master.SimulationError if an FMU fails

# The scenario's [plots] table: lists of signals per kind, plus skip [s], f_max [Hz], window [s]
options = {k: s.plots[k] for k in ("skip", "f_max", "window") if k in s.plots}
options["skip"] = min(options.get("skip", 0.0), args.stop / 2)  # keep a spectrum for short runs
kinds = {k: s.plots[k] for k in ("time", "spectrum", "film", "envelope") if s.plots.get(k)}
pngs = plots.plot_all(result.recording, kinds, args.out, **options)

summary = result.summary()
print(f"{summary['scenario']}: {summary['steps']} steps ({summary['rejected']} rejected), "
      f"wall {summary['wall_time_s']:.2f} s, of which FMI calls {summary['fmi_call_time_s']:.2f} s")
f_upper = result.recording.columns.get("Contact.F_upper")  # N, load of one upper roller
if f_upper is not None:
    print(f"Contact.F_upper: min {f_upper.min():.2f} N, max {f_upper.max():.2f} N")
print("wrote", csv, *(png.name for png in pngs))
exit_without_finalising(0)  # FMUs loaded: see guideway_fmu.cosim.interrupts
