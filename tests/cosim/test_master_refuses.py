"""What the master cannot do with a third-party FMU is refused at the scenario check, naming the
table, the key and the FMU: String connections and records, step-size control without get/set
state, a run that is not a whole number of steps for an FMU that cannot change its step, and
Integer values outside FMI's 32-bit range. The FMU here is built in the test with pythonfmu,
declaring what it cannot do as a third party's would."""
from __future__ import annotations

import textwrap

import numpy as np
import pytest
from pythonfmu.builder import FmuBuilder

from guideway_fmu.fmu_build import exit_patch
from guideway_fmu.cosim import master, system
from support import write_file

PROBE = '''
from pythonfmu import Fmi2Causality, Fmi2Slave, Fmi2Variability, Integer, Real, String


class Probe(Fmi2Slave):
    """x = n u; a String output and input; cannot vary its step nor save its state."""

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.u, self.x, self.label, self.tag, self.n = 0.0, 0.0, "probe", "", 2
        self.register_variable(Real("u", causality=Fmi2Causality.input))
        self.register_variable(String("tag", causality=Fmi2Causality.input,
                                      variability=Fmi2Variability.discrete))
        self.register_variable(Real("x", causality=Fmi2Causality.output))
        self.register_variable(String("label", causality=Fmi2Causality.output,
                                      variability=Fmi2Variability.discrete))
        self.register_variable(Integer("n", causality=Fmi2Causality.parameter,
                                       variability=Fmi2Variability.tunable))

    def do_step(self, current_time, step_size):
        self.x = self.n * self.u
        return True
'''


@pytest.fixture(scope="module")
def probe_fmu(tmp_path_factory):
    folder = tmp_path_factory.mktemp("probe")
    script = folder / "probe.py"
    script.write_text(PROBE)
    # a plain pythonfmu FMU with its exit-time defect patched: the test process exits cleanly
    return exit_patch.patch_fmu(FmuBuilder.build_FMU(
        script, dest=folder / "Probe.fmu", canHandleVariableCommunicationStepSize=False))


def probe_scenario(tmp_path, fmu, extra="", experiment="stop = 0.01\nstep = 0.001", record='"A.x"'):
    """probe.toml in ``tmp_path``: two instances A, B of ``fmu``, A.x -> B.u (``extra``: more
    connections), the ``experiment`` table's body, A.x (``record``) recorded; its path."""
    text = textwrap.dedent(f"""\
        name = "probe"
        connections = [{{ from = "A.x", to = "B.u" }}{extra}]

        [experiment]
        {experiment}

        [components.A]
        fmu = "{fmu}"

        [components.B]
        fmu = "{fmu}"

        [record]
        variables = [{record}]
        """)
    return write_file(tmp_path, text, "probe.toml")


def test_a_probe_that_fits_runs_at_constant_steps(tmp_path, probe_fmu):
    result = master.simulate(system.load(probe_scenario(tmp_path, probe_fmu)))
    assert np.allclose(np.diff(result.recording.time), 0.001, rtol=1e-9, atol=0.0)
    assert result.recording.time[-1] == pytest.approx(0.01, rel=1e-12)


@pytest.mark.parametrize("kwargs, message", [
    ({"extra": ', { from = "A.label", to = "B.tag" }'},
     r"\[connections #2\] key 'from': A.label is a String: the master exchanges numbers only"),
    ({"record": '"A.x", "A.label"'},
     r"\[record\] key 'variables': A.label is a String: results hold numbers only"),
    ({"experiment": "stop = 0.01\nstep = 0.001\ntolerance = 0.01"},
     r"\[experiment\] key 'tolerance': .*A \(Probe.fmu\) cannot get and set its state"),
    ({"experiment": "stop = 0.0105\nstep = 0.001"},
     r"\[experiment\] key 'stop': A \(Probe.fmu\) cannot change its communication step size "
     r".* use stop = 0.01\b"),
])
def test_what_the_master_cannot_do_is_refused_naming_table_key_and_fmu(tmp_path, probe_fmu,
                                                                        kwargs, message):
    with pytest.raises(system.ScenarioError, match=message):
        system.load(probe_scenario(tmp_path, probe_fmu, **kwargs))


@pytest.mark.parametrize("value", [2**31, -2**31 - 1, 4294967316])
def test_integer_outside_fmis_32_bit_range_is_refused_not_wrapped(tmp_path, probe_fmu, value):
    path = probe_scenario(tmp_path, probe_fmu)
    path.write_text(path.read_text() + f"\n[components.A.parameters]\nn = {value}\n")
    with pytest.raises(system.ScenarioError,
                       match=rf"\[components.A.parameters\] key 'n': Integer variable cannot "
                             rf"take {value}"):
        system.load(path)
    path.write_text(path.read_text().replace(f"n = {value}", f"n = {2**31 - 1}"))
    assert system.load(path).components["A"].parameters["n"] == 2**31 - 1
