"""The discrepancy workflow end to end on synthetic runs with hidden effects (guideway_synthetic/truth.py):
the named effect, diagnosis.json and fit.csv exactly as docs/measured-run.md says,
the report, and the refusals. The diagnoses run in one child process (each co-simulates)."""
from __future__ import annotations

import csv
import json
import re

import numpy as np
import pytest

from guideway_synthetic.trials import run_batch
from guideway_fmu.diagnose.workflow import diagnose

pytestmark = pytest.mark.slow  # end-to-end: co-simulation in a subprocess

CASES = {  # run name -> (hidden effect, seed)
    "presliding": ("presliding_hysteresis", 11),
    "mass": ("unmodeled_mass", 12),
    "quiet": ("none", 13),
    "load": ("normal_load_friction", 14),
}
NUMBER = re.compile(r"^-?\d+(\.\d+)?$")


@pytest.fixture(scope="module")
def results(tmp_path_factory, fmu_dir):
    root = tmp_path_factory.mktemp("diagnose")
    summaries = run_batch(root, fmu_dir, [
        {"name": name, "effect": effect, "seed": seed, "noise": 0.01, "n_samples": 3000}
        for name, (effect, seed) in CASES.items()], timeout=600)
    return root, {s["name"]: s for s in summaries}


@pytest.mark.parametrize("name", list(CASES))
def test_workflow_names_hidden_effect(results, name):
    _, out = results
    assert out[name]["diagnosis"]["missing_effect"] == out[name]["expected"]


def test_diagnosis_json_follows_spec(results):
    root, _ = results
    text = (root / "presliding_out" / "diagnosis.json").read_text()
    d = json.loads(text)
    assert list(d) == ["format", "missing_effect", "confidence", "channel", "gap_before",
                       "gap_after", "noise_floor", "candidates", "equation",
                       "baseline_corrections", "intervals", "missing_effects", "warnings"]
    assert d["format"] == "guideway-diagnosis/1" and d["channel"] == "drive_force"
    assert d["baseline_corrections"] == [] and all(isinstance(w, str) for w in d["warnings"])
    named = next(c["parameters"] for c in d["candidates"] if c["effect"] == d["missing_effect"])
    for key, (low, high) in d["intervals"].items():
        assert low <= named[key] <= high
    assert 0.0 <= d["confidence"] <= 1.0 and d["equation"] is None
    # one effect hidden: the one step is the named effect, its gap and parameters the candidate's
    first = next(c for c in d["candidates"] if c["effect"] == d["missing_effect"])
    assert [list(step) for step in d["missing_effects"]] == [
        ["effect", "gap_after", "score", "parameters", "intervals"]]
    assert {k: d["missing_effects"][0][k] for k in first} == first
    for c in d["candidates"]:
        assert list(c) == ["effect", "gap_after", "score", "parameters"]
    assert "e-" not in text and "e+" not in text and "NaN" not in text  # plain decimals
    assert d["gap_after"] <= 1.3 * d["noise_floor"] < d["gap_before"]


def test_fit_csv_holds_held_out_samples_and_reproduces_the_gaps(results):
    root, _ = results
    d = json.loads((root / "presliding_out" / "diagnosis.json").read_text())
    with (root / "presliding_out" / "fit.csv").open() as handle:
        rows = list(csv.reader(handle))
    assert rows[0] == ["time", "measured", "baseline", "augmented"]
    assert all(NUMBER.match(cell) for row in rows[1:] for cell in row)
    data = np.array(rows[1:], dtype=float)
    assert len(data) >= 0.2 * 3000  # at least 20 % held out
    assert data[0, 0] < 0.1 * data[-1, 0] and data[-1, 0] > 0.9 * 3.0  # spread over the record
    m, span = data[:, 1], np.ptp(data[:, 1])
    assert np.sqrt(np.mean((m - data[:, 2]) ** 2)) / span == pytest.approx(d["gap_before"], rel=1e-5)
    assert np.sqrt(np.mean((m - data[:, 3]) ** 2)) / span == pytest.approx(d["gap_after"], rel=1e-5)


def test_unknown_proposes_an_equation_that_evaluates(results):
    root, out = results
    d = out["load"]["diagnosis"]
    assert d["missing_effect"] == "unknown" and "normal_force" in d["equation"]
    assert d["gap_after"] == d["gap_before"]
    data = np.genfromtxt(root / "load" / "data.csv", delimiter=",", names=True)
    names = {n: data[n] for n in data.dtype.names}
    value = eval(d["equation"], {"sign": np.sign, "sin": np.sin, "cos": np.cos, "pi": np.pi, **names})
    assert np.all(np.isfinite(value))


def test_none_keeps_augmented_equal_to_baseline(results):
    root, out = results
    assert out["quiet"]["diagnosis"]["gap_after"] == out["quiet"]["diagnosis"]["gap_before"]
    assert out["quiet"]["diagnosis"]["missing_effects"] == []
    data = np.genfromtxt(root / "quiet_out" / "fit.csv", delimiter=",", names=True)
    np.testing.assert_array_equal(data["baseline"], data["augmented"])


def test_report_is_self_contained_with_plots_and_augmented_scenario(results):
    root, _ = results
    out = root / "presliding_out"
    html = (out / "report.html").read_text()
    assert html.count("data:image/png;base64,") == 3 and "src='http" not in html
    assert len(list(out.glob("*.png"))) == 3
    scenario = (out / "augmented.toml").read_text()
    assert "FrictionDahl.fmu" in scenario and 'profile = "replay"' in scenario


def test_vertical_kind_with_a_horizontal_channel_is_refused_naming_key(results, tmp_path):
    root, _ = results
    run = tmp_path / "vertical"
    run.mkdir()
    (run / "data.csv").write_text((root / "quiet" / "data.csv").read_text())
    rig = (root / "quiet" / "rig.toml").read_text().replace('"horizontal_drive"', '"vertical_response"')
    (run / "rig.toml").write_text(rig)
    with pytest.raises(ValueError, match=r"rig.toml: \[channels\] key 'outputs'"):
        diagnose(run, tmp_path / "out")


def test_one_way_record_is_refused_naming_the_file(results, tmp_path):
    # with motion one way only, the Coulomb level (times sign v = +1) and the offset are the
    # same regressor: the baseline cannot be calibrated, so the run is refused, not diagnosed
    root, _ = results
    run = tmp_path / "one_way"
    run.mkdir()
    (run / "rig.toml").write_text((root / "quiet" / "rig.toml").read_text())
    data = np.genfromtxt(root / "quiet" / "data.csv", delimiter=",", names=True)
    names = data.dtype.names
    if "feed_position" in names:  # the running distance: the same strokes, all forward
        data["feed_position"] = np.concatenate([[0.0], np.cumsum(np.abs(np.diff(data["feed_position"])))])
    if "feed_velocity" in names:
        data["feed_velocity"] = np.abs(data["feed_velocity"])
    if "feed_acceleration" in names:
        data["feed_acceleration"] = np.gradient(np.abs(data["feed_velocity"]), data["time"])
    np.savetxt(run / "data.csv", np.column_stack([data[n] for n in names]), delimiter=",",
               header=",".join(names), comments="", fmt="%.9g")
    with pytest.raises(ValueError, match=r"data.csv: the feed moves one way only \([\d.]+ m "
                                         r"forward, 0 m backward by the distance travelled"):
        diagnose(run, tmp_path / "out")
