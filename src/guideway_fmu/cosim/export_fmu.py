"""Pack a scenario's connected system into one FMI 2.0 co-simulation FMU (``export-fmu``).

The FMU is built by the components' build (fmu_build/build.py ``pack``) from the slave class
:class:`~.packed_fmu.PackedSystem`, whose package carries the scenario as TOML and its FMUs
(packed_fmu.py says what the FMU's variables are and how it steps).
"""
from __future__ import annotations

import shutil
import tempfile
from pathlib import Path

from fmpy import read_model_description

from ..fmu_build import build
from .packed_fmu import DATA, SCENARIO, PackedSystem
from .ssp import packed_files
from .system import System, dump


def export_fmu(system: System, out: str | Path) -> Path:
    """Write ``system`` as one FMU at ``out``; returns its path. Raises ValueError if ``out``
    does not end in ``.fmu``, and what ssp.packed_files raises for the output and the FMUs."""
    out = Path(out)
    if out.suffix != ".fmu":
        raise ValueError(f"cannot write {out}: the name of an FMU file ends in .fmu")
    sources = packed_files(system, out, "FMU")
    with tempfile.TemporaryDirectory(prefix="guideway_fmu_pack_") as tmp:
        tmp = Path(tmp)
        for name, path in sources.items():
            shutil.copy2(path, tmp / name)
        # the FMUs beside the scenario: system.dump writes their paths as file names
        inner = system.with_changes(fmus={n: tmp / c.fmu.name for n, c in system.components.items()})
        dump(inner, tmp / SCENARIO, f"The system packed into {out.name}; its FMUs beside this file")
        data = {f"{DATA}/{name}": tmp / name for name in [*sources, SCENARIO]}
        # its state is its inner instances' states: it can get and set it if they all can
        state = all(read_model_description(str(path)).coSimulation.canGetAndSetFMUstate
                    for path in sources.values())
        return build.pack([(PackedSystem, out)], data, handle_state=state)[0]
