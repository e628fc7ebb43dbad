"""The probe FMU `Faulty` shared by the tests of failing, hanging and interrupted runs."""
from __future__ import annotations

import pytest
from pythonfmu.builder import FmuBuilder

from guideway_fmu.components import exit_patch

FAULTY = '''
import time

from pythonfmu import Fmi2Causality, Fmi2Slave, Fmi2Variability, Real, String


class Faulty(Fmi2Slave):
    """x = t, with the fault the parameter `fault` names (any other value: none):
    "raise": the doStep that starts at 5 ms raises;
    "get": after that doStep, reading x raises;
    "nan": the doStep that ends at 5 ms outputs NaN with status OK;
    "slow": every doStep takes 10 ms of wall time;
    "hang": the doStep that starts at 5 ms never returns."""

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.x, self.fault, self.late = 0.0, "raise", False
        self.register_variable(Real("x", causality=Fmi2Causality.output, getter=self._read_x))
        self.register_variable(String("fault", causality=Fmi2Causality.parameter,
                                      variability=Fmi2Variability.tunable))

    def _read_x(self):
        if self.fault == "get" and self.late:
            raise RuntimeError("the faulty model's output broke at 5 ms")
        return self.x

    def do_step(self, current_time, step_size):
        end = current_time + step_size
        self.late = current_time >= 0.005 - 1e-12
        if self.fault == "raise" and self.late:
            raise RuntimeError("the faulty model broke at 5 ms")
        while self.fault == "hang" and self.late:
            time.sleep(1.0)
        if self.fault == "slow":
            time.sleep(0.01)
        self.x = float("nan") if self.fault == "nan" and end >= 0.005 - 1e-12 else end
        return True
'''


@pytest.fixture(scope="session")
def faulty(tmp_path_factory):
    """Faulty.fmu, built once per test session."""
    folder = tmp_path_factory.mktemp("faulty")
    (folder / "faulty.py").write_text(FAULTY)
    # a plain pythonfmu FMU with its exit-time defect patched: the test process exits cleanly
    return exit_patch.patch_fmu(FmuBuilder.build_FMU(folder / "faulty.py",
                                                     dest=folder / "Faulty.fmu"))
