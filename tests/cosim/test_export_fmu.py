"""The packed FMU (export-fmu): a scenario's system in one FMU, run in our master, fmpy and
libcosim next to HarmonicForce, an FMU written in C (harmonic_force/, compiled here with the
system's C compiler; the tests that need it are skipped without one).

The independent check of the packing is the unpacked system: the same FMUs, the same C FMU
wired to the same input, run by our master. With the communication points on the inner steps
the packed FMU makes the same FMI calls with the same values in the same order, so the two
agree bit for bit (assert_array_equal, no tolerance).
"""
from __future__ import annotations

import math
import re
import shutil
import subprocess
import sys
import tempfile
import tomllib
import zipfile
from pathlib import Path

import fmpy
import numpy as np
import pytest
import tomli_w
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Slave
from fmpy.ssp.simulation import simulate_ssp  # fmpy.ssp.simulate parses sys.argv on import
from fmpy.validation import validate_fmu

from guideway_fmu import cli, scenarios
from guideway_fmu.cosim import master, ssp, system
from guideway_fmu.cosim.export_fmu import export_fmu

SCENARIO = "soleimanian2020_9000N_4500Hz"
STEP = 4e-6  # s, the scenario's macro step
STOP = 400 * STEP  # s
SOURCE = Path(__file__).with_name("harmonic_force")
COMPILER = shutil.which("cc") or shutil.which("gcc")
needs_cc = pytest.mark.skipif(COMPILER is None, reason="no C compiler (cc or gcc) for HarmonicForce")
WATCHED = ["Carriage.y", "Carriage.y_dot", "Contact.F_contact", "Contact.F_upper", "Contact.h_upper"]


def compile_harmonic_force(folder: Path) -> Path:
    """HarmonicForce.fmu in ``folder``: harmonic_force.c compiled against fmpy's FMI headers."""
    library = folder / "HarmonicForce.so"
    subprocess.run([COMPILER, "-shared", "-fPIC", "-O2", "-I", str(Path(fmpy.__file__).parent / "c-code"),
                    str(SOURCE / "harmonic_force.c"), "-o", str(library), "-lm"], check=True)
    fmu = folder / "HarmonicForce.fmu"
    with zipfile.ZipFile(fmu, "w") as zf:
        zf.write(SOURCE / "modelDescription.xml", "modelDescription.xml")
        zf.write(SOURCE / "harmonic_force.c", "sources/harmonic_force.c")
        zf.write(library, "binaries/linux64/HarmonicForce.so")
    return fmu


@pytest.fixture(scope="module")
def shipped(fmu_dir):
    """The shipped scenario SCENARIO, loaded with the session's FMUs."""
    return system.load(scenarios.find(SCENARIO), fmu_dir)


@pytest.fixture(scope="module")
def packed(shipped, tmp_path_factory):
    return export_fmu(shipped, tmp_path_factory.mktemp("packed") / "Loaded.fmu")


@pytest.fixture(scope="module")
def force(tmp_path_factory):  # the tests that use it are marked needs_cc
    return compile_harmonic_force(tmp_path_factory.mktemp("harmonic_force"))


def unpacked_with_force(shipped, force: Path, folder: Path) -> system.System:
    """``shipped`` with HarmonicForce's F on Carriage.F_ext, run for STOP."""
    system.dump(shipped, folder / "unpacked.toml")
    data = tomllib.loads((folder / "unpacked.toml").read_text())
    data["components"]["Force"] = {"fmu": str(force)}
    data["connections"].append({"from": "Force.F", "to": "Carriage.F_ext"})
    data["record"] = {"variables": WATCHED}
    data["experiment"]["stop"] = STOP
    (folder / "unpacked.toml").write_text(tomli_w.dumps(data))
    return system.load(folder / "unpacked.toml")


def packed_with_force(packed: Path, force: Path, algorithm: str = "gauss-seidel") -> system.System:
    """HarmonicForce's F on the packed FMU's Carriage.F_ext, communicating every STEP for STOP."""
    b = system.Builder("packed").experiment(stop=STOP, step=STEP, algorithm=algorithm)
    b.component("Force", force).component("Rig", packed).connect("Force.F", "Rig.Carriage.F_ext")
    return b.record([f"Rig.{w}" for w in WATCHED]).system()


def test_the_packed_fmu_validates_clean_and_declares_the_systems_free_inputs_outputs_and_parameters(
        packed, shipped):
    assert validate_fmu(str(packed)) == []
    md = fmpy.read_model_description(str(packed))
    by = {v.name: v for v in md.modelVariables}
    assert sorted(n for n, v in by.items() if v.causality == "input") == ["Carriage.F_ext", "Feed.u_cmd"]
    outputs = [f"{i}.{n}" for i, vs in shipped.variables.items() for n, v in vs.items()
               if v.causality == "output"]
    assert [n for n, v in by.items() if v.causality == "output"] == outputs
    assert float(by["Carriage.load_amplitude"].start) == 9000.0  # the scenario's value
    assert float(by["Carriage.mass"].start) == float(shipped.variables["Carriage"]["mass"].start)
    assert by["Feed.profile"].type == "String" and by["Feed.profile"].start == "biharmonic"
    for name in outputs:
        inst, var = name.split(".", 1)
        inner = shipped.variables[inst][var]
        assert (by[name].unit, by[name].description) == (inner.unit, inner.description)
    assert md.coSimulation.modelIdentifier == SCENARIO
    exp = md.defaultExperiment
    assert (float(exp.stopTime), float(exp.stepSize)) == (shipped.experiment.stop, STEP)


@needs_cc
def test_the_c_fmu_validates_clean(force):
    assert validate_fmu(str(force)) == []


@needs_cc
def test_packed_equals_unpacked_bit_for_bit_in_our_master_next_to_the_c_fmu(
        shipped, packed, force, tmp_path):
    unpacked = master.simulate(unpacked_with_force(shipped, force, tmp_path)).recording
    result = master.simulate(packed_with_force(packed, force))
    assert result.steps == 400
    for name in WATCHED:
        np.testing.assert_array_equal(result.recording.columns[f"Rig.{name}"], unpacked.columns[name])
    assert np.ptp(unpacked.columns["Contact.F_upper"]) > 500.0  # the loads do oscillate


def test_a_communication_step_of_ten_inner_steps_gives_the_same_trajectory(shipped, packed):
    """Inputs constant: the inner master takes the same steps whatever the communication step;
    the FMUs' time differs in the last bits (t + h summed inside or outside), hence rtol 1e-12."""
    runs = [fmpy.simulate_fmu(str(packed), stop_time=STOP, step_size=h, output_interval=h,
                              output=WATCHED, start_values={"Carriage.F_ext": 500.0})
            for h in (STEP, 10 * STEP)]  # fmpy communicates every output_interval
    assert len(runs[0]) == 401 and len(runs[1]) == 41
    for name in WATCHED:
        np.testing.assert_allclose(runs[1][name], runs[0][name][::10], rtol=1e-12,
                                   atol=1e-12 * np.abs(runs[0][name]).max())


def test_a_communication_step_of_half_an_inner_step_halves_the_inner_steps(packed):
    """The inner master ends its steps at the communication points: at STEP / 2 it takes steps
    of STEP / 2, a run as accurate as at STEP (against each other: 1e-3 of the load's range,
    where the stabilised coupling's own error at STEP is 2e-5 of it, docs/export-fmu.md)."""
    runs = [fmpy.simulate_fmu(str(packed), stop_time=STOP, step_size=h, output_interval=h,
                              output=["Contact.F_upper"]) for h in (STEP, STEP / 2)]
    assert len(runs[1]) == 2 * len(runs[0]) - 1 == 801  # fmpy communicates every output_interval
    load, halved = runs[0]["Contact.F_upper"], runs[1]["Contact.F_upper"][::2]
    assert not np.array_equal(halved, load)
    np.testing.assert_allclose(halved, load, atol=1e-3 * np.ptp(load))


@needs_cc
def test_libcosim_and_fmpy_run_the_packed_fmu_next_to_the_c_fmu_as_our_jacobi_master_does(
        packed, force, tmp_path):
    """Through an SSP package of [HarmonicForce, packed FMU]: libcosim to round-off (its clock
    counts integer ns, the FMUs see t off by ~1e-19 s), fmpy to round-off one step later (its
    first step sees 0.0 on every connected input: the force is 0 at t = 0 anyway)."""
    outer = packed_with_force(packed, force, algorithm="jacobi")
    ours = master.simulate(outer).recording
    package = ssp.export_ssp(outer, tmp_path / "outer.ssp")
    names = [f"Rig.{w}" for w in WATCHED]
    _, libcosim = ssp.run_libcosim(package, names, 400)
    rows = simulate_ssp(str(package), start_time=0.0, stop_time=STOP, step_size=STEP)
    for name in names:
        scale = np.abs(ours.columns[name]).max()
        np.testing.assert_allclose(libcosim[name], ours.columns[name], rtol=1e-11, atol=1e-11 * scale)
        np.testing.assert_allclose(rows[name][:400], ours.columns[name][1:], rtol=1e-11,
                                   atol=1e-11 * scale)


def test_a_non_finite_input_a_bad_parameter_and_a_step_from_elsewhere_discard_with_a_message(
        packed, tmp_path, capfd):
    md = fmpy.read_model_description(str(packed))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    fmpy.extract(str(packed), str(tmp_path))
    for name, value, when in (("Carriage.F_ext", math.nan, "step"), ("Carriage.mass", -1.0, "init"),
                              ("a step from t = 0.001 s", 0.001, "time")):
        fmu = FMU2Slave(guid=md.guid, unzipDirectory=str(tmp_path),
                        modelIdentifier=md.coSimulation.modelIdentifier, instanceName="rig")
        fmu.instantiate()
        fmu.setupExperiment(startTime=0.0, stopTime=STOP)
        fmu.enterInitializationMode()
        if when == "init":
            fmu.setReal([vr[name]], [value])
        fmu.exitInitializationMode()
        if when == "step":
            fmu.setReal([vr[name]], [value])
        with pytest.raises(FMICallException) as failed:
            fmu.doStep(value if when == "time" else 0.0, STEP)
        assert failed.value.status == 2  # fmi2Discard
        fmu.terminate()
        fmu.freeInstance()
        assert name in capfd.readouterr().err


@pytest.mark.parametrize("terminate", [True, False])
def test_inner_fmus_are_extracted_at_instantiation_and_removed_at_terminate_or_free(
        packed, tmp_path, monkeypatch, terminate):
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path / "tmp"))
    (tmp_path / "tmp").mkdir()
    md = fmpy.read_model_description(str(packed))
    fmpy.extract(str(packed), str(tmp_path / "fmu"))
    fmu = FMU2Slave(guid=md.guid, unzipDirectory=str(tmp_path / "fmu"),
                    modelIdentifier=md.coSimulation.modelIdentifier, instanceName="rig")
    fmu.instantiate()
    assert len(list((tmp_path / "tmp").glob("guideway-fmu-*"))) == 3
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    fmu.doStep(0.0, STEP)
    if terminate:
        fmu.terminate()
        assert list((tmp_path / "tmp").glob("guideway-fmu-*")) == []
    fmu.freeInstance()
    assert list((tmp_path / "tmp").glob("guideway-fmu-*")) == []


@pytest.mark.parametrize("out, message", [
    ("loaded.zip", "the name of an FMU file ends in .fmu"),
    ("VerticalDynamics.fmu", "it is Carriage's FMU, which the FMU is made from"),
    ("missing/loaded.fmu", "folder .*missing does not exist"),
])
def test_export_fmu_command_refuses_bad_output_paths_with_exit_2(fmu_dir, out, message, capsys):
    before = (fmu_dir / "VerticalDynamics.fmu").read_bytes()
    assert cli.main(["export-fmu", SCENARIO, str(fmu_dir / out), "--fmus", str(fmu_dir)]) == 2
    assert re.search(message, capsys.readouterr().err)
    assert (fmu_dir / "VerticalDynamics.fmu").read_bytes() == before


def test_export_fmu_command_names_an_unknown_scenario(tmp_path, capsys):
    assert cli.main(["export-fmu", "no_such_scenario", str(tmp_path / "x.fmu")]) == 2
    assert "scenario 'no_such_scenario' is neither a file nor a shipped scenario" in capsys.readouterr().err


@needs_cc
@pytest.mark.slow
def test_the_packed_fmu_exits_cleanly_in_a_c_host_and_agrees_with_fmpy(packed, tmp_path):
    """The inner pythonfmu FMUs re-enter the interpreter through ctypes from the outer FMU's
    Python: in a C host (fmu_build/c_host.c) as in Python, 3 runs, each exit status 0."""
    from guideway_fmu.fmu_build import host_env
    environment = host_env.host_environment()
    executable = host_env.compile_c_host(tmp_path)
    runs = [host_env.run_in_c_host(executable, packed, environment, work_dir=tmp_path, steps=10)
            for _ in range(3)]
    assert [r.status for r in runs] == [0, 0, 0], runs[0].stderr[-500:]
    ref = fmpy.simulate_fmu(str(packed), stop_time=10 * STEP, step_size=STEP, output=WATCHED)
    for name in WATCHED:
        assert runs[0].outputs[name] == pytest.approx(ref[name][-1], rel=1e-12, abs=1e-30)


@pytest.mark.slow
def test_a_python_host_running_the_packed_fmu_exits_with_status_0(packed):
    script = ("import fmpy\nfor _ in range(5):\n"
              f"    fmpy.simulate_fmu({str(packed)!r}, stop_time={10 * STEP!r}, step_size={STEP!r})\n")
    runs = [subprocess.run([sys.executable, "-c", script], capture_output=True, text=True)
            for _ in range(3)]
    assert [r.returncode for r in runs] == [0, 0, 0], runs[0].stderr[-500:]


def test_export_fmu_command_writes_an_fmu_that_validates(fmu_dir, tmp_path, capsys):
    out = tmp_path / "Unloaded.fmu"
    assert cli.main(["export-fmu", "soleimanian2020_unloaded", str(out), "--fmus", str(fmu_dir),
                     "--stop", "0.01"]) == 0
    assert capsys.readouterr().out.strip() == str(out)
    assert validate_fmu(str(out)) == []
    md = fmpy.read_model_description(str(out))
    assert float(md.defaultExperiment.stopTime) == 0.01
    assert "Friction.F_friction" in {v.name for v in md.modelVariables if v.causality == "output"}


def test_an_fmu_stepped_before_its_inner_system_initialised_discards_with_a_message(packed, tmp_path,
                                                                                    capfd):
    md = fmpy.read_model_description(str(packed))
    fmpy.extract(str(packed), str(tmp_path))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    fmu = FMU2Slave(guid=md.guid, unzipDirectory=str(tmp_path),
                    modelIdentifier=md.coSimulation.modelIdentifier, instanceName="rig")
    fmu.instantiate()
    fmu.setupExperiment(startTime=0.0, stopTime=1e-7)  # shorter than the scenario's step
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    with pytest.raises(FMICallException):
        fmu.doStep(0.0, 1e-7)
    assert fmu.getReal([vr["Carriage.y"]]) == [0.0]  # outputs stay readable
    fmu.terminate()
    fmu.freeInstance()
    err = capfd.readouterr().err
    assert "[experiment] key 'step'" in err and "is not initialised" in err


def test_two_packed_fmus_and_two_instances_of_one_run_side_by_side_as_each_alone(
        packed, fmu_dir, tmp_path):
    """Module names are process-wide: the packed FMUs of two scenarios, one of them twice, in
    one run of our master give each instance's solo run bit for bit."""
    unloaded = system.load(scenarios.find("soleimanian2020_unloaded"), fmu_dir)
    other = export_fmu(unloaded, tmp_path / "Unloaded.fmu")
    watched = ["Carriage.y", "Contact.F_upper"]

    def run(instances):
        b = system.Builder("side_by_side").experiment(stop=100 * STEP, step=STEP)
        for name, fmu in instances.items():
            b.component(name, fmu)
        return master.simulate(b.record([f"{n}.{w}" for n in instances for w in watched])
                               .system()).recording.columns

    together = run({"A": packed, "B": other, "C": packed})
    for name, fmu in (("A", packed), ("B", other), ("C", packed)):
        alone = run({name: fmu})
        for w in watched:
            np.testing.assert_array_equal(together[f"{name}.{w}"], alone[f"{name}.{w}"])
    assert not np.array_equal(together["A.Contact.F_upper"], together["B.Contact.F_upper"])


def test_parameters_set_on_the_packed_fmu_reach_its_inner_fmus(shipped, packed):
    """A Real and a String parameter changed on the packed FMU: the run equals the unpacked
    scenario with the same changes, bit for bit."""
    changes = {"Carriage": {"load_amplitude": 3000.0}, "Feed": {"profile": "constant"}}
    unpacked = master.simulate(shipped.with_changes(parameters=changes, stop=100 * STEP))
    b = system.Builder("changed").experiment(stop=100 * STEP, step=STEP)
    b.component("Rig", packed, **{f"{i}.{k}": v for i, ps in changes.items() for k, v in ps.items()})
    result = master.simulate(b.record([f"Rig.{w}" for w in WATCHED]).system())
    for name in WATCHED:
        np.testing.assert_array_equal(result.recording.columns[f"Rig.{name}"],
                                      unpacked.recording.columns[name])
    assert result.parameters["Rig"]["Feed.profile"] == "constant"


def test_the_packed_fmu_gets_and_sets_its_state_as_its_inner_fmus_do(packed, tmp_path):
    """Steps repeated from a saved state give the same outputs bit for bit; the state, freed,
    frees the inner ones (the instance then still steps and terminates)."""
    md = fmpy.read_model_description(str(packed))
    assert md.coSimulation.canGetAndSetFMUstate
    vr = [v.valueReference for v in md.modelVariables if v.name in WATCHED]
    fmpy.extract(str(packed), str(tmp_path))
    fmu = FMU2Slave(guid=md.guid, unzipDirectory=str(tmp_path),
                    modelIdentifier=md.coSimulation.modelIdentifier, instanceName="rig")
    fmu.instantiate()
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()

    def steps(t0, n):
        for k in range(n):
            fmu.doStep(t0 + k * STEP, STEP)
        return fmu.getReal(vr)

    steps(0.0, 10)
    state = fmu.getFMUstate()
    first = steps(10 * STEP, 10)
    assert steps(20 * STEP, 5) != first  # the system moves on
    fmu.setFMUstate(state)
    assert steps(10 * STEP, 10) == first
    fmu.freeFMUstate(state)
    steps(20 * STEP, 5)
    fmu.terminate()
    fmu.freeInstance()


def test_a_scenario_exports_again_after_its_packed_fmu_ran_in_this_process(shipped, packed,
                                                                          tmp_path):
    """The packed FMU's modules (same code hash) are loaded here by the tests before; the build
    must import its own copy, not those (pythonfmu's builder found no slave class then)."""
    fmpy.simulate_fmu(str(packed), stop_time=STEP, step_size=STEP)
    again = export_fmu(shipped, tmp_path / packed.name)  # the name is in its scenario's header
    assert validate_fmu(str(again)) == []
    with zipfile.ZipFile(packed) as a, zipfile.ZipFile(again) as b:
        assert sorted(a.namelist()) == sorted(b.namelist())  # the same package name: same code
