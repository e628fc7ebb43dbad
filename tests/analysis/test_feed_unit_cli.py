"""``guideway-fmu feed-unit``: the feed-unit file, its errors, one load case and the sweeps."""
from __future__ import annotations

import json

import numpy as np
import pytest

from guideway_fmu import examples
from guideway_fmu.analysis import feed_unit as fa
from guideway_fmu.cli import main
from support import write_file

EXAMPLES = examples.FOLDER / "ball_guides"
VERTICAL = EXAMPLES / "zhang2019_vertical_10kN.toml"
CUTTING = EXAMPLES / "zhang2019_cutting_offset.toml"
BASE = VERTICAL.read_text()


def test_json_gives_five_errors_and_four_sliders_for_both_models(capsys):
    assert main(["feed-unit", str(CUTTING), "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    for model in ("angle_change", "constant_angle"):
        assert set(result[model]["errors"]) == {"delta_y", "delta_z", "epsilon_x", "epsilon_y",
                                                "epsilon_z"}
        assert [s["slider"] for s in result[model]["sliders"]] == [1, 2, 3, 4]
        assert all(s["stiffness_y"] > 0 and s["stiffness_z"] > 0 for s in result[model]["sliders"])
    assert result["constant_angle"]["sliders"][0]["row_contact_angle_deg"] == [45.0] * 4
    # the force (1500, 1000, -2000) N at (0.05, 0.08, 0.15) m: M = r x F by hand
    generalized = result["load"]["generalized"]
    assert generalized["M_x"] == pytest.approx(0.08 * -2000 - 0.15 * 1000)
    assert generalized["M_y"] == pytest.approx(0.15 * 1500 - 0.05 * -2000)
    assert generalized["M_z"] == pytest.approx(0.05 * 1000 - 0.08 * 1500)


def test_text_output_lists_errors_and_stiffness(capsys):
    assert main(["feed-unit", str(VERTICAL)]) == 0
    out = capsys.readouterr().out
    assert "delta_z [um]" in out and "slider 4 stiffness_z [N/um]" in out


def test_load_sweep_starts_at_zero_errors_and_is_monotone_with_a_plot(tmp_path, capsys):
    plot = tmp_path / "load.png"
    assert main(["feed-unit", str(VERTICAL), "--sweep", "load", "--points", "6", "--plot",
                 str(plot), "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert plot.stat().st_size > 10_000
    np.testing.assert_allclose(result["force_magnitude"], np.linspace(0, 10_000, 6))
    for model in ("angle_change", "constant_angle"):
        dz = np.array(result[model]["delta_z"])
        assert dz[0] == 0.0 and np.all(np.diff(dz) < 0)
    # the contact-angle change stiffens the unit vertically (Zhang et al. conclusion 1)
    assert result["angle_change"]["delta_z"][-1] > result["constant_angle"]["delta_z"][-1]


def test_point_sweep_reverses_the_roll_error_across_the_centre(capsys):
    assert main(["feed-unit", str(VERTICAL), "--sweep", "point_y", "--range", "-0.1", "0.1",
                 "--points", "5", "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    roll = np.array(result["angle_change"]["epsilon_x"])
    np.testing.assert_allclose(roll, -roll[::-1], rtol=1e-9, atol=1e-18)
    assert roll[0] != 0.0


def test_contact_angle_sweep_covers_the_papers_range_by_default():
    case = fa.read_feed_unit(VERTICAL)
    values = fa.sweep_values(case, "contact_angle")
    assert values[0] == 30.0 and values[-1] == 65.0 and len(values) == 21


@pytest.mark.parametrize("edit, message", [
    (lambda t: t.replace("[table]", "[tabel]"), "table [table] is missing"),
    (lambda t: t.replace("per_row = 12", "per_row = 12.5"), "[balls] key 'per_row'"),
    (lambda t: t.replace("conformity = 0.52", "conformity = 0.45"), "conformity"),
    (lambda t: t.replace("pitch = 4.8e-3", "pitch = -4.8e-3"), "[balls] key 'pitch'"),
    (lambda t: t.replace("contact_angle_deg = 45.0", "contact_angle_deg = 120.0"),
     "contact_angle"),
    (lambda t: t.replace("force = [0.0, 0.0, -10000.0]", "force = [0.0, -10000.0]"),
     "[load] key 'force'"),
    (lambda t: t.replace("[load]", "[load]\nspeed = 3"), "unknown [load] key 'speed'"),
    (lambda t: t + "\n[extra]\na = 1\n", "unknown table(s) [extra]"),
    (lambda t: t.replace("per_row = 12", "per_row = 60"), "sliders would overlap"),
    (lambda t: t.replace("half_span_x = 0.100", "half_span_x = 0.1 0"), "not valid TOML"),
])
def test_bad_feed_unit_file_is_refused_naming_file_and_key(tmp_path, capsys, edit, message):
    path = write_file(tmp_path, edit(BASE), "unit.toml")
    assert main(["feed-unit", str(path)]) == 2
    err = capsys.readouterr().err
    assert str(path) in err and message in err, err


def test_missing_file_and_bad_options_are_refused(tmp_path, capsys):
    assert main(["feed-unit", str(tmp_path / "none.toml")]) == 2
    assert "no such feed-unit file" in capsys.readouterr().err
    assert main(["feed-unit", str(VERTICAL), "--plot", str(tmp_path / "a.png")]) == 2
    assert "need --sweep" in capsys.readouterr().err
    assert main(["feed-unit", str(VERTICAL), "--sweep", "load", "--points", "1"]) == 2
    assert "--points" in capsys.readouterr().err
    assert main(["feed-unit", str(VERTICAL), "--sweep", "contact_angle", "--range", "0",
                 "50"]) == 2
    assert "(0, 90)" in capsys.readouterr().err
