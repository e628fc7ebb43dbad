import json

import numpy as np

from guideway_fmu import cli, demo
from guideway_fmu.physics import guideway


def test_cli_unknown_fmu_is_a_clear_error(tmp_path, capsys):
    assert cli.main(["build", "--out", str(tmp_path), "ContactMagic"]) == 2
    err = capsys.readouterr().err
    assert "ContactMagic" in err and "Traceback" not in err


def test_cli_facts_natural_frequency_near_published_6590_hz(capsys):
    assert cli.main(["facts"]) == 0
    facts = json.loads(capsys.readouterr().out)
    assert abs(facts["natural_frequency_lubricated_Hz"] / 6590.0 - 1) < 0.01
    assert facts["preload_per_roller_N"] == 115.0


def test_stiffness_curves_through_fmus_match_physics_derivative(fmu_dir):
    y = np.linspace(-1e-6, 1e-6, 21)  # both rows loaded: no kink inside the differences
    curves = demo.stiffness_curves(fmu_dir, y)
    g = guideway.Guideway()
    inner = slice(1, -1)  # np.gradient is one-sided at the ends
    np.testing.assert_allclose(curves["K_dry"][inner], curves["K_contact_output_dry"][inner], rtol=2e-3)
    np.testing.assert_allclose(curves["K_lubricated"][inner],
                               guideway.quasi_static_stiffness(g, y, demo.RIG_SPEED)[inner], rtol=2e-3)
    assert abs(curves["F_lubricated"][10]) < 1e-6  # y = 0: symmetric preload


def test_rig_run_oscillates_at_the_natural_frequency(fmu_dir):
    rec = demo.rig_run(fmu_dir, stop=1.5e-3, step=5e-6)
    y = rec.columns["body.y"] - rec.columns["body.y"].mean()
    crossings = np.count_nonzero(np.diff(np.sign(y)) != 0)
    frequency = crossings / 2 / rec.time[-1]
    assert abs(frequency / 6590.0 - 1) < 0.1  # ~10 periods: coarse count, published 6590 Hz
    assert np.all(np.isfinite(rec.columns["friction.F_friction"]))
    assert np.all(rec.columns["friction.F_friction"] < 0)  # feed velocity is positive here


def test_cli_demo_refuses_bad_step_before_any_work(tmp_path, capsys):
    assert cli.main(["demo", "--out", str(tmp_path / "o"), "--fmus", str(tmp_path / "f"),
                     "--step", "-1"]) == 2
    assert "--step" in capsys.readouterr().err
    assert not (tmp_path / "f").exists()
