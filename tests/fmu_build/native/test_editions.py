"""The native edition against the pythonfmu edition of the same component: the same
modelDescription, the same outputs step by step, the same named refusals, and FMU state that
repeats steps exactly. The Python edition is the reference: its physics is tested against
hand calculations and published numbers elsewhere; here every number must come out the same."""
from __future__ import annotations

import importlib.util
import math
import zipfile
from pathlib import Path

import numpy as np
import pytest
from drive import Driven, run_script
from fmpy import read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import fmi2Discard, fmi2OK
from fmpy.validation import validate_fmu
from support import capturing_callbacks

from guideway_fmu.components import registry
from guideway_fmu.fmu_build.native.build import build_native

#: the components with a native edition, and an input range [low, high] for random drives
NATIVE = {
    "HorizontalRig": {"a": (-5.0, 5.0), "F_friction": (-40.0, 40.0)},
    "FrictionCoulomb": {"F_upper": (0.0, 900.0), "F_lower": (0.0, 900.0), "u": (-0.2, 0.2)},
    "FrictionStribeck": {"F_upper": (0.0, 900.0), "F_lower": (0.0, 900.0), "u": (-0.2, 0.2)},
    "FrictionDahl": {"F_upper": (0.0, 900.0), "F_lower": (0.0, 900.0), "u": (-0.2, 0.2),
                     "x": (-3e-5, 3e-5)},
    "ContactDryHertz": {"y": (-2e-6, 2e-6), "y_dot": (-1e-3, 1e-3), "u": (-0.2, 0.2)},
    "VerticalDynamics": {"F_contact": (-5e3, 5e3), "F_ext": (-100.0, 100.0),
                         "K_contact": (0.0, 1e9), "C_contact": (0.0, 1e3)},
    "FeedKinematics": {"u_cmd": (-0.2, 0.2)},
    "ContactEHL": {"y": (-2e-6, 2e-6), "y_dot": (-1e-3, 1e-3), "u": (-0.2, 0.2)},
    **{name: {"F_upper": (0.0, 900.0), "F_lower": (0.0, 900.0), "u": (-0.2, 0.2), "x": (-0.3, 1.3)}
       for name in ("FrictionPositionDependent", "FrictionBallToBall", "FrictionPreloadLoss")},
    "MillingForce": {"u_feed": (-0.05, 0.05)},
    "BallCarriage5DOF": {"F_z": (-200.0, 200.0), "M_y": (-2.0, 2.0), "M_z": (-1.0, 1.0),
                         "u_feed": (-0.2, 0.2), "preload": (30.0, 60.0)},  # F_y, M_x: the rigid mode
    "FeedUnitErrors": {"F_x": (-2e3, 2e3), "F_y": (-2e3, 2e3), "F_z": (-6e3, 2e3),
                       "point_x": (-0.1, 0.1), "point_y": (-0.1, 0.1), "point_z": (0.0, 0.2),
                       "x_feed": (-0.05, 0.05)},
}
STEP = 1e-4  # s
#: components whose outputs come from an iterative solve: the editions' iterates round
#: differently (numpy's LAPACK against gw_solve), so their answers agree to the solve's
#: tolerance only: of each output's largest magnitude over the script (force balance to 1e-9 of
#: the load: FeedUnitErrors at every evaluation, BallCarriage5DOF at its start in equilibrium)
SOLVED = {"FeedUnitErrors": 1e-8, "BallCarriage5DOF": 1e-8}


@pytest.fixture(scope="session")
def native_dir(fmu_dir):
    """The session cache's native set (built once for the code, shared by the workers): the
    native FMUs of NATIVE. Shared: a test that changes an FMU works on a copy."""
    from guideway_fmu.fmu_build import cache
    return cache.folder("native")


def _script(name: str, steps: int, seed: int) -> list[dict]:
    rng = np.random.default_rng(seed)
    return [{k: rng.uniform(*bounds) for k, bounds in NATIVE[name].items()} for _ in range(steps)]


@pytest.mark.parametrize("name", NATIVE)
def test_native_outputs_equal_the_python_edition_step_by_step(name, native_dir, fmu_dir):
    script = _script(name, 40, seed=len(name))
    python = run_script(fmu_dir / f"{name}.fmu", {}, script, STEP)
    native = run_script(native_dir / f"{name}.fmu", {}, script, STEP)
    largest = {output: max(abs(row[output]) for row in python) for output in python[0]}
    for k, (a, b) in enumerate(zip(python, native)):
        for output in a:  # exp and tanh may differ in the last bit between numpy and libm
            close = pytest.approx(a[output], rel=1e-13, abs=SOLVED.get(name, 0.0) * largest[output]
                                  or 1e-300)
            assert b[output] == close, (k, output)


@pytest.mark.parametrize("name", NATIVE)
def test_native_model_description_declares_the_python_editions_variables(name, native_dir, fmu_dir):
    native = read_model_description(native_dir / f"{name}.fmu")
    python = read_model_description(fmu_dir / f"{name}.fmu")
    described = [(v.name, v.causality, v.variability, v.type, v.unit, v.start, v.description,
                  v.valueReference) for v in native.modelVariables]
    assert described == [(v.name, v.causality, v.variability, v.type, v.unit, v.start,
                          v.description, v.valueReference) for v in python.modelVariables]
    assert [(o.variable.name, [d.name for d in o.dependencies or []]) for o in native.outputs] == \
        [(o.variable.name, [d.name for d in o.dependencies or []]) for o in python.outputs]
    assert native.coSimulation.canGetAndSetFMUstate and native.coSimulation.canSerializeFMUstate
    assert not native.coSimulation.needsExecutionTool
    assert validate_fmu(str(native_dir / f"{name}.fmu")) == []


BAD = [("VerticalDynamics", {"mass": -1.0}, "Carriage.mass must be > 0, got -1.0"),
       ("VerticalDynamics", {"load_frequency": math.nan}, "ExternalLoad.frequency must be finite"),
       ("FrictionCoulomb", {"rollers_per_groove": 0},
        "CoulombParams.rollers_per_groove must be a positive integer, got 0"),
       ("ContactDryHertz", {"preload": -5.0}, "preload"),
       ("HorizontalRig", {"mass": math.inf}, "mass must be finite, got inf"),
       ("FrictionDahl", {"second_share": 0.5, "third_share": 0.75},
        "third_share must lie in [0.0, 0.5], got 0.75"),
       ("BallCarriage5DOF", {"mass": -0.3}, "mass must be > 0, got -0.3"),
       ("FeedUnitErrors", {"conformity": 0.45}, "conformity must be > 0.5"),
       ("FeedUnitErrors", {"balls_per_row": 50}, "the sliders would overlap")]


@pytest.mark.parametrize("name, parameters, words", BAD)
def test_bad_parameter_discards_the_step_as_terminated_naming_it_like_python(
        name, parameters, words, native_dir, fmu_dir, capfd):
    said = {}
    for edition, folder in (("native", native_dir), ("python", fmu_dir)):
        fmu = Driven(folder / f"{name}.fmu")
        try:
            fmu.start({}, {})
            assert fmu.step(0.0, STEP) == fmi2OK
            fmu.set(parameters)  # tunable: takes effect at the next step
            assert fmu.step(STEP, STEP) == fmi2Discard
            assert fmu.terminated  # no shorter step cures a bad parameter
        finally:
            fmu.close()
        said[edition] = capfd.readouterr().err
    assert words in said["native"]
    line = next(x for x in said["native"].splitlines() if words in x)
    assert line in said["python"].splitlines()  # the same sentence, word for word


@pytest.mark.parametrize("name, parameters, words", BAD[:2])
def test_bad_start_parameter_is_an_error_leaving_initialisation(name, parameters, words,
                                                                native_dir, capfd):
    fmu = Driven(native_dir / f"{name}.fmu")
    fmu.set(parameters)
    fmu.slave.setupExperiment(startTime=0.0)
    fmu.slave.enterInitializationMode()
    with pytest.raises(FMICallException) as raised:
        fmu.slave.exitInitializationMode()
    assert raised.value.status == 3  # fmi2Error, as the Python edition with error_patch
    fmu.slave.freeInstance()  # after fmi2Error FMI allows little else
    assert words in capfd.readouterr().err


def test_bad_input_discards_naming_the_input_and_the_last_outputs_stay_readable(native_dir, capfd):
    fmu = Driven(native_dir / "FrictionCoulomb.fmu")
    try:
        fmu.start({}, {"F_upper": 100.0, "F_lower": 50.0, "u": 0.1})
        assert fmu.step(0.0, STEP) == fmi2OK
        before = fmu.outputs()
        fmu.set({"F_upper": -3.0})
        assert fmu.step(STEP, STEP) == fmi2Discard and fmu.terminated
        assert fmu.outputs() == before  # the outputs at the last successful time
        fmu.set({"F_upper": 100.0})
        assert fmu.step(STEP, STEP) == fmi2OK and not fmu.terminated
    finally:
        fmu.close()
    assert "input F_upper must be >= 0, got -3.0" in capfd.readouterr().err


def test_too_many_substeps_discards_without_terminating_so_a_shorter_step_may_retry(native_dir):
    fmu = Driven(native_dir / "VerticalDynamics.fmu")
    try:
        fmu.start({}, {"K_contact": 1e14})
        assert fmu.step(0.0, 1.0) == fmi2Discard
        assert not fmu.terminated
        assert fmu.step(0.0, 1e-6) == fmi2OK
    finally:
        fmu.close()


def test_fmu_state_repeats_the_steps_bit_for_bit_and_survives_serialisation(native_dir):
    fmu = Driven(native_dir / "VerticalDynamics.fmu")
    script = _script("VerticalDynamics", 30, seed=7)
    try:
        fmu.start({"load_amplitude": 500.0, "load_frequency": 300.0}, script[0])

        def run(k0):
            rows = []
            for k, values in enumerate(script[k0:], start=k0):
                fmu.set(values)
                assert fmu.step(k * STEP, STEP) == fmi2OK
                rows.append(fmu.outputs())
            return rows

        for k, values in enumerate(script[:10]):
            fmu.set(values)
            fmu.step(k * STEP, STEP)
        state = fmu.slave.getFMUstate()
        first = run(10)
        fmu.slave.setFMUstate(state)
        assert run(10) == first
        restored = fmu.slave.deSerializeFMUstate(fmu.slave.serializeFMUstate(state))
        fmu.slave.setFMUstate(restored)
        assert run(10) == first
        fmu.slave.freeFMUstate(state)
        fmu.slave.freeFMUstate(restored)
    finally:
        fmu.close()


def test_two_instances_keep_their_own_parameters_and_state(native_dir):
    a, b = Driven(native_dir / "VerticalDynamics.fmu", "a"), Driven(native_dir / "VerticalDynamics.fmu", "b")
    try:
        a.start({"mass": 2.0}, {"F_ext": 10.0})
        b.start({"mass": 4.0}, {"F_ext": 10.0})
        for fmu in (a, b):
            assert fmu.step(0.0, STEP) == fmi2OK
        assert a.outputs()["y_ddot"] != b.outputs()["y_ddot"]
        assert b.outputs()["y_ddot"] == pytest.approx(9.80665 + 10.0 / 4.0)  # hand calculation
    finally:
        a.close()
        b.close()


def test_every_component_is_native_python_only_with_a_reason_or_refused_by_name():
    from guideway_fmu.fmu_build import native
    from guideway_fmu.fmu_build.native.component import Unit
    from guideway_fmu.fmu_build.native.source import TranslationError

    assert set(native.COMPONENTS) == set(NATIVE)  # every native edition is tested above
    assert not set(native.COMPONENTS) & set(native.PYTHON_ONLY)
    for name in registry.names():
        if name in native.COMPONENTS or name in native.PYTHON_ONLY:
            continue
        with pytest.raises(TranslationError, match=name + r"|\.py:\d+: "):
            Unit(registry.component(name)).text  # noqa: B018 - refused, naming what and where


def test_start_values_baked_into_the_model_description_are_where_both_editions_start(
        native_dir, fmu_dir, tmp_path):
    from guideway_fmu.fmi.archive import with_start_values
    baked = {"mass": 4.0, "load_amplitude": 250.0, "F_ext": 10.0}
    script = _script("VerticalDynamics", 10, seed=3)
    rows = {}
    for edition, folder in (("native", native_dir), ("python", fmu_dir)):
        fmu = with_start_values(folder / "VerticalDynamics.fmu", tmp_path / f"{edition}.fmu", baked)
        driven = Driven(fmu)
        try:
            assert {k: driven.slave.getReal([driven.refs[k].valueReference])[0]
                    for k in baked} == baked
        finally:
            driven.close()
        rows[edition] = run_script(fmu, {}, [{}] + script, STEP)
    for a, b in zip(rows["python"], rows["native"], strict=True):
        assert b == pytest.approx(a, rel=1e-13, abs=1e-300)
    assert rows["native"][1]["y_ddot"] == pytest.approx(9.80665 + 10.0 / 4.0)  # hand calculation


def test_a_start_value_not_of_its_type_refuses_the_instance_naming_variable_and_file(
        native_dir, tmp_path, capfd):
    from fmpy import extract
    from fmpy.fmi2 import FMU2Slave

    from guideway_fmu.fmi.archive import rewrite

    def spoil(name, data):  # what a careless tool may write (fmpy itself refuses to read it)
        if name == "modelDescription.xml":
            start = data.index(b'start="', data.index(b'name="mass"')) + len('start="')
            data = data[:start] + b"heavy" + data[data.index(b'"', start):]
        return name, data

    fmu = rewrite(native_dir / "VerticalDynamics.fmu", tmp_path / "spoilt.fmu", spoil)
    described = read_model_description(native_dir / "VerticalDynamics.fmu")
    slave = FMU2Slave(guid=described.guid, unzipDirectory=extract(fmu, tmp_path / "x"),
                      modelIdentifier="VerticalDynamics", instanceName="spoilt")
    logged = []
    with pytest.raises(Exception, match="instantiate"):
        slave.instantiate(callbacks=capturing_callbacks(logged))
    err = capfd.readouterr().err
    assert 'the start value "heavy" of mass is not of its type' in err
    assert "modelDescription.xml" in err
    assert any("heavy" in str(m) for m in logged)


def test_build_edition_native_writes_native_fmus_under_the_same_names_and_python_for_the_rest(
        tmp_path, capsys):
    from guideway_fmu import cli
    from guideway_fmu.fmu_build import build

    assert cli.main(["build", "--edition", "native", "--out", str(tmp_path),
                     "FrictionCoulomb", "FrictionMixedEHL"]) == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "FrictionCoulomb.fmu", "FrictionMixedEHL.fmu", "README.md"]
    native = build.built_edition(tmp_path / "FrictionCoulomb.fmu")
    assert native == ("native", build.fmu_hash(registry.component("FrictionCoulomb"), "native"))
    assert build.built_edition(tmp_path / "FrictionMixedEHL.fmu")[0] == "python"  # none native
    readme = (tmp_path / "README.md").read_text()
    assert "Built: native edition." in readme and "Built: python edition." in readme
    with pytest.raises(SystemExit):
        cli.main(["build", "--edition", "wasm", "--out", str(tmp_path)])
    assert "invalid choice: 'wasm'" in capsys.readouterr().err
    assert cli.main(["build", "--cross", "--out", str(tmp_path), "FrictionCoulomb"]) == 2
    assert "--cross cross-compiles native FMUs: give --edition native" in capsys.readouterr().err


def test_ensure_rebuilds_a_native_fmu_of_other_code_in_the_native_edition(native_dir, tmp_path):
    import shutil

    from guideway_fmu.fmi.archive import rewrite
    from guideway_fmu.fmu_build import build

    fmu = tmp_path / "FrictionDahl.fmu"
    shutil.copy2(native_dir / "FrictionDahl.fmu", fmu)
    current = build.built_tag(fmu)
    rewrite(fmu, fmu, lambda n, d: (n, d.replace(current.encode(), b"0000000000")))
    assert build.built_edition(fmu) == ("native", "0000000000")
    build.ensure(tmp_path, ["FrictionDahl"])
    assert build.built_edition(fmu) == ("native", current)


@pytest.mark.slow
def test_ensure_rebuilds_a_stale_cross_built_fmu_with_its_other_platforms(native_dir, tmp_path):
    import shutil

    from guideway_fmu.fmi.archive import rewrite
    from guideway_fmu.fmu_build import build

    fmu = tmp_path / "FrictionDahl.fmu"
    shutil.copy2(native_dir / "FrictionDahl.fmu", fmu)
    current = build.built_tag(fmu)
    assert not build.cross_built(fmu)
    with zipfile.ZipFile(fmu, "a") as archive:  # as --cross made it, from older code
        archive.writestr("binaries/win64/FrictionDahl.dll", b"old")
    rewrite(fmu, fmu, lambda n, d: (n, d.replace(current.encode(), b"0000000000")))
    assert build.cross_built(fmu)
    build.ensure(tmp_path, ["FrictionDahl"])
    assert build.built_edition(fmu) == ("native", current) and build.cross_built(fmu)
    with zipfile.ZipFile(fmu) as archive:
        assert archive.read("binaries/win64/FrictionDahl.dll")[:2] == b"MZ"  # built anew
        assert "binaries/darwin64/FrictionDahl.dylib" in archive.namelist()


def test_getattr_takes_its_default_only_where_the_attribute_is_missing():
    from compiled import compiled

    from guideway_fmu.fmu_build.native.source import TranslationError

    assert compiled(_attribute_or_default, 2)(2.0, 0.0) == 2.0 + 7.0
    with pytest.raises(TranslationError, match="attribute real of a run-time double is not translated"):
        compiled(_untranslated_attribute_or_default, 2)


class _Holder:
    scale = 7.0


def _attribute_or_default(x, _):
    return x + getattr(_Holder, "scale", 1.0) + getattr(_Holder, "missing", 0.0)


def _untranslated_attribute_or_default(x, _):
    return getattr(x, "real", 0.0)  # Python has x.real: a default would change the answer


def test_the_caches_native_set_holds_every_fmu_native_where_it_can_be(fmu_dir):
    import os

    from guideway_fmu.fmu_build import build, cache
    from guideway_fmu.fmu_build.native import COMPONENTS

    folder = cache.folder("native")
    assert sorted(p.name for p in folder.glob("*.fmu")) == sorted(p.name for p in fmu_dir.glob("*.fmu"))
    for fmu in folder.glob("*.fmu"):
        edition, _ = build.built_edition(fmu)
        assert edition == ("native" if fmu.stem in COMPONENTS else "python"), fmu.name
        if edition == "python":  # the python set's very file
            assert os.path.samefile(fmu, fmu_dir / fmu.name)


def test_a_shipped_scenario_runs_from_the_native_set_with_the_python_sets_results(
        fmu_dir, tmp_path, capsys):
    import json

    from guideway_fmu import cli

    results = {}
    for edition in ("python", "native"):
        out = tmp_path / edition
        assert cli.main(["run", "soleimanian2020_9000N_4500Hz_dry", "--stop", "4e-4", "--out",
                         str(out), "--edition", edition, "--no-progress"]) == 0
        json.loads(capsys.readouterr().out)
        results[edition] = np.genfromtxt(out / "results.csv", delimiter=",", names=True)
    python, native = results["python"], results["native"]
    assert native.dtype.names == python.dtype.names and len(native) == len(python) > 50
    for column in python.dtype.names:
        assert native[column] == pytest.approx(python[column], rel=1e-12, abs=1e-18), column


FEEDS = {"biharmonic": {"frequency": 3.0}, "oscillating": {"mean_velocity": 0.05},
         "constant": {"velocity": -0.02}, "trapezoid": {"distance": 0.01, "t_start": 1e-3},
         "input": {}}


@pytest.mark.parametrize("profile", FEEDS)
def test_every_feed_profile_a_string_parameter_chooses_runs_natively_as_in_python(
        profile, native_dir, fmu_dir):
    from guideway_fmu.physics.rigs.feed_motion import PROFILES
    assert set(FEEDS) == set(PROFILES) - {"table", "replay"}  # these two read a file
    script = _script("FeedKinematics", 60, seed=11)
    parameters = {"profile": profile, **FEEDS[profile]}
    python = run_script(fmu_dir / "FeedKinematics.fmu", parameters, script, STEP)
    native = run_script(native_dir / "FeedKinematics.fmu", parameters, script, STEP)
    assert len({r["x"] for r in native}) > 5  # the feed moves
    for a, b in zip(python, native, strict=True):
        assert b == pytest.approx(a, rel=1e-13, abs=1e-300)


@pytest.mark.parametrize("profile, words", [
    ("zigzag", "parameter profile must be one of ('biharmonic', 'oscillating', 'constant', "
               "'trapezoid', 'table', 'replay', 'input'), got 'zigzag'"),
    ("table", "profile 'table' is not in the native edition of FeedKinematics (parameter "
              "table_file must name a CSV file when profile is 'table'); the python edition has it")])
def test_a_profile_outside_the_choices_or_not_translated_is_refused_by_name(
        profile, words, native_dir, fmu_dir, capfd):
    fmu = Driven(native_dir / "FeedKinematics.fmu")
    try:
        fmu.start({}, {})
        assert fmu.step(0.0, STEP) == fmi2OK
        fmu.set({"profile": profile})
        assert fmu.step(STEP, STEP) == fmi2Discard and fmu.terminated
        assert fmu.slave.getString([fmu.refs["profile"].valueReference]) == [profile.encode()]
    finally:
        fmu.close()
    said = capfd.readouterr().err
    assert words in said
    if profile == "zigzag":  # the Python edition's sentence, word for word
        python = Driven(fmu_dir / "FeedKinematics.fmu")
        try:
            python.start({}, {})
            python.set({"profile": profile})
            assert python.step(0.0, STEP) == fmi2Discard
        finally:
            python.close()
        assert words in capfd.readouterr().err


@pytest.mark.parametrize("parameters", [{"film_model": "pan_hamrock"}, {"interpolate_inputs": True}],
                         ids=["pan_hamrock", "interpolated"])
def test_contact_ehl_film_laws_run_natively_as_in_python(parameters, native_dir, fmu_dir):
    script = _script("ContactEHL", 40, seed=5)
    python = run_script(fmu_dir / "ContactEHL.fmu", parameters, script, STEP)
    native = run_script(native_dir / "ContactEHL.fmu", parameters, script, STEP)
    for k, (a, b) in enumerate(zip(python, native, strict=True)):
        assert b == pytest.approx(a, rel=1e-12, abs=1e-300), k


@pytest.mark.slow
def test_every_native_fmu_runs_in_a_plain_c_host_with_an_empty_environment_like_python(
        native_dir, fmu_dir, tmp_path):
    from guideway_fmu.fmu_build import host_env

    executable = host_env.compile_c_host(tmp_path)
    python_env = host_env.host_environment()
    for name in NATIVE:
        runs = [host_env.run_in_c_host(executable, native_dir / f"{name}.fmu", {},
                                       work_dir=tmp_path) for _ in range(3)]
        assert [r.status for r in runs] == [0, 0, 0], (name, runs[0].stderr[-2000:])
        python = host_env.run_in_c_host(executable, fmu_dir / f"{name}.fmu", python_env,
                                        work_dir=tmp_path)
        assert python.status == 0, python.stderr[-2000:]
        assert runs[0].outputs == pytest.approx(python.outputs, rel=1e-13, abs=1e-300), name
        assert runs[0].outputs  # every Real output was read


@pytest.mark.slow
def test_an_ssp_of_native_fmus_with_baked_parameters_runs_in_libcosim_and_fmpy_as_in_our_master(
        native_dir, fmu_dir, tmp_path):
    """The native FMUs of a Soleimanian rig in an SSP package whose FMUs carry the scenario's
    parameters as start values (a String among them): libcosim and fmpy's SSP runner give our
    master's rows, and so does the python edition."""
    from fmpy.ssp.simulation import simulate_ssp

    from guideway_fmu import scenarios
    from guideway_fmu.cosim import master, ssp, system

    def load(folder, name):
        b = system.Builder(name).experiment(start=0.0, stop=2e-4, step=1e-6, algorithm="jacobi")
        b.component("Feed", "FeedKinematics.fmu", profile="oscillating", mean_velocity=0.0,
                    frequency=40.0)
        b.component("Carriage", "VerticalDynamics.fmu")
        b.component("Contact", "ContactEHL.fmu", preload=8000.0)
        for source, target in [("Feed.u", "Contact.u"), *scenarios.coupling()]:
            b.connect(source, target)
        system.dump(b.system(check_fmus=False), tmp_path / f"{name}.toml")
        return system.load(tmp_path / f"{name}.toml", fmu_dir=folder)

    native, python = load(native_dir, "native"), load(fmu_dir, "python")
    names = [f"{i}.{n}" for i, vs in native.variables.items() for n, v in vs.items()
             if v.causality == "output"]
    ours = master.simulate(native).recording
    reference = master.simulate(python).recording
    package = ssp.export_ssp(native, tmp_path / "native.ssp")
    _, libcosim = ssp.run_libcosim(package, names, 200)
    rows = simulate_ssp(str(package), start_time=0.0, stop_time=2e-4, step_size=1e-6)
    assert ours.columns["Contact.F_upper"][0] == pytest.approx(8000.0 / 80)  # baked preload
    for name in names:
        scale = np.abs(ours.columns[name]).max()
        np.testing.assert_allclose(ours.columns[name], reference.columns[name], rtol=1e-13,
                                   atol=1e-13 * scale, err_msg=name)
        np.testing.assert_allclose(libcosim[name], ours.columns[name], rtol=1e-11,
                                   atol=1e-11 * scale, err_msg=name)
        np.testing.assert_allclose(rows[name][:200], ours.columns[name][1:], rtol=1e-11,
                                   atol=1e-11 * scale, err_msg=name)


@pytest.mark.slow
def test_export_fmu_packs_the_native_set_and_runs_as_the_python_one(tmp_path, capsys):
    import fmpy

    from guideway_fmu import cli

    results = {}
    for edition in ("python", "native"):
        out = tmp_path / f"{edition}.fmu"
        assert cli.main(["export-fmu", "soleimanian2020_9000N_4500Hz_dry", str(out), "--edition",
                         edition, "--stop", "2e-4"]) == 0
        results[edition] = fmpy.simulate_fmu(str(out), stop_time=2e-4, output_interval=4e-6)
    capsys.readouterr()
    python, native = results["python"], results["native"]
    assert len(native) == len(python) > 40
    for name in python.dtype.names:
        assert native[name] == pytest.approx(python[name], rel=1e-12, abs=1e-18), name


TABLES = [("FrictionPositionDependent", {"factors": "0.8 1.3 0.9 1.1 1.0 1.25 0.7"}),
          ("FrictionBallToBall", {"factors": "1 1.5 2", "table_start": 0.1, "table_end": 0.4}),
          ("FrictionBallToBall", {"factors": " ".join(["1.0", "1.2"] * 60)}),
          ("FrictionPreloadLoss", {"law": "table", "profile": "0 0.5 0.6 0.9 1",
                                   "loss": 0.4, "wear_distance": 0.01}),
          ("FrictionPreloadLoss", {"law": "wear", "loss": 0.3, "wear_distance": 0.02}),
          ("FrictionPreloadLoss", {"law": "exponential", "loss": 0.3, "wear_distance": 0.005})]


@pytest.mark.parametrize("name, parameters", TABLES,
                         ids=[f"{n}-{len(str(p).split())}" for n, p in TABLES])
def test_friction_tables_of_any_length_a_string_gives_run_natively_as_in_python(
        name, parameters, native_dir, fmu_dir):
    script = _script(name, 60, seed=17)
    python = run_script(fmu_dir / f"{name}.fmu", parameters, script, STEP)
    native = run_script(native_dir / f"{name}.fmu", parameters, script, STEP)
    assert len({r["F_friction"] for r in native}) > 10
    for a, b in zip(python, native, strict=True):
        assert b == pytest.approx(a, rel=1e-13, abs=1e-300)


@pytest.mark.parametrize("name, parameters, words", [
    ("FrictionPositionDependent", {"factors": "1 x 2"},
     "parameter factors must be numbers separated by spaces, got '1 x 2'"),
    ("FrictionBallToBall", {"factors": "1"},
     "parameter factors needs at least 2 finite numbers, got '1'"),
    ("FrictionBallToBall", {"factors": "1 nan"},
     "parameter factors needs at least 2 finite numbers, got '1 nan'"),
    ("FrictionPreloadLoss", {"law": "table", "profile": "0 0.7 0.6 1"},
     "parameter profile must rise from 0 to 1 without falling back, got '0 0.7 0.6 1'"),
    ("FrictionPreloadLoss", {"law": "linear"},
     "parameter law must be one of ('exponential', 'wear', 'table'), got 'linear'")])
def test_a_bad_table_is_refused_in_pythons_words(name, parameters, words, native_dir, fmu_dir,
                                                 capfd):
    for folder in (native_dir, fmu_dir):
        fmu = Driven(folder / f"{name}.fmu")
        try:
            fmu.start({}, {})
            fmu.set(parameters)
            assert fmu.step(0.0, STEP) == fmi2Discard and fmu.terminated
        finally:
            fmu.close()
        assert words in capfd.readouterr().err, folder


def test_a_table_longer_than_the_native_capacity_is_refused_naming_the_python_edition(
        native_dir, capfd):
    from guideway_fmu.fmu_build.native.vectors import CAPACITY
    fmu = Driven(native_dir / "FrictionBallToBall.fmu")
    try:
        fmu.start({}, {})
        fmu.set({"factors": " ".join(["1"] * (CAPACITY + 1))})
        assert fmu.step(0.0, STEP) == fmi2Discard and fmu.terminated
    finally:
        fmu.close()
    assert (f"an array of {CAPACITY + 1} numbers is longer than the native edition holds "
            f"({CAPACITY}); take the python edition") in capfd.readouterr().err


def test_a_text_longer_than_the_native_edition_holds_is_an_error_naming_the_variable(
        native_dir, capfd):
    from guideway_fmu.fmu_build.native.component import STRING_SIZE
    fmu = Driven(native_dir / "FrictionPositionDependent.fmu")
    try:
        with pytest.raises(FMICallException):
            fmu.set({"factors": "1 " * STRING_SIZE})
        assert fmu.slave.getString([fmu.refs["factors"].valueReference]) == [b"1 1"]  # kept
    finally:
        fmu.slave.freeInstance()
    assert (f"the text given to factors is longer than the native edition holds "
            f"({STRING_SIZE - 1} bytes); take the python edition") in capfd.readouterr().err


def test_a_long_table_baked_into_the_model_description_is_where_the_native_fmu_starts(
        native_dir, fmu_dir, tmp_path):
    from guideway_fmu.fmi.archive import with_start_values
    factors = " ".join(repr(1.0 + 0.01 * k) for k in range(200))  # 3.6 kB of text
    script = _script("FrictionPositionDependent", 20, seed=4)
    rows = {}
    for edition, folder in (("native", native_dir), ("python", fmu_dir)):
        fmu = with_start_values(folder / "FrictionPositionDependent.fmu", tmp_path / f"{edition}.fmu",
                                {"factors": factors})
        rows[edition] = run_script(fmu, {}, script, STEP)
    for a, b in zip(rows["python"], rows["native"], strict=True):
        assert b == pytest.approx(a, rel=1e-13, abs=1e-300)


@pytest.mark.parametrize("teeth", [1, 3, 8, 13])
def test_an_end_mill_of_any_tooth_count_runs_natively_as_in_python(teeth, native_dir, fmu_dir):
    parameters = {"teeth": teeth, "entry_angle": 0.3, "exit_angle": 2.9}
    script = _script("MillingForce", 80, seed=teeth)
    python = run_script(fmu_dir / "MillingForce.fmu", parameters, script, 3e-5)
    native = run_script(native_dir / "MillingForce.fmu", parameters, script, 3e-5)
    assert len({r["F_x"] for r in native}) > 20
    for a, b in zip(python, native, strict=True):
        assert b == pytest.approx(a, rel=1e-12, abs=1e-9)


WINE = Path("/usr/lib/wine/wine64")


@pytest.mark.slow
@pytest.mark.skipif(importlib.util.find_spec("ziglang") is None,
                    reason="cross-compiling needs the ziglang package (the [cross] extra)")
def test_cross_compiled_binaries_a_win64_host_runs_under_wine_as_linux_runs_them(tmp_path):
    """Every native FMU with win64 and darwin64 binaries beside linux64; the win64 one, in a C
    host compiled for Windows, under wine (where Debian's wine64 is installed), gives the linux
    binary's outputs; the darwin64 one is a 64-bit Mach-O library (no macOS here to run it)."""
    from guideway_fmu.fmu_build import host_env
    from guideway_fmu.fmu_build.native import COMPONENTS

    fmus = [build_native(registry.component(name), tmp_path / f"{name}.fmu",
                         ("linux64", "win64", "darwin64")) for name in COMPONENTS]
    linux_host = host_env.compile_c_host(tmp_path)
    windows_host = host_env.compile_c_host(tmp_path, "win64") if WINE.exists() else None
    environment = {"WINEPREFIX": str(tmp_path / "wine"), "WINEDEBUG": "-all",
                   "HOME": str(tmp_path)}
    for fmu in fmus:
        with zipfile.ZipFile(fmu) as archive:
            mach_o = archive.read(f"binaries/darwin64/{fmu.stem}.dylib")[:4]
            assert mach_o == b"\xcf\xfa\xed\xfe", fmu.name  # MH_MAGIC_64, little-endian
            assert archive.read(f"binaries/win64/{fmu.stem}.dll")[:2] == b"MZ"
        linux = host_env.run_in_c_host(linux_host, fmu, {}, work_dir=tmp_path)
        assert linux.status == 0, linux.stderr[-2000:]
        if windows_host is None:
            continue
        windows = host_env.run_in_c_host(windows_host, fmu, environment, work_dir=tmp_path,
                                         platform="win64", launcher=(str(WINE),))
        assert windows.status == 0, windows.stderr[-2000:]
        assert windows.outputs == pytest.approx(linux.outputs, rel=1e-13, abs=1e-300), fmu.name
    if windows_host is None:
        pytest.skip("wine64 is not installed: the win64 binaries were built, not run")


@pytest.mark.parametrize("h", [0.0, -1e-5, math.nan])
def test_a_bad_step_size_is_refused_in_the_python_editions_sentence(h, native_dir, fmu_dir, capfd):
    said = []
    for folder in (native_dir, fmu_dir):
        fmu = Driven(folder / "HorizontalRig.fmu")
        try:
            fmu.start({}, {})
            assert fmu.step(0.0, h) == fmi2Discard
        finally:
            fmu.close()
        said.append(next(line for line in capfd.readouterr().err.splitlines()
                         if "communication step size" in line))
    assert said[0] == said[1] and said[0].endswith(f"must be > 0, got {h!r}")


def test_the_logger_hears_of_failures_only_while_logging_is_on_and_stderr_always(
        native_dir, capfd):
    fmu = Driven(native_dir / "FrictionCoulomb.fmu")
    try:
        fmu.start({}, {})
        fmu.slave.setDebugLogging(False, [])
        fmu.set({"F_upper": -1.0})
        assert fmu.step(0.0, STEP) == fmi2Discard
        assert fmu.messages == [] and "F_upper" in capfd.readouterr().err
        fmu.slave.setDebugLogging(True, [])
        fmu.set({"F_upper": -2.0})
        assert fmu.step(0.0, STEP) == fmi2Discard
        assert any("input F_upper must be >= 0, got -2.0" in str(m) for m in fmu.messages)
    finally:
        fmu.close()


def test_baked_string_start_values_choose_the_law_and_their_xml_entities_are_read(
        native_dir, fmu_dir, tmp_path):
    from guideway_fmu.fmi.archive import with_start_values
    script = _script("FeedKinematics", 20, seed=9)
    rows = {}
    for edition, folder in (("native", native_dir), ("python", fmu_dir)):
        fmu = with_start_values(folder / "FeedKinematics.fmu", tmp_path / f"{edition}.fmu",
                                {"profile": "oscillating", "table_file": "a&b <c>.csv"})
        driven = Driven(fmu)
        try:
            assert driven.slave.getString([driven.refs["profile"].valueReference,
                                           driven.refs["table_file"].valueReference]) == \
                [b"oscillating", b"a&b <c>.csv"]
        finally:
            driven.close()
        rows[edition] = run_script(fmu, {}, script, STEP)
    assert rows["native"] == rows["python"]
    unbaked = native_dir / "FeedKinematics.fmu"
    assert rows["native"] == run_script(unbaked, {"profile": "oscillating"}, script, STEP)
    assert rows["native"] != run_script(unbaked, {}, script, STEP)  # not the default law


def test_values_a_failing_set_call_stored_before_its_failure_take_effect(native_dir, capfd):
    """FMI leaves a failed call's partial effect open; here what was stored counts: the
    parameter is used at the next step, not a model built from the old value."""
    fmu = Driven(native_dir / "VerticalDynamics.fmu")
    try:
        fmu.start({}, {"F_ext": 10.0})
        assert fmu.step(0.0, STEP) == fmi2OK
        with pytest.raises(FMICallException):  # y is an output: the call fails there
            fmu.slave.setReal([fmu.refs["mass"].valueReference, fmu.refs["y"].valueReference],
                              [4.0, 0.0])
        assert fmu.step(STEP, STEP) == fmi2OK
        assert fmu.outputs()["y_ddot"] == pytest.approx(9.80665 + 10.0 / 4.0)  # hand value
    finally:
        fmu.close()
    loss = Driven(native_dir / "FrictionPreloadLoss.fmu")
    try:
        loss.start({}, {})
        refs = [loss.refs[n].valueReference for n in ("law", "profile")]
        with pytest.raises(FMICallException):  # the profile is too long: refused
            loss.slave.setString(refs, ["linear", "1 " * 5000])
        assert loss.step(0.0, STEP) == fmi2Discard and loss.terminated  # 'linear' was stored
    finally:
        loss.close()
    assert "got 'linear'" in capfd.readouterr().err
