"""Shared fixtures of the test suite."""
import os

# One thread per process for the numerical libraries, set before numpy loads them: the tests run
# on pytest-xdist workers, one per core, and the libraries' own threads would only contend with
# the other worker's (the fast loop took twice as long with them). Child processes inherit it.
for _variable in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_variable, "1")

import numpy as np  # noqa: E402
import pytest  # noqa: E402
from pythonfmu.builder import FmuBuilder  # noqa: E402

from guideway_fmu.fmu_build import exit_patch  # noqa: E402


@pytest.fixture(scope="session", autouse=True)
def fmu_cache(tmp_path_factory):
    """The FMU cache of this test session (GUIDEWAY_FMU_CACHE, inherited by the commands the
    tests start), never the user's: one folder shared by the xdist workers of one run (the
    parent of their temporary folders), so one of them builds each FMU and the other waits."""
    from guideway_fmu.fmu_build import cache

    base = tmp_path_factory.getbasetemp()
    folder = (base.parent if os.environ.get("PYTEST_XDIST_WORKER") else base) / "fmu-cache"
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv(cache.ENVIRONMENT, str(folder))
        yield folder


@pytest.fixture(scope="session")
def fmu_dir(fmu_cache):
    """All FMUs, extensions included (and their README.md): the session cache's folder, built
    once per test run. Shared: a test that changes an FMU works on a copy."""
    from guideway_fmu.fmu_build import cache

    return cache.folder()


@pytest.fixture(scope="session")
def cosine_blend_strokes():
    """Strokes reversing through half-cosine blends (v = speed cos(pi tau / blend)), whose
    acceleration is continuous with a corner at each end of a blend: 4000 samples of 4.4 ms,
    0.1 m/s, blends of 0.16 s (36 samples), cruises of 0.6 s. (time [s], position [m],
    velocity [m/s], acceleration [m/s^2], corner instants [s])."""
    n, step, speed, blend, cruise = 4000, 0.0044, 0.1, 0.16, 0.6
    period = 2 * (blend + cruise)
    t = np.arange(n) * step
    fine = np.arange(0.0, t[-1] + 1e-4, 1e-5)
    phase = np.mod(fine, period)

    def profile(p):
        tau = np.mod(p, period / 2)
        sign = np.where(p < period / 2, 1.0, -1.0)
        inside = tau < blend
        v = sign * np.where(inside, speed * np.cos(np.pi * tau / blend), -speed)
        a = sign * np.where(inside, -speed * np.pi / blend * np.sin(np.pi * tau / blend), 0.0)
        return v, a

    v_fine, _ = profile(phase)
    x_fine = np.concatenate([[0.0], np.cumsum(0.5 * (v_fine[1:] + v_fine[:-1]) * np.diff(fine))])
    v, a = profile(np.mod(t, period))
    corners = np.sort(np.concatenate([np.arange(0.0, t[-1], period / 2),
                                      np.arange(blend, t[-1], period / 2)]))
    return t, np.interp(t, fine, x_fine), v, a, corners


# The probe FMU `Faulty`, shared by the tests of failing, hanging and interrupted runs (cosim/).
FAULTY = '''
import sys
import time

from pythonfmu import Fmi2Causality, Fmi2Slave, Fmi2Variability, Real, String


class Faulty(Fmi2Slave):
    """x = t, with the fault the parameter `fault` names (any other value: none):
    "raise": the doStep that starts at 5 ms raises;
    "get": after that doStep, reading x raises;
    "nan": the doStep that ends at 5 ms outputs NaN with status OK;
    "slow": every doStep takes 10 ms of wall time;
    "hang": the doStep that starts at 5 ms never returns;
    "hang_init": exitInitializationMode never returns;
    "terminate": terminate raises.
    A hang begins with the line "Faulty: hanging" on stderr."""

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

    def exit_initialization_mode(self):
        self._hang("hang_init")

    def terminate(self):
        if self.fault == "terminate":
            raise RuntimeError("the faulty model could not terminate")

    def _hang(self, fault):
        if self.fault == fault:
            print("Faulty: hanging", file=sys.stderr, flush=True)
        while self.fault == fault:
            time.sleep(1.0)

    def do_step(self, current_time, step_size):
        end = current_time + step_size
        self.late = current_time >= 0.005 - 1e-12
        if self.fault == "raise" and self.late:
            raise RuntimeError("the faulty model broke at 5 ms")
        if self.late:
            self._hang("hang")
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
