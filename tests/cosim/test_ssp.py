"""SSP export: the package's structure, and runs of it in libcosim and in fmpy's SSP runner
compared with our own Jacobi master (master.simulate).

The scenario starts at rest: feed velocity, displacement and velocity are 0 at t = 0. fmpy's
first step sees 0.0 on every connected input (cosim/ssp.py's docstring); the other tools see
the outputs at t = 0, which differ from 0 only in the contact loads, and the friction at u = 0 is
0 whatever the loads: the same first step. The fmpy case keeps the default feed profile
(biharmonic) with phases 0, and gets its parameters only from the baked FMUs.
"""
import dataclasses
import shutil
from pathlib import Path
import xml.etree.ElementTree as ET
import zipfile

from fmpy import read_model_description

import numpy as np
import pytest
from fmpy.ssp.simulation import simulate_ssp  # fmpy.ssp.simulate parses sys.argv on import

from guideway_fmu import cli, scenarios
from guideway_fmu.cosim import master, ssp, system
from support import SYMLINK, with_entry  # a malicious FMU

NS = {"ssd": ssp.SSD, "ssc": ssp.SSC, "ssv": ssp.SSV, "osp": ssp.OSP}
BASE = {"Contact": {"preload": 8000.0}, "Rough": {"rollers_per_groove": 18}}
LIBCOSIM = {**BASE, "Feed": {"profile": "oscillating", "mean_velocity": 0.0, "frequency": 40.0}}
FMPY = {**BASE, "Feed": {"phase1": 0.0, "phase2": 0.0}}  # biharmonic; both profiles: u(0) = 0
FRICTION_INPUTS = [("Feed.u", "u")] + [(f"Contact.{v}", v)
                                       for v in ("F_upper", "F_lower", "h_upper", "h_lower")]
WIRES = [("Feed.u", "Contact.u"), *scenarios.coupling()] + [
    (src, f"{inst}.{var}") for inst in ("Friction", "Rough") for src, var in FRICTION_INPUTS]
FMUS = {"Feed": "FeedKinematics", "Contact": "ContactEHL", "Carriage": "VerticalDynamics",
        "Friction": "FrictionMixedEHL", "Rough": "FrictionMixedEHL"}  # two instances, one file
RTOL = 1e-11  # round-off: libcosim counts integer ns, its FMUs see t off by ~1e-19 s (worst seen 9e-14)


def make(folder, fmu_dir, parameters, bake=True):
    """Write the scenario (``parameters``: instance -> {name: value}), load it and export it."""
    b = system.Builder("ssp_test").experiment(start=0.0, stop=2e-4, step=1e-6, algorithm="jacobi")
    for inst, fmu in FMUS.items():
        b.component(inst, f"{fmu}.fmu", **parameters.get(inst, {}))
    for source, target in WIRES:
        b.connect(source, target)
    system.dump(b.system(check_fmus=False), folder / "ssp_test.toml")
    sys_ = system.load(folder / "ssp_test.toml", fmu_dir=fmu_dir)
    return sys_, ssp.export_ssp(sys_, folder / "ssp_test.ssp", bake=bake)


def outputs(sys_):
    return [f"{i}.{n}" for i, vs in sys_.variables.items() for n, v in vs.items() if v.causality == "output"]


def run_fmpy(sys_, package, **options):
    """fmpy's rows: row k holds the values read after the step t_k -> t_k + h (here one row more
    than steps: its summed t falls short of stop). No parameter set: the package carries them."""
    exp = sys_.experiment
    return simulate_ssp(str(package), start_time=exp.start, stop_time=exp.stop, step_size=exp.step,
                        **options)


def steps(sys_):
    exp = sys_.experiment
    return round((exp.stop - exp.start) / exp.step)


def assert_same(actual, expected, names):
    for name in names:
        scale = np.abs(expected[name]).max()
        np.testing.assert_allclose(actual[name], expected[name], rtol=RTOL, atol=RTOL * scale, err_msg=name)


@pytest.fixture(scope="module")
def lc_case(tmp_path_factory, fmu_dir):
    return make(tmp_path_factory.mktemp("lc"), fmu_dir, LIBCOSIM)


@pytest.fixture(scope="module")
def fmpy_case(tmp_path_factory, fmu_dir):
    return make(tmp_path_factory.mktemp("fmpy"), fmu_dir, FMPY)


# -- structure ---------------------------------------------------------------------------------
def test_ssd_structure(lc_case):
    sys_, package = lc_case
    with zipfile.ZipFile(package) as zf:
        names = zf.namelist()
        root = ET.fromstring(zf.read("SystemStructure.ssd"))
    assert sorted(names) == ["SystemStructure.ssd", "resources/ContactEHL.fmu", "resources/FeedKinematics.fmu",
                             "resources/FrictionMixedEHL_Friction.fmu", "resources/FrictionMixedEHL_Rough.fmu",
                             "resources/VerticalDynamics.fmu"]  # Friction and Rough: two variants
    assert root.tag == f"{{{ssp.SSD}}}SystemStructureDescription" and root.get("version") == "1.0"
    (system_el,) = root.findall("ssd:System", NS)
    comps = {c.get("name"): c for c in system_el.findall("ssd:Elements/ssd:Component", NS)}
    assert list(comps) == list(sys_.components)
    assert {comp.get("type") for comp in comps.values()} == {"application/x-fmu-sharedlibrary"}
    assert comps["Rough"].get("source") == "resources/FrictionMixedEHL_Rough.fmu"
    assert comps["Carriage"].get("source") == "resources/VerticalDynamics.fmu"
    kinds = {(c.get("name"), c.get("kind"), c[0].tag.split("}")[1])
             for c in comps["Carriage"].findall("ssd:Connectors/ssd:Connector", NS)}
    assert ("F_contact", "input", "Real") in kinds and ("y", "output", "Real") in kinds
    assert ("mass", "parameter", "Real") in kinds
    assert not {"F_ext", "K_contact", "C_contact"} & {k[0] for k in kinds}  # unconnected inputs
    wires = [tuple(f"{c.get(f'{end}Element')}.{c.get(f'{end}Connector')}" for end in ("start", "end"))
             for c in system_el.findall("ssd:Connections/ssd:Connection", NS)]
    assert wires == WIRES

    def bindings(inst):
        path = ("ssd:ParameterBindings/ssd:ParameterBinding/ssd:ParameterValues/ssv:ParameterSet/"
                "ssv:Parameters/ssv:Parameter")
        return {p.get("name"): (p[0].tag.split("}")[1], p[0].get("value"))
                for p in comps[inst].findall(path, NS)}

    assert bindings("Feed") == {"profile": ("String", "oscillating"), "mean_velocity": ("Real", "0.0"),
                                "frequency": ("Real", "40.0")}
    assert bindings("Contact") == {"preload": ("Real", "8000.0")}
    assert bindings("Rough") == {"rollers_per_groove": ("Integer", "18")}
    assert bindings("Carriage") == {}
    exp = root.find("ssd:DefaultExperiment", NS)
    assert (float(exp.get("startTime")), float(exp.get("stopTime"))) == (0.0, 2e-4)
    algorithm = exp.find("ssd:Annotations/ssc:Annotation[@type='com.opensimulationplatform']/"
                         "osp:Algorithm/osp:FixedStepAlgorithm", NS)
    assert float(algorithm.get("baseStepSize")) == 1e-6


def test_ssd_validates_against_the_ssp_schema(lc_case):
    from fmpy.ssp.ssd import read_ssd  # validates against the SSP 1.0 XML schema

    assert read_ssd(str(lc_case[1])).system.name == "ssp_test"


def test_every_real_connector_has_its_fmus_unit_declared_once_with_its_base_unit(lc_case):
    from fmpy.ssp.ssd import read_ssd

    sys_, package = lc_case
    with zipfile.ZipFile(package) as zf:
        root = ET.fromstring(zf.read("SystemStructure.ssd"))
    connectors = root.findall("ssd:System/ssd:Elements/ssd:Component/ssd:Connectors/ssd:Connector", NS)
    reals = [c for c in connectors if c[0].tag == f"{{{ssp.SSC}}}Real"]
    owner = {id(c): comp.get("name") for comp in root.iter(f"{{{ssp.SSD}}}Component")
             for c in comp.iter(f"{{{ssp.SSD}}}Connector")}
    assert reals and all(c[0].get("unit") == sys_.unit(owner[id(c)], c.get("name")) for c in reals)
    units = {u.get("name"): u.find("ssc:BaseUnit", NS).attrib for u in root.findall("ssd:Units/ssc:Unit", NS)}
    assert set(units) == {c[0].get("unit") for c in reals}
    assert units["N"] == {"kg": "1", "m": "1", "s": "-2"} and units["m"] == {"m": "1"}
    assert units["Hz"] == {"s": "-1"}
    parsed = {u.name: (u.kg, u.m, u.s) for u in read_ssd(str(package)).units}  # fmpy reads them back
    assert parsed["N"] == (1, 1, -2) and len(parsed) == len(units)


def test_baked_copies_start_at_their_instances_parameters_and_keep_every_other_entry(lc_case, fmu_dir):
    sys_, package = lc_case
    with zipfile.ZipFile(package) as zf:
        for entry, fmu, values in (("ContactEHL.fmu", "ContactEHL", {"preload": 8000.0}),
                                   ("FrictionMixedEHL_Rough.fmu", "FrictionMixedEHL", {"rollers_per_groove": 18}),
                                   ("FrictionMixedEHL_Friction.fmu", "FrictionMixedEHL", {}),
                                   ("VerticalDynamics.fmu", "VerticalDynamics", {})):
            copy = sys_.path.parent / entry
            copy.write_bytes(zf.read(f"resources/{entry}"))
            original = fmu_dir / f"{fmu}.fmu"
            if not values:  # nothing to bake: the file itself
                assert copy.read_bytes() == original.read_bytes()
                continue
            starts = {v.name: v.start for v in read_model_description(str(copy)).modelVariables}
            assert {k: type(v)(starts[k]) for k, v in values.items()} == values
            with zipfile.ZipFile(copy) as a, zipfile.ZipFile(original) as b:
                assert a.namelist() == b.namelist()
                assert all(a.read(n) == b.read(n) for n in a.namelist() if n != "modelDescription.xml")


def test_an_unbaked_package_packs_each_fmu_file_once_unchanged(fmu_dir, tmp_path):
    sys_, package = make(tmp_path, fmu_dir, LIBCOSIM, bake=False)
    with zipfile.ZipFile(package) as zf:
        entries = sorted(n for n in zf.namelist() if n.startswith("resources/"))
        assert entries == sorted(f"resources/{f}.fmu" for f in set(FMUS.values()))
        assert all(zf.read(f"resources/{f}.fmu") == (fmu_dir / f"{f}.fmu").read_bytes() for f in FMUS.values())


# -- runs --------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def lc_run(lc_case):
    sys_, package = lc_case
    return ssp.run_libcosim(package, outputs(sys_), steps(sys_))


@pytest.fixture(scope="module")
def fmpy_run(fmpy_case):
    return run_fmpy(*fmpy_case)


def test_libcosim_matches_master(lc_case, lc_run):
    sys_, _ = lc_case
    expected = master.simulate(sys_).recording
    time, columns = lc_run
    np.testing.assert_allclose(time, expected.time, rtol=0, atol=1e-15)
    assert_same(columns, expected.columns, outputs(sys_))


def test_fmpy_matches_master(fmpy_case, fmpy_run):
    sys_, _ = fmpy_case
    n, expected = steps(sys_), master.simulate(sys_).recording
    np.testing.assert_allclose(fmpy_run["time"][:n], expected.time[:n], rtol=0, atol=1e-15)
    assert_same({k: fmpy_run[k][:n] for k in outputs(sys_)},
                {k: v[1:] for k, v in expected.columns.items()}, outputs(sys_))


def test_fmpy_matches_libcosim(fmpy_case, fmpy_run):
    sys_, package = fmpy_case
    n, names = steps(sys_), outputs(sys_)
    _, columns = ssp.run_libcosim(package, names, n)
    assert_same({k: fmpy_run[k][:n] for k in names}, {k: v[1:] for k, v in columns.items()}, names)


def check_parameters_reached(time, columns, feed_velocity):
    """Feed.u follows the bound profile; Contact's first loads are preload / (4 N) with the bound
    preload; Rough, a FrictionMixedEHL with the same inputs as Friction, differs only by its
    bound Integer parameter."""
    np.testing.assert_allclose(columns["Feed.u"], feed_velocity(time), rtol=1e-12, atol=1e-15)
    assert columns["Contact.F_upper"][0] == pytest.approx(8000.0 / 80)
    with pytest.raises(AssertionError):
        assert_same(columns, {"Rough.F_friction": columns["Friction.F_friction"]}, ["Rough.F_friction"])


def test_parameters_reach_libcosim(lc_run):
    check_parameters_reached(*lc_run, lambda t: -0.25 * np.sin(2 * np.pi * 40.0 * t))


def test_parameters_reach_fmpy(fmpy_case, fmpy_run):
    w = 2 * np.pi * 5.0
    time = fmpy_run["time"] + fmpy_case[0].experiment.step  # row k holds the values at t_k + h
    check_parameters_reached(time, fmpy_run, lambda t: 0.2919 * np.sin(w * t) + 0.0178 * np.sin(3 * w * t))


def test_fmpy_runs_the_exported_9000N_scenario_loaded_as_our_master_does(fmu_dir, tmp_path):
    """The shipped 9000 N, 4500 Hz scenario, 0.4 ms (100 steps of 4 us) under "jacobi", the
    scheme fmpy runs, with the feed starting at rest (phases 0: fmpy feeds 0.0 to every input in
    its first step and initialises the films with inputs at their start values, so a feed moving
    at t = 0 would change the films of its first steps). Explicit Jacobi coupling of this stiff
    contact grows away from the stabilised answer (docs/cosimulation.md): the check is that fmpy
    runs the same system as our master, step for step, which holds to the last bit. Without the
    baked FMUs fmpy ran the FMUs' defaults, unloaded."""
    scenario = system.load(Path(scenarios.__file__).parent / "soleimanian2020_9000N_4500Hz.toml",
                           fmu_dir=fmu_dir)
    loaded = scenario.with_changes(algorithm="jacobi", stop=4e-4,
                                   parameters={"Feed": {"phase1": 0.0, "phase2": 0.0}})
    unloaded = loaded.with_changes(parameters={"Carriage": {"load_amplitude": 0.0}})
    rows = run_fmpy(loaded, ssp.export_ssp(loaded, tmp_path / "loaded.ssp"))
    n = steps(loaded)
    expected = {k: v[1:n + 1] for k, v in master.simulate(loaded).recording.columns.items()}
    names = list(expected)  # the scenario's recorded variables
    assert_same({k: rows[k][:n] for k in names}, expected, names)
    other = master.simulate(unloaded).recording.columns
    for name in ("Carriage.y", "Contact.F_upper", "Contact.F_lower"):
        assert np.abs(rows[name][:n] - other[name][1:n + 1]).max() > 0.5 * np.abs(expected[name]).max()


# -- bad input ---------------------------------------------------------------------------------
def test_export_into_a_missing_folder_names_it(lc_case, tmp_path):
    with pytest.raises(FileNotFoundError, match="no_such_folder"):
        ssp.export_ssp(lc_case[0], tmp_path / "no_such_folder" / "x.ssp")


def test_export_of_a_vanished_fmu_names_it(fmu_dir, tmp_path):
    for fmu in set(FMUS.values()):
        shutil.copy(fmu_dir / f"{fmu}.fmu", tmp_path)
    sys_, _ = make(tmp_path, tmp_path, FMPY)
    (tmp_path / "ContactEHL.fmu").unlink()
    with pytest.raises(FileNotFoundError, match="Contact: FMU file .*ContactEHL.fmu does not exist"):
        ssp.export_ssp(sys_, tmp_path / "again.ssp")
    assert not (tmp_path / "again.ssp").exists()


def test_export_onto_one_of_its_own_inputs_is_refused_and_leaves_it_intact(fmu_dir, tmp_path):
    for fmu in set(FMUS.values()):
        shutil.copy(fmu_dir / f"{fmu}.fmu", tmp_path)
    sys_, _ = make(tmp_path, tmp_path, FMPY)
    for target, what in ((tmp_path / "ContactEHL.fmu", "Contact's FMU"),
                         (sys_.path, "the scenario file")):
        before = Path(target).read_bytes()
        with pytest.raises(ValueError, match=f"it is {what}, which the package is made from"):
            ssp.export_ssp(sys_, target)
        assert Path(target).read_bytes() == before


@pytest.mark.parametrize("export", ["ssp", "fmu"])
def test_export_onto_a_hard_link_to_one_of_its_inputs_is_refused_and_leaves_it_intact(
        fmu_dir, tmp_path, export):
    # another path to the same file passed the guard, which compared paths, and destroyed it
    from guideway_fmu.cosim.export_fmu import export_fmu

    for fmu in set(FMUS.values()):
        shutil.copy(fmu_dir / f"{fmu}.fmu", tmp_path)
    sys_, _ = make(tmp_path, tmp_path, FMPY)
    write = ssp.export_ssp if export == "ssp" else export_fmu
    made = "package" if export == "ssp" else "FMU"
    for target, what in ((tmp_path / "ContactEHL.fmu", "Contact's FMU"),
                         (sys_.path, "the scenario file")):
        link = tmp_path / f"link_to_{Path(target).stem}.{export}"
        link.hardlink_to(target)
        before = Path(target).read_bytes()
        with pytest.raises(ValueError, match=f"cannot write {link}: it is {what}, which the "
                                             f"{made} is made from"):
            write(sys_, link)
        assert Path(target).read_bytes() == before


@pytest.mark.parametrize("entry, mode", [("../../outside.txt", 0), ("/outside.txt", 0),
                                         ("resources/link", SYMLINK)])
def test_export_of_an_fmu_with_an_unsafe_entry_is_refused_naming_both(fmu_dir, tmp_path, entry, mode):
    for fmu in set(FMUS.values()):
        shutil.copy(fmu_dir / f"{fmu}.fmu", tmp_path)
    sys_, _ = make(tmp_path, tmp_path, FMPY)
    with_entry(fmu_dir / "ContactEHL.fmu", tmp_path / "ContactEHL.fmu", entry, mode)
    for bake in (True, False):
        with pytest.raises(ValueError, match=f"ContactEHL.fmu: archive entry '{entry}'"):
            ssp.export_ssp(sys_, tmp_path / "bad.ssp", bake=bake)
        assert not (tmp_path / "bad.ssp").exists()


def test_a_baked_fmu_that_does_not_start_at_its_start_values_is_refused(fmpy_case, tmp_path, monkeypatch):
    """An FMU with start values built into its code (here: the XML left as it was, as such an
    FMU would act) would run the package with other parameters, silently."""
    monkeypatch.setattr(ssp, "with_start_values", lambda fmu, out, values: shutil.copy(fmu, out))
    with pytest.raises(ValueError, match="Feed: .*FeedKinematics.fmu starts phase1 at 2.0588 whatever "
                                         "the start value in its modelDescription.xml \\(0.0 baked\\)"):
        ssp.export_ssp(fmpy_case[0], tmp_path / "x.ssp")


@pytest.mark.parametrize("options", [[], ["--no-bake"]])
def test_a_parameter_the_fmu_refuses_is_refused_at_export_with_its_message(fmu_dir, tmp_path,
                                                                           capsys, options):
    # exported with exit 0 before: the FMU refuses it only when initialised, which it was not
    from guideway_fmu import cli

    b = system.Builder("bad").experiment(stop=1e-3, step=1e-5, algorithm="jacobi")
    path = system.dump(b.component("Contact", "ContactEHL.fmu", preload=-100.0)
                       .system(check_fmus=False), tmp_path / "bad.toml")
    out = tmp_path / "bad.ssp"
    assert cli.main(["export-ssp", str(path), str(out), "--fmus", str(fmu_dir), *options]) == 2
    printed, message = capsys.readouterr().err.split("guideway-fmu export-ssp: error: ")
    line = "Contact: Guideway.preload must be > 0, got -100.0"
    assert printed == f"ContactEHL {line}\n"  # the FMU's own, on stderr for hosts without a log
    assert message == f"Contact: {fmu_dir / 'ContactEHL.fmu'} refuses the instance's parameters: {line}\n"
    assert not out.exists()


def test_a_unit_two_fmus_define_differently_is_refused_naming_both(fmu_dir, tmp_path):
    """(A unit an FMU uses without defining it is refused when the scenario is loaded: fmpy's
    validation of the modelDescription.)"""
    new = '<Unit name="N"><BaseUnit kg="1" m="1" s="-2" factor="1000.0"/></Unit>'  # kN named N
    for fmu in set(FMUS.values()):
        shutil.copy(fmu_dir / f"{fmu}.fmu", tmp_path)
    sys_, _ = make(tmp_path, tmp_path, FMPY)
    with zipfile.ZipFile(fmu_dir / "ContactEHL.fmu") as src, \
            zipfile.ZipFile(tmp_path / "ContactEHL.fmu", "w") as dst:
        for info in src.infolist():
            data = src.read(info)
            if info.filename == "modelDescription.xml":
                data = data.replace(b'<Unit name="N">\n\t\t\t<BaseUnit kg="1" m="1" s="-2"/>\n\t\t</Unit>',
                                    new.encode())
                assert new.encode() in data
            dst.writestr(info, data)
    with pytest.raises(ValueError, match="unit 'N' has the base unit .*'factor': '1000.0'.* in "
                                         ".*ContactEHL.fmu but .* in .*VerticalDynamics.fmu"):
        ssp.export_ssp(sys_, tmp_path / "x.ssp")


def test_parameter_set_refuses_what_fmpy_would_get_wrong(lc_case, fmpy_case):
    with pytest.raises(ValueError, match="Feed.profile: fmpy's simulate_ssp cannot set String"):
        ssp.parameter_set(lc_case[0])
    sys_ = fmpy_case[0]
    clash = dataclasses.replace(sys_, components={**sys_.components, "R": sys_.components["Carriage"]})
    with pytest.raises(ValueError, match="Rough.rollers_per_groove: fmpy would also apply it to R"):
        ssp.parameter_set(clash)


def test_export_ssp_warns_of_a_stiff_loop_an_ssp_host_cannot_follow(fmu_dir, tmp_path, capsys):
    package = tmp_path / "loaded.ssp"
    assert cli.main(["export-ssp", "soleimanian2020_9000N_4500Hz", "--fmus", str(fmu_dir),
                     str(package)]) == 0
    printed = capsys.readouterr()
    assert printed.out == f"{package}\n"
    warning = printed.err.replace("\n", " ")
    assert warning.startswith("warning: soleimanian2020_9000N_4500Hz couples a stiff loop "
                              "(Contact.F_contact on Contact.y)")
    assert "docs/hosts.md" in warning and "guideway-fmu export-fmu SCENARIO OUT.fmu" in warning
    assert "\n\n" not in printed.err  # one paragraph
    assert cli.main(["export-ssp", "lin2019_ball_to_ball_friction", "--fmus", str(fmu_dir),
                     str(tmp_path / "balls.ssp")]) == 0  # no tangents: nothing to warn of
    assert capsys.readouterr().err == ""
