"""``guideway-fmu wear``: the case file, the JSON the issue fixes, the profile fit, the plots and
the errors."""
from __future__ import annotations

import json

import numpy as np
import pytest

from guideway_fmu import examples
from guideway_fmu.cli import main
from guideway_fmu.physics.wear import fractal

EXAMPLES = examples.FOLDER / "ball_guides"
LG20 = EXAMPLES / "zhang_wear_lg20_2kN.toml"


def test_json_has_the_fixed_keys_in_si_units(capsys):
    assert main(["wear", str(LG20), "--distance", "5000", "--json", "--points", "11"]) == 0
    result = json.loads(capsys.readouterr().out)
    for key in ("distance", "wear_depth", "preload_deformation", "vertical_displacement"):
        assert len(result[key]) == 11
    assert result["distance"][-1] == 5000.0
    assert result["preload_lost_at"] is None
    assert result["preload_deformation"][0] == pytest.approx(4e-6)
    assert 1e-6 < result["vertical_displacement"][0] < 1e-5  # the elastic sinking, metres
    assert np.all(np.diff(result["wear_depth"]) > 0)


def test_a_minimal_case_takes_the_lg20_defaults(tmp_path, capsys):
    path = tmp_path / "case.toml"
    path.write_text("[load]\nvertical = 2000.0\n")
    assert main(["wear", str(path), "--json", "--points", "3"]) == 0
    minimal = json.loads(capsys.readouterr().out)
    assert main(["wear", str(LG20), "--json", "--points", "3"]) == 0
    assert json.loads(capsys.readouterr().out)["wear_depth"] == pytest.approx(
        minimal["wear_depth"], rel=1e-12)


def test_preload_lost_at_is_reported_when_it_happens_within_the_distance(tmp_path, capsys):
    path = tmp_path / "case.toml"
    path.write_text(LG20.read_text().replace("coefficient = 5e-4", "coefficient = 0.5"))
    assert main(["wear", str(path), "--distance", "5e6", "--json", "--points", "21"]) == 0
    result = json.loads(capsys.readouterr().out)
    lost = result["preload_lost_at"]
    assert lost is not None and 0 < lost < 5e6
    assert np.interp(lost, result["distance"], result["wear_depth"]) == pytest.approx(
        4e-6, rel=5e-3)


def test_profile_gives_the_fractal_parameters_by_the_structure_function(tmp_path, capsys):
    spacing = 1e-7
    x = np.arange(0.0, 1e-2, spacing)
    z = fractal.wm_profile(x, 1.7, 1e-9, lowest=1e2, highest=1e3 / spacing)
    np.savetxt(tmp_path / "profile.csv", np.column_stack([x, z]), delimiter=",",
               header="x,z", comments="")
    path = tmp_path / "case.toml"
    path.write_text('[surface]\nprofile = "profile.csv"\nshortest_lag = 4e-7\n'
                    'longest_lag = 1.03e-5\n[load]\nvertical = 2000.0\n')
    assert main(["wear", str(path), "--json", "--points", "3"]) == 0
    surface = json.loads(capsys.readouterr().out)["surface"]
    assert surface["fractal_dimension"] == pytest.approx(2.7, rel=0.01)
    assert surface["scale"] == pytest.approx(1e-9, rel=0.05)
    assert surface["fit"]["r_squared"] > 0.9


@pytest.mark.slow
def test_plot_draws_the_four_figures(tmp_path, capsys):
    png = tmp_path / "wear.png"
    assert main(["wear", str(LG20), "--distance", "5000", "--plot", str(png)]) == 0
    assert png.stat().st_size > 10_000
    assert "preload lost at no point" in capsys.readouterr().out


@pytest.mark.parametrize("edit, message", [
    (lambda t: t.replace("[load]", "[loads]"), "table [load] is missing"),
    (lambda t: t.replace("conformity = 0.51", "conformity = 0.4"), "conformity"),
    (lambda t: t.replace("balls_per_row = 12", "balls_per_row = 1.5"),
     "[guide] key 'balls_per_row'"),
    (lambda t: t.replace("vertical = 2000.0", 'vertical = "heavy"'), "[load] key 'vertical'"),
    (lambda t: t.replace("[wear]", "[wear]\nspeed = 1"), "unknown [wear] key 'speed'"),
    (lambda t: t.replace("fractal_dimension = 2.8", "fractal_dimension = 3.5"),
     "fractal dimension"),
    (lambda t: t.replace("scale = 2.38e-8", 'profile = "none.csv"'), "profile"),
    (lambda t: t + '\n[surface2]\n', "unknown table(s) [surface2]"),
])
def test_bad_case_file_is_refused_naming_file_and_key(tmp_path, capsys, edit, message):
    path = tmp_path / "case.toml"
    path.write_text(edit(LG20.read_text()))
    assert main(["wear", str(path)]) == 2
    err = capsys.readouterr().err
    assert str(path) in err and message in err, err


def test_bad_profile_rows_are_named(tmp_path, capsys):
    (tmp_path / "profile.csv").write_text("x,z\n" + "".join(
        f"{i * 1e-6},{'nan' if i == 7 else 1e-9 * i}\n" for i in range(40)))
    path = tmp_path / "case.toml"
    path.write_text('[surface]\nprofile = "profile.csv"\n[load]\nvertical = 2000.0\n')
    assert main(["wear", str(path)]) == 2
    err = capsys.readouterr().err
    assert "profile.csv" in err and "row 9" in err, err


@pytest.mark.parametrize("option, message", [(["--distance", "-5"], "--distance"),
                                             (["--points", "1"], "--points")])
def test_bad_options_are_refused_by_name(capsys, option, message):
    assert main(["wear", str(LG20), *option]) == 2
    assert message in capsys.readouterr().err
