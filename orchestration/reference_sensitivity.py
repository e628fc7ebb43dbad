"""How predictable is a scenario? The monolithic reference against itself, slightly disturbed.

For each scenario, the reference (LSODA, rtol 1e-10) is solved again (a) with the body started
1e-12 m off its rest position, (b) at rtol 1e-12 and (c) at rtol 1e-9, and the RMS change of
Contact.F_upper is printed relative to its range, over the whole run and per eighth of it (a).
Where (a) grows to per cent levels the response is chaotic: no co-simulation (and no other
integrator) can follow the trajectory to 1 % over a full feed cycle, and only statistics of the
response (envelope, spectrum) are meaningful there. Where (c) reaches per cent levels, the
trajectory is that sensitive to errors of 1e-9: a co-simulation whose error exceeds 1 % there
is no worse than a good integrator one decade looser than the reference. Where all stay tiny, a
larger co-simulation error comes from the coupling itself.

    python reference_sensitivity.py                       # every shipped scenario, 0.2 s
    python reference_sensitivity.py soleimanian2020_9000N_2500Hz_dry --stop 0.1
"""
import argparse
import json
from pathlib import Path

import numpy as np

from guideway_fmu.reference import monolithic
from guideway_fmu import scenarios
from guideway_fmu.cosim import system
from guideway_fmu.cosim.interrupts import exit_without_finalising

SIGNAL = "Contact.F_upper"

p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
p.add_argument("scenarios", nargs="*", help="scenario names or TOML files (default: all shipped)")
p.add_argument("--stop", type=float, default=None, help="simulated time [s] (default: the scenario's)")
p.add_argument("--fmus", type=Path, default=Path(__file__).resolve().parents[1] / "fmus",
               help="take the FMUs from this folder by file name (default: the repository's fmus/)")
p.add_argument("--offset", type=float, default=1e-12, help="initial displacement [m] (default 1e-12)")
args = p.parse_args()


def rms_parts(a, b, scale, parts=8):
    """RMS of a - b over the whole run and over each of ``parts`` equal pieces, relative to scale."""
    pieces = np.array_split(a - b, parts)
    return (float(np.sqrt(np.mean((a - b) ** 2)) / scale),
            [float(np.sqrt(np.mean(d ** 2)) / scale) for d in pieces])


for path in map(scenarios.find, args.scenarios or scenarios.names()):
    s = system.load(path, args.fmus)
    if args.stop is not None:
        s = s.with_changes(stop=args.stop)
    exp = s.experiment
    times = np.arange(exp.start, exp.stop + 1e-12, s.record_interval or exp.step)
    base = monolithic.simulate(s, times=times).columns[SIGNAL]
    scale = float(np.ptp(base))
    changed_rtol = {f"rms_rtol_{rtol:g}": rms_parts(
        monolithic.simulate(s, times=times, rtol=rtol).columns[SIGNAL], base, scale)[0]
        for rtol in (1e-12, 1e-9)}
    body = next(n for n, c in s.components.items() if c.fmu.stem == "VerticalDynamics")
    s.components[body].parameters["y_start"] = args.offset
    moved = monolithic.simulate(s, times=times).columns[SIGNAL]
    offset_rms, offset_parts = rms_parts(moved, base, scale)
    print(json.dumps({"scenario": s.name, "signal": SIGNAL, "offset_m": args.offset,
                      "rms_offset": offset_rms, "rms_offset_per_eighth": offset_parts,
                      **changed_rtol}), flush=True)
exit_without_finalising(0)  # FMUs loaded: see guideway_fmu.cosim.interrupts
