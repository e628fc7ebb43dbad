"""``guideway-fmu ball-to-ball``: the case file, its errors and the two shipped cases."""
from __future__ import annotations

import json
from dataclasses import replace

import numpy as np
import pytest

from guideway_fmu import examples
from guideway_fmu.analysis import ball_to_ball
from guideway_fmu.cli import main

EXAMPLES = examples.FOLDER / "ball_guides"
CASE_A = EXAMPLES / "lin2019_case_a.toml"


def test_case_a_json_has_both_models_with_the_published_contact_forces(capsys):
    assert main(["ball-to-ball", str(CASE_A), "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    for model, published in (("analytical", 3.74), ("numerical", 4.01)):
        assert len(result[model]["epsilon"]) == 2
        assert result[model]["contact_force"] == pytest.approx(published, rel=0.03)
        assert result[model]["friction_loss"] > 0


def test_case_b_text_output_shows_no_contact(capsys):
    assert main(["ball-to-ball", str(EXAMPLES / "lin2019_case_b.toml")]) == 0
    out = capsys.readouterr().out
    assert "contact force [N]" in out and "0.0000       0.0000" in out


def test_per_ball_deviations_are_read_ball_by_ball(tmp_path, capsys):
    # ball 2 alone has the bottom deviation: ball 1 rolls at v/2, ball 2 does not
    text = CASE_A.read_text().replace("BL = -2.0", "BL = [0.0, -2.0]").replace(
        "BR = 2.0 ", "BR = [0.0, 2.0]")
    path = tmp_path / "case.toml"
    path.write_text(text)
    assert main(["ball-to-ball", str(path), "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["numerical"]["epsilon"][0] == pytest.approx(0.0, abs=1e-9)
    assert result["numerical"]["epsilon"][1] != pytest.approx(0.0, abs=1e-4)


@pytest.mark.parametrize("edit, message", [
    (lambda t: t.replace("[motion]", "[moving]"), "table [motion] is missing"),
    (lambda t: t.replace("conformity = 0.56", "conformity = 0.4"), "conformity"),
    (lambda t: t.replace("BL = -2.0", "BL = [1.0, 2.0, 3.0]"), "[contact] key 'BL'"),
    (lambda t: t.replace("side_ratio = -0.6", "side_ratio = -1.5"), "two-point contact"),
    (lambda t: t.replace("normal = 100.0", "normal = -5.0"), "[load] key 'normal'"),
    (lambda t: t.replace("[ball]", "[ball]\nmass = 1"), "unknown [ball] key 'mass'"),
])
def test_bad_case_file_is_refused_naming_file_and_key(tmp_path, capsys, edit, message):
    path = tmp_path / "case.toml"
    path.write_text(edit(CASE_A.read_text()))
    assert main(["ball-to-ball", str(path)]) == 2
    err = capsys.readouterr().err
    assert str(path) in err and message in err, err


def test_the_side_ratio_sweep_passes_through_the_case_and_plots(tmp_path, capsys):
    plot = tmp_path / "b2b.png"
    assert main(["ball-to-ball", str(CASE_A), "--json", "--plot", str(plot)]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["plot"] == str(plot) and plot.read_bytes()[:4] == b"\x89PNG"
    case = ball_to_ball.read_case(CASE_A)
    sweep = ball_to_ball.side_ratio_sweep(case, points=5)  # rho = -0.95, ..., 0.95 (tan 45 deg)
    np.testing.assert_allclose(sweep["side_ratio"], [-0.95, -0.475, 0.0, 0.475, 0.95])
    # without a side load both diagonals of a ball carry alike, and the bottom groove's
    # deviations of case (a), -2 and +2 deg, cancel in eq. 22: neither ball is faster
    assert sweep["analytical"]["contact_force"][2] == pytest.approx(0.0, abs=1e-12)
    assert sweep["numerical"]["contact_force"][2] == pytest.approx(0.0, abs=1e-9)
    # next to two-point contact the numerical model refuses (a contact unloads), the
    # analytical one does not know
    assert sweep["numerical"]["contact_force"][0] is None
    assert sweep["analytical"]["contact_force"][0] > 0
    at_case = ball_to_ball.side_ratio_sweep(replace(case, side_ratio=0.0), points=3)
    assert at_case["numerical"]["groove_loss"][1] == pytest.approx(
        ball_to_ball.analyse(replace(case, side_ratio=0.0))["numerical"]["groove_loss"], rel=1e-9)
