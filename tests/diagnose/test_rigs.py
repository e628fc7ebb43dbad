"""The rigs as plug-ins of the workflow (diagnose/rigs.py): every kind of the measured-run format
has one, and a run is read once."""
from __future__ import annotations

import pytest

from guideway_fmu.diagnose import decide as decide_module
from guideway_fmu.diagnose import rigs, run_io
from guideway_synthetic import second_truth


def test_every_kind_of_the_format_has_a_rig():
    assert set(rigs.RIGS) == set(run_io.KINDS)
    assert all(rigs.RIGS[kind].kind == kind for kind in run_io.KINDS)


def test_the_horizontal_rig_decides_the_run_it_is_given_without_reading_it_again(tmp_path,
                                                                                  monkeypatch):
    second_truth.draw(tmp_path / "run", "unmodeled_mass", "drive", 64200, n_samples=2000)
    run = run_io.load_run(tmp_path / "run")

    def read_again(_):
        raise AssertionError("the run was read a second time")

    monkeypatch.setattr(decide_module, "load_run", read_again)
    named = rigs.HorizontalDrive().decide(run, tmp_path / "out", tmp_path / "fmus")
    assert named.run is run and named.effect == "unmodeled_mass"


def test_friction_is_turned_along_the_motion_once(tmp_path):
    second_truth.draw(tmp_path / "run", "none", "friction_opposes", 64201, n_samples=2000)
    run = run_io.load_run(tmp_path / "run")
    v = decide_module.motion_of(run).v
    run.orient_friction(v)
    turned = run.columns["friction_force"].copy()
    run.orient_friction(v)
    assert (run.columns["friction_force"] == turned).all()


def test_a_rig_without_its_three_steps_cannot_be_made():
    class Half(rigs.Rig):
        kind = "half_for_the_test"

        def decide(self, run, out, fmu_dir):
            return None

    try:
        assert rigs.RIGS["half_for_the_test"] is Half  # subclassing registered it
        with pytest.raises(TypeError, match="realise"):
            Half()
    finally:
        del rigs.RIGS["half_for_the_test"]
