"""Reading a measured run: every refusal names the file and the row, column, section or key."""
from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from guideway_fmu.diagnose.run_io import load_run
from guideway_fmu.physics.rigs.feed_motion import Replay, make_profile

RIG = """format = "guideway-measured-run/1"
[rig]
kind = "horizontal_drive"
moving_mass = 3.2
[model]
friction = "coulomb"
[channels]
inputs = ["feed_velocity"]
outputs = ["drive_force"]
"""


def write_short_run(tmp_path, rig=RIG, rows=None, header="time,feed_velocity,drive_force"):
    """``rig`` as rig.toml and ``rows`` (default: 60 samples of a sine stroke) under ``header`` as
    data.csv into ``tmp_path``; the folder."""
    t = np.arange(60) * 1e-3
    rows = rows or [f"{a:.4f},{0.1 * np.sin(20 * a):.6f},{np.sign(np.cos(20 * a)):.3f}" for a in t]
    (tmp_path / "rig.toml").write_text(rig)
    (tmp_path / "data.csv").write_text("\n".join([header] + rows) + "\n")
    return tmp_path


def refused(run_dir, *fragments, kind=ValueError):
    with pytest.raises(kind) as info:
        load_run(run_dir)
    for fragment in fragments:
        assert fragment in str(info.value), str(info.value)
    assert "\n" not in str(info.value)


def test_valid_run_is_read(tmp_path):
    run = load_run(write_short_run(tmp_path))
    assert run.channel == "drive_force" and run.time.size == 60


def test_missing_files_name_them(tmp_path):
    refused(tmp_path / "nope", "nope", kind=FileNotFoundError)
    write_short_run(tmp_path)
    (tmp_path / "data.csv").unlink()
    refused(tmp_path, "data.csv", kind=FileNotFoundError)


@pytest.mark.parametrize("cell, text", [("nan", "nan"), ("", "empty cell"), ("inf", "inf"),
                                        ("abc", "abc")])
def test_bad_cell_names_row_and_column(tmp_path, cell, text):
    run = write_short_run(tmp_path)
    lines = (run / "data.csv").read_text().splitlines()
    parts = lines[7].split(",")
    parts[2] = cell
    lines[7] = ",".join(parts)
    (run / "data.csv").write_text("\n".join(lines) + "\n")
    refused(run, "data.csv", "row 8", "column 'drive_force'", text)


def test_non_increasing_time_names_row(tmp_path):
    run = write_short_run(tmp_path)
    lines = (run / "data.csv").read_text().splitlines()
    lines[11] = lines[10]
    (run / "data.csv").write_text("\n".join(lines) + "\n")
    refused(run, "data.csv", "row 12", "column 'time'", "increase")


def test_missing_output_column_names_key(tmp_path):
    refused(write_short_run(tmp_path, header="time,feed_velocity,friction_force"), "rig.toml", "outputs",
            "'drive_force'")


def test_unknown_component_names_key(tmp_path):
    refused(write_short_run(tmp_path, rig=RIG.replace('"coulomb"', '"magic"')), "rig.toml",
            "[model] key 'friction'", "magic")


def test_component_needing_missing_section_names_section_and_key(tmp_path):
    rig = RIG.replace('friction = "coulomb"', 'friction = "mixed_ehl"') + """[guideway]
rows = 4
elements_per_row = 20
element_radius = 2.5e-3
roller_length = 8e-3
preload = 9200.0
"""
    refused(write_short_run(tmp_path, rig=rig), "rig.toml", "[lubricant]")
    rig += "[lubricant]\nviscosity = 0.1\n[surface]\nroughness_rms = 1e-7\n"
    refused(write_short_run(tmp_path, rig=rig), "rig.toml", "'pressure_viscosity'", "[lubricant]")


@pytest.mark.parametrize("entry, key", [("rows = 0", "rows"), ("elements_per_row = 2.5",
                                                                 "elements_per_row"),
                                        ("element_radius = -1e-3", "element_radius"),
                                        ("preload = -5.0", "preload"),
                                        ("contact_angle_deg = 95.0", "contact_angle_deg")])
def test_impossible_guideway_numbers_name_the_key(tmp_path, entry, key):
    # a zero row count would divide the preload by zero further on
    refused(write_short_run(tmp_path, RIG + f"[guideway]\n{entry}\n"), "rig.toml", f"[guideway] key '{key}'")


def test_bad_format_and_mass_name_key(tmp_path):
    refused(write_short_run(tmp_path, rig=RIG.replace("/1", "/2")), "rig.toml", "'format'")
    refused(write_short_run(tmp_path, rig=RIG.replace("3.2", "-1.0")), "rig.toml", "moving_mass")


def test_column_outside_vocabulary_warns_naming_it(tmp_path):
    t = np.arange(60) * 1e-3
    rows = [f"{a:.4f},{0.1 * np.sin(20 * a):.6f},1.0,{a}" for a in t]
    with pytest.warns(UserWarning, match="temperature"):
        run = load_run(write_short_run(tmp_path, rows=rows, header="time,feed_velocity,drive_force,temperature"))
    assert "temperature" not in run.columns


def test_replay_profile_reproduces_samples_and_interpolates_by_hand(tmp_path):
    path = tmp_path / "replay.csv"
    path.write_text("time,feed_position,feed_velocity,feed_acceleration\n"
                    "0,0,1,2\n1,1,3,2\n2,5,3,0\n")
    replay = make_profile("replay", path=str(path))
    assert replay == Replay((0, 1, 2), (0, 1, 5), (1, 3, 3), (2, 2, 0))
    x, u, a = replay.evaluate(np.array([0.5, 1.5, 3.0]))
    np.testing.assert_allclose(x, [0.5, 3.0, 5.0])
    np.testing.assert_allclose(u, [2.0, 3.0, 3.0])
    np.testing.assert_allclose(a, [2.0, 1.0, 0.0])


def test_replay_from_csv_refusal_names_row_and_column(tmp_path):
    path = tmp_path / "replay.csv"
    path.write_text("time,feed_position,feed_velocity,feed_acceleration\n0,0,1,2\n1,x,3,2\n")
    with pytest.raises(ValueError, match="row 3, column 'feed_position'"):
        Replay.from_csv(path)


# -- the sign of friction_force -----------------------------------------------------------------
def _friction_record(tmp_path, name, sign, stated):
    """A pre-sliding run turned into a friction_force record (moving mass 0): the drive force
    less m a, times ``sign`` (-1: opposing the motion), with friction_sign stated or not."""
    from guideway_synthetic import truth
    run = truth.simulate("presliding_hysteresis", np.random.default_rng(11), noise=0.005,
                         n_samples=3000)
    mass = run.info.parameters["moving_mass"]
    friction = run.columns["drive_force"] - mass * run.truth["acceleration"]
    columns = {k: v for k, v in run.columns.items() if k != "drive_force"}
    columns["friction_force"] = sign * friction
    rig = {**run.rig, "rig": {**run.rig["rig"], "moving_mass": 0.0},
           "channels": {**run.rig["channels"], "outputs": ["friction_force"]}}
    if stated:
        rig["channels"]["friction_sign"] = "opposes_motion" if sign < 0 else "along_motion"
    return truth.write_run(tmp_path / name, replace(run, columns=columns, rig=rig))


@pytest.mark.parametrize("sign, stated", [(1.0, False), (-1.0, False), (-1.0, True)])
def test_friction_force_in_either_sign_convention_names_the_same_effect(tmp_path, sign, stated):
    from guideway_fmu.diagnose import decide
    from guideway_fmu.diagnose.report import describe_friction_sign
    named = decide.decide(_friction_record(tmp_path, "run", sign, stated))
    assert named.effect == "presliding_hysteresis"
    run = named.run
    assert run.friction_sign == ("opposes_motion" if sign < 0 else "along_motion")
    assert run.channel_sign == sign
    words = describe_friction_sign(run)
    assert ("as [channels] friction_sign states" in words) == stated
    assert ("found from the data" in words) != stated


def test_stated_friction_sign_wins_over_the_data(tmp_path):
    # stated wrongly: the workflow believes the file, the Coulomb level then fits negative
    from guideway_fmu.diagnose import decide
    path = _friction_record(tmp_path, "run", -1.0, stated=False)
    text = (path / "rig.toml").read_text().replace(
        "[channels]", '[channels]\nfriction_sign = "along_motion"')
    (path / "rig.toml").write_text(text)
    with pytest.raises(ValueError, match="friction_force"):
        decide.decide(path)


@pytest.mark.parametrize("edit, message", [
    (lambda t: t.replace("[channels]", '[channels]\nfriction_sign = "backwards"'),
     "friction_sign' must be one of"),
])
def test_bad_friction_sign_is_refused_naming_the_key(tmp_path, edit, message):
    path = _friction_record(tmp_path, "run", 1.0, stated=False)
    (path / "rig.toml").write_text(edit((path / "rig.toml").read_text()))
    with pytest.raises(ValueError, match=message):
        load_run(path)


def test_friction_sign_without_a_friction_channel_is_refused(tmp_path):
    from guideway_synthetic import truth
    path = truth.write_run(tmp_path / "run", truth.simulate("none", np.random.default_rng(3),
                                                           n_samples=1000))
    text = (path / "rig.toml").read_text().replace(
        "[channels]", '[channels]\nfriction_sign = "opposes_motion"')
    (path / "rig.toml").write_text(text)
    with pytest.raises(ValueError, match="goes with a friction_force channel"):
        load_run(path)


@pytest.mark.parametrize("name", ["data.csv", "rig.toml"])
def test_a_file_that_is_not_utf8_names_its_line_and_byte(tmp_path, name):
    run = write_short_run(tmp_path)
    path = run / name
    lines = path.read_bytes().split(b"\n")
    lines[2] = lines[2] + b" \xe9"  # a Latin-1 e-acute on line 3
    path.write_bytes(b"\n".join(lines))
    refused(run, name, "line 3", "byte 0xe9 is not UTF-8")


# -- units: refused where they cannot be SI, warned about where unusual --------------------------
def _scaled_record(tmp_path, scale: dict, **knobs):
    """A first-generator record with the columns of ``scale`` multiplied by their factors."""
    from guideway_synthetic import truth
    run = truth.simulate("none", np.random.default_rng(5), n_samples=2000, **knobs)
    columns = {k: v * scale.get(k, 1.0) for k, v in run.columns.items()}
    return truth.write_run(tmp_path / "run", replace(run, columns=columns))


@pytest.mark.parametrize("knobs", [{}, {"with_position": False, "with_acceleration": False}])
def test_time_in_milliseconds_is_refused_naming_the_likely_unit(tmp_path, knobs):
    # before: read as seconds, the record was diagnosed as unmodeled_mass with confidence 1
    refused(_scaled_record(tmp_path, {"time": 1e3}, **knobs), "data.csv", "'time'",
            "milliseconds")


def test_position_in_millimetres_is_refused_naming_the_column(tmp_path):
    refused(_scaled_record(tmp_path, {"feed_position": 1e3}), "data.csv", "'feed_position'",
            "millimetres")
    refused(_scaled_record(tmp_path, {"feed_position": 1e3}, with_velocity=False,
                           with_acceleration=False), "data.csv", "'feed_position'", "millimetres")


def test_velocity_in_mm_per_second_is_refused(tmp_path):
    refused(_scaled_record(tmp_path, {"feed_velocity": 1e3}, with_position=False,
                           with_acceleration=False), "data.csv", "'feed_velocity'", "mm/s")


def test_velocity_against_the_position_sign_is_refused(tmp_path):
    refused(_scaled_record(tmp_path, {"feed_velocity": -1.0, "feed_acceleration": -1.0}),
            "data.csv", "'feed_position' and 'feed_velocity'", "opposite")


def test_friction_force_in_millinewtons_is_refused_against_the_load(tmp_path):
    path = _friction_record(tmp_path, "run", 1.0, stated=False)
    text = (path / "data.csv").read_text().splitlines()
    rows = [",".join(cells[:-1] + [f"{1e3 * float(cells[-1]):.3f}"])
            for cells in (line.split(",") for line in text[1:])]
    (path / "data.csv").write_text("\n".join(text[:1] + rows) + "\n")
    refused(path, "data.csv", "'friction_force'", "normal load", "mN")


def test_vertical_displacement_in_millimetres_is_refused_against_the_element_radius(tmp_path):
    rig = RIG.replace('"horizontal_drive"', '"vertical_response"').replace(
        '["drive_force"]', '["vertical_displacement"]') + "[guideway]\nelement_radius = 2.5e-3\n"
    t = np.arange(60) * 1e-3
    rows = [f"{a:.4f},{0.1 * np.sin(20 * a):.6f},{1e-3 * np.sin(900 * a):.6f}" for a in t]  # 1 um in mm
    path = write_short_run(tmp_path, rig=rig, rows=rows, header="time,feed_velocity,vertical_displacement")
    refused(path, "data.csv", "'vertical_displacement'", "element_radius", "mm")
    rows = [f"{a:.4f},{0.1 * np.sin(20 * a):.6f},{1e-6 * np.sin(900 * a):.9f}" for a in t]
    assert load_run(write_short_run(tmp_path, rig=rig, rows=rows,
                          header="time,feed_velocity,vertical_displacement")).time.size == 60


def test_slightly_inconsistent_derivative_and_slow_sampling_warn_naming_the_columns(tmp_path):
    with pytest.warns(UserWarning, match="'feed_position' and 'feed_velocity' disagree"):
        run = load_run(_scaled_record(tmp_path, {"feed_velocity": 1.5, "feed_acceleration": 1.5}))
    assert any("feed_velocity" in note for note in run.warnings)
    with pytest.warns(UserWarning, match="samples 0.2 s apart"):
        load_run(_scaled_record(tmp_path, {"time": 200.0}, with_velocity=False,
                                with_acceleration=False))
