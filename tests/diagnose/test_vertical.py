"""Vertical responses: the static start, the recorded-force replay, the refusals, and the
workflow naming hidden effects of the first generator's vertical records end to end."""
from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest

from guideway_fmu.diagnose import truth_vertical
from guideway_fmu.diagnose.run_io import load_run
from guideway_fmu.diagnose.vertical import VerticalRig, decide_vertical
from guideway_fmu.physics import force_table, guideway as gw
from guideway_fmu.physics.roller_contact import contact_force
from guideway_fmu.reference import monolithic
from guideway_fmu.reference.vertical import FusedVertical


def test_static_displacement_balances_the_load_by_palmgren_hand_calculation():
    g = gw.Guideway()
    y = gw.static_displacement(g, 9000.0, lubricated=False)
    s = math.sin(g.contact_angle)
    upper = contact_force(g.delta0 + y * s, g.k)
    lower = contact_force(g.delta0 - y * s, g.k)
    assert 2 * 20 * s * (upper - lower) == pytest.approx(9000.0, rel=1e-10)
    # lubricated: the films add to the approaches, the rows sit a little higher under the load
    assert gw.static_displacement(g, 9000.0, 0.2) < y


def test_force_table_interpolates_and_holds_its_ends(tmp_path):
    path = tmp_path / "load.csv"
    path.write_text("time,normal_force\n0.0,10.0\n1.0,30.0\n")
    model = force_table.from_parameters(str(path), "normal_force")
    assert [model.outputs(t, (), {})["F"] for t in (-1.0, 0.25, 2.0)] == [10.0, 15.0, 30.0]


@pytest.mark.parametrize("text, message", [("time,normal_force\n0.0,1\n0.0,2\n", "row 3"),
                                           ("time,load\n0.0,1\n1.0,2\n", "normal_force"),
                                           ("time,normal_force\n0.0,x\n1.0,2\n", "row 2")])
def test_bad_force_table_is_refused_naming_file_and_row(tmp_path, text, message):
    path = tmp_path / "load.csv"
    path.write_text(text)
    with pytest.raises(ValueError, match=message):
        force_table.from_parameters(str(path), "normal_force")


@pytest.fixture(scope="module")
def record(tmp_path_factory, fmu_dir):
    """A short first-generator vertical record hiding nothing, and its folder."""
    folder = tmp_path_factory.mktemp("vertical") / "run"
    truth_vertical.make_run(folder, "none", np.random.default_rng(2), fmu_dir, duration=0.02)
    return folder


@pytest.mark.parametrize("edit, message", [
    (lambda t: t.replace('type = "roller"', 'type = "ball"'), "ball guides"),
    (lambda t: t.replace('outputs = ["vertical_displacement"]', 'outputs = ["normal_force"]'),
     "'vertical_displacement' or 'vertical_acceleration'"),
    (lambda t: t.replace('contact = "ehl"', "").replace('contact = "dry_hertz"', ""),
     "names its contact"),
])
def test_vertical_rigs_the_model_cannot_take_are_refused_naming_the_key(tmp_path, record,
                                                                         fmu_dir, edit, message):
    (tmp_path / "run").mkdir()
    (tmp_path / "run" / "data.csv").write_text((record / "data.csv").read_text())
    (tmp_path / "run" / "rig.toml").write_text(edit((record / "rig.toml").read_text()))
    with pytest.raises(ValueError, match=message):
        VerticalRig(load_run(tmp_path / "run"), tmp_path / "model", fmu_dir)


@pytest.mark.slow
def test_baseline_of_a_record_hiding_nothing_reproduces_it_to_the_noise(tmp_path, record,
                                                                        fmu_dir):
    # the truth is the stated model at rtol 1e-9: the baseline's gap is the noise (limiting case)
    named = decide_vertical(load_run(record), tmp_path / "model", fmu_dir)
    assert named.gap_base == pytest.approx(named.noise, rel=0.1)
    assert named.effect == "none"


@pytest.mark.slow
@pytest.mark.parametrize("effect, seed", [("lubricant_film", 1), ("unmodeled_mass", 1),
                                          ("structural_mode", 2)])
def test_vertical_workflow_names_the_hidden_effect_of_first_generator_records(
        tmp_path, fmu_dir, effect, seed):
    from guideway_fmu.diagnose.workflow import diagnose
    info = truth_vertical.make_run(tmp_path / "run", effect, np.random.default_rng(seed), fmu_dir,
                                   duration=0.03)
    diagnosis = diagnose(tmp_path / "run", tmp_path / "out", fmu_dir=fmu_dir)
    assert diagnosis["missing_effect"] == info.expected
    d = json.loads((tmp_path / "out" / "diagnosis.json").read_text())
    assert list(d) == ["format", "missing_effect", "confidence", "channel", "gap_before",
                       "gap_after", "noise_floor", "candidates", "equation"]
    if info.expected != "unknown":  # the gap closes (on 0.03 s records not yet to the noise:
        # the free vibration's frequency is resolved to about 1 %, its phase needs less)
        assert d["gap_after"] < 0.6 * d["gap_before"] and d["gap_before"] > 3 * d["noise_floor"]
    else:
        assert d["equation"]
    assert (tmp_path / "out" / "spectra.png").stat().st_size > 10_000


@pytest.mark.parametrize("contact", ["dry_hertz", "ehl"])
def test_fused_vertical_model_matches_generic_monolithic_reference(tmp_path, record, fmu_dir,
                                                                  contact):
    # the same models in one fused right-hand side (DOP853 from sample to sample, rtol 1e-10)
    # against the generic assembly (LSODA, rtol 1e-11; itself about 1e-5 of the ranges off at
    # rtol 1e-9): the displacement and the acceleration agree to 1e-5 of their ranges over the
    # 0.02 s record (about 150 periods of the free vibration)
    rig = VerticalRig(load_run(record), tmp_path / "model", fmu_dir)
    system = rig.system(dataclasses.replace(rig.base, contact=contact))
    columns = ["Carriage.y", "Carriage.y_ddot"]
    generic = monolithic.simulate(system, times=rig.run.time, rtol=1e-11, columns=columns)
    fused = FusedVertical(system).simulate(rig.run.time, 1e-10, columns)
    for name in columns:
        expected = generic.columns[name]
        assert np.max(np.abs(fused[name] - expected)) < 1e-5 * np.ptp(expected), name


def test_fused_vertical_model_refuses_other_wiring_or_a_damped_contact_naming_it(tmp_path, record,
                                                                                 fmu_dir):
    rig = VerticalRig(load_run(record), tmp_path / "model", fmu_dir)
    system = rig.system(rig.base)
    unloaded = dataclasses.replace(system, connections=tuple(
        c for c in system.connections if (c.target, c.input) != ("Carriage", "F_ext")))
    with pytest.raises(ValueError, match=r"Load\.F -> Carriage\.F_ext, got none"):
        FusedVertical(unloaded)
    contact = system.components["Contact"]
    damped = dataclasses.replace(system, components={**system.components, "Contact":
                                 dataclasses.replace(contact, parameters={**contact.parameters,
                                                                          "damping": 10.0})})
    with pytest.raises(ValueError, match="'Contact' parameter damping"):
        FusedVertical(damped)


def test_free_vibration_peak_is_read_off_a_known_sine_beside_the_load_line(tmp_path, record,
                                                                          fmu_dir):
    # a sine at 0.9 of the baseline's natural frequency under the response to the normal force
    # (its line ten times stronger, its harmonics excluded): the peak comes back to 0.1 %; the
    # load's line alone, noise-free, shows no free vibration (its window leakage is not one)
    rig = VerticalRig(load_run(record), tmp_path / "model", fmu_dir)
    t = rig.run.time
    line = 2e-7 * (rig.normal - rig.normal.mean()) / np.ptp(rig.normal)
    f_load = rig.spectrum(rig.normal, 16)[0][np.argmax(rig.spectrum(rig.normal, 16)[1][1:]) + 1]
    f0 = 0.9 * rig.natural_frequency(rig.base)
    assert abs(f0 / f_load - round(2 * f0 / f_load) / 2) > 0.05  # away from the load's lines
    y = 1e-8 * np.sin(2 * np.pi * f0 * t + 0.3) + line
    assert rig.measured_natural_frequency(y) == pytest.approx(f0, rel=1e-3)
    assert rig.measured_natural_frequency(line) is None
