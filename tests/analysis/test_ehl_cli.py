"""``guideway-fmu ehl`` and ``guideway-fmu ehl-cycle``: numbers, files and errors."""
import csv
import json

import numpy as np
import pytest

from guideway_fmu import scenarios
from guideway_fmu.analysis import ehl as ea
from guideway_fmu.cli import main
from guideway_fmu.physics.roller_guide.ehl import (EHLConvergenceError, LineContactEHL,
                                                   pan_hamrock, solve_steady)
from support import RUN_PARAMETERS, write_run_folder, write_run_summary

CHECK_POINT = ["--W", "1e-4", "--U", "1e-11", "--G", "4500"]
SCENARIO = scenarios.find("soleimanian2020_9000N_9000Hz")


def _json(capsys, argv):
    assert main(argv) == 0
    return json.loads(capsys.readouterr().out)


def test_ehl_json_at_the_check_point_agrees_with_pan_hamrock(capsys):
    d = _json(capsys, ["ehl", *CHECK_POINT, "--json"])
    for key in ("H_c", "H_min", "P_max", "asperity_load_ratio", "friction_coefficient",
                "iterations", "converged"):
        assert key in d
    fit_c, fit_min = pan_hamrock(1e-4, 1e-11, 4500)
    assert d["converged"] and d["iterations"] > 0
    assert d["H_c"] == pytest.approx(fit_c, rel=0.10)
    assert d["H_min"] == pytest.approx(fit_min, rel=0.10)
    assert d["H_c_pan_hamrock"] == pytest.approx(fit_c)
    assert d["asperity_load_ratio"] == 0.0  # smooth by default
    # P_max is p / E': close to the Hertz peak sqrt(W / (2 pi)) at this load
    assert d["P_max"] == pytest.approx(np.sqrt(1e-4 / (2 * np.pi)), rel=0.05)


def test_ehl_average_flow_option_thins_the_film_of_ground_surfaces(capsys):
    # limiting case: eq. 18 (no --peklenik) on the same rough surface; ridges along the motion
    # (gamma = 9) at lambda ~ 1 let the pressure drive more flow, so the film must be thinner
    rough = ["ehl", *CHECK_POINT, "--roughness", "5e-8", "--json"]
    plain = _json(capsys, rough)
    ground = _json(capsys, [*rough, "--peklenik", "9"])
    assert plain["peklenik"] is None and ground["peklenik"] == 9.0
    assert ground["converged"] and ground["H_c"] < 0.8 * plain["H_c"]
    assert main(["ehl", *CHECK_POINT, "--roughness", "5e-8", "--peklenik", "1/3"]) == 0
    assert "Patir-Cheng average flow, gamma = 0.3333" in capsys.readouterr().out
    with pytest.raises(SystemExit) as stop:  # argparse's own exit for an unreadable number
        main(["ehl", *CHECK_POINT, "--roughness", "5e-8", "--peklenik", "1/0"])
    assert stop.value.code == 2
    assert "--peklenik: expected a number or a fraction like 1/3, got '1/0'" in capsys.readouterr().err


def test_ehl_dimensional_input_equals_the_equivalent_dimensionless_one(capsys):
    er, mu = 2e11 * 2.5e-3, 0.195
    dimensional = _json(capsys, ["ehl", "--load", str(1e-4 * er), "--velocity", str(1e-11 * er / mu),
                                 "--pressure-viscosity", str(4500 / 2e11), "--radius", "2.5e-3",
                                 "--json"])
    groups = _json(capsys, ["ehl", *CHECK_POINT, "--json"])
    for key in ("W", "U", "G", "H_c", "H_min", "P_max", "friction_coefficient"):
        assert dimensional[key] == pytest.approx(groups[key], rel=1e-9), key


def test_ehl_table_and_plot(capsys, tmp_path):
    plot = tmp_path / "ehl.png"
    assert main(["ehl", *CHECK_POINT, "--roughness", "3e-8", "--nodes", "513",
                 "--plot", str(plot)]) == 0
    out = capsys.readouterr().out
    assert "central film h_c" in out and "asperity load ratio" in out and str(plot) in out
    assert plot.read_bytes()[:4] == b"\x89PNG"


@pytest.mark.parametrize("argv, words", [
    (["--W", "1e-4", "--U", "1e-11"], ["--G", "missing"]),
    (["--W", "1e-4", "--U", "1e-11", "--G", "4500", "--load", "5e4"], ["--load", "--W"]),
    (["--load", "5e4"], ["--velocity", "missing"]),
    ([], ["--load", "--W"]),
    (["--load", "-5", "--velocity", "0.1"], ["--load", "> 0"]),
    (["--W", "1e-4", "--U", "0", "--G", "4500"], ["--U", "> 0"]),
    (["--W", "1e-4", "--U", "1e-11", "--G", "4500", "--e-reduced=-1e9"], ["--e-reduced", "> 0"]),
    (["--W", "1e-4", "--U", "1e-11", "--G", "4500", "--nodes", "8"], ["nodes", ">= 33"]),
    (["--W", "1e-4", "--U", "1e-11", "--G", "4500", "--peklenik", "9"], ["--peklenik", "--roughness"]),
    (["--W", "1e-4", "--U", "1e-11", "--G", "4500", "--roughness", "1e-8", "--peklenik", "2"],
     ["--peklenik", "1/9", "got 2.0"]),
])
def test_ehl_bad_input_exits_2_naming_the_option(capsys, argv, words):
    assert main(["ehl", *argv]) == 2
    err = capsys.readouterr().err
    assert err.startswith("guideway-fmu ehl: error:")
    for word in words:
        assert word in err


# --- ehl-cycle on synthetic records ----------------------------------------------------------

def _pulse_run(folder):
    """60 samples at 4 us of a load oscillating at 6.6 kHz that lifts off (0 N) part-time."""
    t = np.arange(60) * 4e-6
    load = np.maximum(0.0, 300 + 350 * np.sin(2 * np.pi * 6600 * t))
    return write_run_folder(folder, t, load, np.full(t.size, 0.26), np.full(t.size, 2.4e-7))


def test_select_instants_spread_over_the_oscillation_of_the_largest_peak():
    t = np.arange(200) * 1e-6
    load = np.maximum(0.0, np.sin(2 * np.pi * 1e4 * t)) * (1 + 0.5 * (t > 1e-4))
    chosen = ea.select_instants(t, load, count=4)
    assert [c[0] for c in chosen] == list("ABCD")
    idx = [c[1] for c in chosen]
    peak = int(np.argmax(load))
    assert idx == sorted(idx) and min(idx) < peak < max(idx)
    # the largest pulse (after 0.1 ms) is loaded from sample 100 to 150: instants inside it
    assert 100 < min(idx) and max(idx) < 150 and all(load[i] > 0 for i in idx)
    around = ea.select_instants(t, load, count=3, window=10e-6)
    assert [i for _, i in around] == [peak - 3, peak, peak + 3]
    given = ea.select_instants(t, load, times=[150.4e-6, 20.2e-6])
    assert given == [("A", 20), ("B", 150)]


@pytest.mark.parametrize("kwargs, message", [
    ({"times": [-1e-6]}, "outside the record"),
    ({"times": [1.0]}, "outside the record"),
    ({"count": 27}, "'count'"),
    ({"count": 0}, "'count'"),
    ({"window": -1.0}, "'window'"),
])
def test_select_instants_refuses_bad_choices(kwargs, message):
    t = np.arange(50) * 1e-6
    with pytest.raises(ValueError, match=message):
        ea.select_instants(t, np.sin(t * 1e5) + 1, **kwargs)


def test_ehl_cycle_transient_through_lift_off_compares_central_films(tmp_path, capsys):
    run = _pulse_run(tmp_path / "run")
    out = tmp_path / "cycle"
    assert main(["ehl-cycle", str(run), "--out", str(out), "--count", "3", "--history", "2e-5",
                 "--nodes", "257"]) == 0
    printed = capsys.readouterr().out
    doc = json.loads((out / "instants.json").read_text())
    rows = doc["instants"]
    assert [r["label"] for r in rows] == ["A", "B", "C"]
    for r in rows:
        assert r["status"] == "solved" and r["method"] == "transient" and r["converged"]
        assert r["u_m"] == pytest.approx(0.13)  # |u| / 2
        assert r["load_per_length"] == pytest.approx(r["load"] / 0.008)
        assert r["film_ratio"] == pytest.approx(r["h_analytical"] / r["h_c"])
        assert r["h_c"] == pytest.approx(r["H_c"] * 0.0025)
        assert 5e-8 < r["h_c"] < 1e-6 and r["p_max"] > 0 and r["history"] > 0
        assert r["label"] in printed
    # a heavier load thins the film (A is on the rising flank, B near the peak)
    assert rows[1]["load"] > rows[0]["load"] and rows[1]["h_c"] < rows[0]["h_c"]
    assert doc["units"]["h_c"] == "m" and doc["contact"] == RUN_PARAMETERS
    with (out / "instants.csv").open() as f:
        table = list(csv.DictReader(f))
    assert [r["label"] for r in table] == ["A", "B", "C"]
    assert float(table[1]["film_ratio"]) == pytest.approx(rows[1]["film_ratio"])
    for name in ("load_history.png", "instant_A.png", "instant_B.png", "instant_C.png"):
        assert (out / name).read_bytes()[:4] == b"\x89PNG"


def test_ehl_cycle_steady_load_is_the_steady_solution(tmp_path):
    t = np.arange(5) * 1e-5
    run = write_run_folder(tmp_path / "run", t, np.full(5, 400.0), np.full(5, -0.3),
                           np.full(5, 2e-7))
    instants, files = ea.ehl_cycle(run, tmp_path / "out", times=[4e-5], nodes=513, roughness=0.0)
    (only,) = instants
    contact = LineContactEHL(load=400 / 0.008, radius=0.0025, entrainment_velocity=0.15)
    expected = solve_steady(contact, nodes=513)
    assert only.row["method"] == "steady" and only.row["u_m"] == pytest.approx(0.15)
    assert only.row["h_c"] == pytest.approx(expected.H_c * 0.0025, rel=1e-12)
    assert only.row["film_ratio"] == pytest.approx(2e-7 / only.row["h_c"])
    assert only.row["floored"] is False
    assert len(files) == 4  # json, csv, load history, one instant


def test_ehl_cycle_reports_separation_and_failures_per_instant(tmp_path, monkeypatch, capsys):
    run = _pulse_run(tmp_path / "run")
    times = np.arange(60) * 4e-6
    lifted = float(times[np.nonzero(np.loadtxt(run / "results.csv", delimiter=",",
                                               skiprows=1)[:, 2] == 0)[0][0]])

    def diverge(*args, **kwargs):
        raise EHLConvergenceError("EHL Newton iteration did not converge (test)")

    monkeypatch.setattr(ea, "solve_transient", diverge)
    assert main(["ehl-cycle", str(run), "--out", str(tmp_path / "o"), "--times",
                 f"{lifted},6e-5", "--history", "2e-5"]) == 2  # an instant was not solved
    printed = capsys.readouterr()
    out = printed.out
    rows = json.loads((tmp_path / "o" / "instants.json").read_text())["instants"]
    assert [r["status"] for r in rows] == ["failed", "separated"]
    assert "did not converge (test)" in rows[0]["error"] and "did not converge (test)" in out
    assert rows[1]["h_c"] is None and "roller unloaded" in out
    assert printed.err == ("guideway-fmu ehl-cycle: error: 1 of 2 instants not solved: A (t = "
                           f"6e-05 s); their errors are in {tmp_path / 'o' / 'instants.csv'}\n")


def test_ehl_cycle_writes_what_it_solved_and_exits_2_naming_the_instants_it_could_not(
        tmp_path, capsys):
    # the feed stands still until 40 us: the history of an instant before then starts without
    # entrainment, which has no steady film to start from
    t = np.arange(30) * 4e-6
    u = np.where(t < 4e-5, 0.0, 0.26)
    run = write_run_folder(tmp_path / "run", t, np.full(t.size, 400.0), u, np.full(t.size, 2e-7))
    out = tmp_path / "o"
    assert main(["ehl-cycle", str(run), "--out", str(out), "--times", "2e-5,1.1e-4",
                 "--history", "0", "--nodes", "257"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err
    assert "1 of 2 instants not solved: A (t = 2e-05 s)" in err and "B (" not in err
    rows = json.loads((out / "instants.json").read_text())["instants"]
    assert [r["status"] for r in rows] == ["failed", "solved"]
    assert "entrainment_velocity must be > 0" in rows[0]["error"]
    assert (out / "instant_B.png").is_file() and not (out / "instant_A.png").exists()


@pytest.mark.parametrize("change, words", [
    ("no_results", ["results.csv", "not found"]),
    ("no_column", ["Contact.h_upper", "--instance"]),
    ("no_instance", ["summary.json", "'Contact'"]),
    ("dry_contact", ["viscosity", "lubricated"]),
    ("outside", ["--times", "outside the record"]),
    ("floor", ["--floor"]),
])
def test_ehl_cycle_bad_input_exits_2_with_a_clear_message(tmp_path, capsys, change, words):
    run = _pulse_run(tmp_path / "run")
    argv = ["ehl-cycle", str(run), "--out", str(tmp_path / "o"), "--count", "1"]
    if change == "no_results":
        (run / "results.csv").unlink()
    elif change == "no_column":
        t = np.arange(4) * 1e-6
        write_run_folder(run, t, t + 1, t, t,
                         columns=["time", "Feed.u", "Contact.F_upper", "Carriage.y"])
    elif change == "no_instance":
        write_run_summary(run, {"Carriage": {}})
    elif change == "dry_contact":
        write_run_summary(run, {"Contact": {k: v for k, v in RUN_PARAMETERS.items()
                                            if k != "viscosity"}})
    elif change == "outside":
        argv += ["--times", "0.5"]
    else:
        argv += ["--floor", "0"]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("guideway-fmu ehl-cycle: error:")
    for word in words:
        assert word in err


@pytest.mark.slow
def test_ehl_cycle_on_a_short_real_co_simulation(fmu_dir, tmp_path, capsys):
    run = tmp_path / "run"
    assert main(["run", str(SCENARIO), "--fmus", str(fmu_dir), "--out", str(run), "--stop", "4e-4", "--no-progress"]) == 0
    capsys.readouterr()
    instants, _ = ea.ehl_cycle(run, tmp_path / "cycle", count=2, history=1.2e-5, nodes=257)
    for i in instants:
        r = i.row
        assert r["status"] == "solved", r["error"]
        assert r["load"] > 0 and r["u"] > 0.2  # biharmonic feed near its start
        # the analytical film of the dynamics against the numerical central film
        assert 0.3 < r["film_ratio"] < 3.0


def test_ehl_cycle_retries_each_instant_alone_when_a_shared_march_fails(tmp_path, monkeypatch):
    run = _pulse_run(tmp_path / "run")
    real = ea.solve_transient

    def short_only(contact, times, loads, **kwargs):
        if len(times) > 6:
            raise EHLConvergenceError("the long march failed (test)")
        return real(contact, times, loads, **kwargs)

    monkeypatch.setattr(ea, "solve_transient", short_only)
    instants, _ = ea.ehl_cycle(run, tmp_path / "o", times=[6e-5, 6.8e-5], history=2e-5, nodes=257)
    assert [i.row["status"] for i in instants] == ["solved", "solved"]
    assert [i.row["history"] for i in instants] == pytest.approx([2e-5, 2e-5])
