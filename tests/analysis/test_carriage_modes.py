"""``guideway-fmu modes``: the carriage file, its errors, and the shipped examples against
Wu et al. (2012) Table 3."""
from __future__ import annotations

import json

import numpy as np
import pytest

from guideway_fmu import examples
from guideway_fmu.analysis import carriage_modes
from guideway_fmu.cli import main

EXAMPLES = examples.FOLDER / "ball_guides"
BASE = """[carriage]
mass = 0.313
inertia = [9.938e-5, 6.136e-5, 1.394e-4]
contact_angle_deg = 45.0
d = 7.37e-3
e = 10.3e-3
[balls]
per_row = 9
pitch = 4.7778e-3
"""
HERTZ = "diameter = 4.763e-3\nconformity = 0.534\npreload = 46.6\n"


def test_modes_json_of_table2_at_rest_reproduces_table3_published_numbers(capsys):
    assert main(["modes", str(EXAMPLES / "wu2012_table2_moment_0.toml"), "--json"]) == 0
    modes = json.loads(capsys.readouterr().out)["modes"]
    assert [m["label"] for m in modes] == ["rigid", "yawing", "pitching", "vertical", "rolling"]
    assert modes[0]["frequency_hz"] == 0.0
    np.testing.assert_allclose([m["frequency_hz"] for m in modes[1:]],
                               [2.10e3, 3.16e3, 3.60e3, 5.08e3], rtol=0.01)
    for m in modes:
        assert sum(m["participation"].values()) == pytest.approx(1.0)


def test_hertz_example_under_moment_couples_pitch_and_vertical_published_numbers(capsys):
    assert main(["modes", str(EXAMPLES / "wu2012_hertz_moment_2p9.toml"), "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    np.testing.assert_allclose([m["frequency_hz"] for m in result["modes"][1:]],
                               [2.03e3, 2.99e3, 3.66e3, 5.03e3], rtol=0.015)  # 1.1 % at most
    assert result["modes"][2]["label"] == "pitching-vertical"
    k = result["ball_stiffness"]["row_1"]
    assert max(k) > 17.8e6 > min(k)  # the moment loads one end of the rows, unloads the other
    assert result["displacement"]["theta"] > 0.0


def test_text_output_lists_the_modes(capsys):
    assert main(["modes", str(EXAMPLES / "wu2012_table2_moment_0.toml")]) == 0
    out = capsys.readouterr().out
    assert "yawing" in out and "rigid" in out and "3600" in out


@pytest.mark.parametrize("text, words", [
    (BASE.replace("mass = 0.313\n", ""), ["[carriage] key 'mass'", "missing"]),
    (BASE.replace("mass = 0.313", "mass = -1.0"), ["'mass'", "> 0"]),
    (BASE.replace("[9.938e-5, 6.136e-5, 1.394e-4]", "[1e-4, 1e-4]"), ["'inertia'", "J_x, J_y, J_z"]),
    (BASE.replace("45.0", "95.0"), ["'contact_angle_deg'", "(0, 90)"]),
    (BASE.replace("per_row = 9", "per_row = 2.5") + HERTZ, ["'per_row'", "whole number"]),
    (BASE + "stiffness = [1e7, 1e7]\n", ["'stiffness'", "9 values"]),
    (BASE + "stiffness = [1e7, 1e7, 1e7, 1e7, 1e7, 1e7, 1e7, 1e7, 1e7]\n" + HERTZ, ["not both"]),
    (BASE + "diameter = 4.763e-3\n", ["missing conformity, preload"]),
    (BASE + HERTZ.replace("0.534", "0.45"), ["[balls]", "conformity must be > 0.5"]),
    (BASE + HERTZ + "[load]\nmoment_y = 200.0\n", ["[load]", "more than the balls can carry"]),
    (BASE + HERTZ + "[load]\nforce_y = 10.0\n", ["[load]", "no ball resists"]),
    (BASE + HERTZ + "[load]\nmoment_q = 1.0\n", ["unknown [load] key 'moment_q'"]),
    (BASE + "stiffness = [1e7, 1e7, 1e7, 1e7, 1e7, 1e7, 1e7, 1e7, 1e7]\n[load]\nmoment_y = 1.0\n",
     ["[load] needs the Hertz route"]),
    ("[carriage\n", ["not valid TOML"]),
])
def test_bad_carriage_file_exits_2_naming_file_table_and_key(tmp_path, capsys, text, words):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    assert main(["modes", str(path)]) == 2
    err = capsys.readouterr().err
    assert "bad.toml" in err and "Traceback" not in err
    for word in words:
        assert word in err


def test_missing_file_is_named(tmp_path, capsys):
    assert main(["modes", str(tmp_path / "none.toml")]) == 2
    assert "none.toml" in capsys.readouterr().err


def test_reader_and_analysis_agree_with_the_physics_directly():
    case = carriage_modes.read_carriage(EXAMPLES / "wu2012_table2_moment_0.toml")
    assert case.per_row == 9 and case.stiffness == (17.8e6,) * 9 and not np.any(case.load)


def test_each_mode_compresses_the_balls_as_its_motion_does_and_plots(tmp_path, capsys):
    # Geometry of eq. A3 (approach g . q): a vertical translation compresses every ball alike;
    # roll (with the lateral shift of the rolling mode) the two rows oppositely, alike along
    # them; pitch and yaw in proportion to the ball's position l, yaw oppositely in the rows.
    plot = tmp_path / "modes.png"
    assert main(["modes", str(EXAMPLES / "wu2012_table2_moment_0.toml"), "--json",
                 "--plot", str(plot)]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["plot"] == str(plot) and plot.read_bytes()[:4] == b"\x89PNG"
    l = np.asarray(result["ball_positions"])
    shapes = {m["label"]: (np.asarray(m["ball_approach"]["row_1"]),
                           np.asarray(m["ball_approach"]["row_2"])) for m in result["modes"]}
    one, two = shapes["vertical"]
    np.testing.assert_allclose(np.abs(one), 1.0)
    np.testing.assert_allclose(two, one)
    one, two = shapes["rolling"]
    np.testing.assert_allclose(np.abs(one), 1.0)
    np.testing.assert_allclose(two, -one)
    for label, sign in (("pitching", 1.0), ("yawing", -1.0)):
        one, two = shapes[label]
        np.testing.assert_allclose(one, one[0] * l / l[0], atol=1e-9)
        np.testing.assert_allclose(two, sign * one, atol=1e-9)
    assert not np.any(shapes["rigid"])  # it stretches no ball
    assert main(["modes", str(EXAMPLES / "wu2012_table2_moment_0.toml"), "--plot",
                 str(tmp_path / "text.png")]) == 0
    assert capsys.readouterr().out.strip().endswith(f"plot: {tmp_path / 'text.png'}")
