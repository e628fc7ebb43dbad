"""Checks of the truth-model generator: files per the measured-run spec, effect sizes, noise,
encoder quantisation and the truth equations (guideway_synthetic/truth.py)."""
import json
import re
import tomllib

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from guideway_synthetic import truth

VOCABULARY = {"feed_position", "feed_velocity", "feed_acceleration", "drive_force",
              "friction_force", "normal_force", "vertical_displacement", "vertical_acceleration"}
PLAIN = re.compile(r"-?\d+\.\d+")
SMALL = 3000  # samples for the format checks


def read(run_dir):
    """(rig.toml as a dict, its text, data.csv header, data.csv values), checked per the spec."""
    text = (run_dir / "rig.toml").read_text(encoding="utf-8")
    rig = tomllib.loads(text)
    lines = (run_dir / "data.csv").read_text(encoding="utf-8").splitlines()
    header = lines[0].split(",")
    cells = [line.split(",") for line in lines[1:]]
    assert all(len(row) == len(header) for row in cells)
    assert all(PLAIN.fullmatch(cell) for row in cells for cell in row), "plain decimals only"
    return rig, text, header, np.array(cells, dtype=float)


def columns(run_dir):
    """{column: samples} of data.csv."""
    _, _, header, values = read(run_dir)
    return dict(zip(header, values.T))


def moving_fit(y, basis, mask):
    """Least-squares coefficients of y on the basis columns over mask, and the residual."""
    coef = np.linalg.lstsq(basis[mask], y[mask], rcond=None)[0]
    return coef, y[mask] - basis[mask] @ coef


def coulomb_sign(v):
    return np.tanh(v / truth.VELOCITY_TOLERANCE)


@pytest.mark.parametrize("effect", truth.EFFECTS)
def test_files_follow_the_measured_run_spec(tmp_path, effect):
    info = truth.make_run(tmp_path, effect, np.random.default_rng(3), n_samples=SMALL,
                          uneven=effect == "lubrication")
    rig, text, header, values = read(tmp_path)
    assert text.splitlines()[0] == 'format = "guideway-measured-run/1"'
    assert rig["rig"]["kind"] == "horizontal_drive" and rig["rig"]["moving_mass"] > 0
    assert rig["model"] == {"friction": "coulomb", "contact": "dry_hertz"}
    guideway = rig["guideway"]
    assert {"rows", "elements_per_row", "element_radius", "contact_angle_deg",
            "preload"} <= set(guideway)
    assert ("roller_length" in guideway) == (guideway["type"] == "roller")
    if effect == "ball_to_ball_contact":
        assert guideway["type"] == "ball"
    assert effect == "none" or effect not in text, "rig.toml must not reveal the effect"
    numbers = [line.split(" = ")[1] for line in text.splitlines()
               if " = " in line and line.split(" = ")[1][0] not in '"[']
    assert numbers and all(re.fullmatch(r"-?\d+(\.\d+)?", n) for n in numbers)
    # data.csv: time first and strictly increasing, vocabulary only, finite, channels present
    assert header[0] == "time" and set(header[1:]) <= VOCABULARY
    assert len(set(header)) == len(header) and values.shape == (SMALL, len(header))
    assert np.all(np.isfinite(values)) and np.all(np.diff(values[:, 0]) > 0)
    channels = rig["channels"]
    assert channels["outputs"][0] == "drive_force"
    assert set(channels["inputs"]) | set(channels["outputs"]) == set(header[1:])
    assert tuple(header[1:]) == info.channels
    assert ("normal_force" in header) == (effect == "normal_load_friction")
    assert info.expected == ("unknown" if effect in ("normal_load_friction", "mains_disturbance")
                             else effect)
    assert list(tmp_path.iterdir()) and {p.name for p in tmp_path.iterdir()} == {"rig.toml",
                                                                                 "data.csv"}


@pytest.mark.parametrize("effect", ["lubrication", "presliding_hysteresis", "unmodeled_mass",
                                    "preload_loss", "mains_disturbance"])
@pytest.mark.parametrize("size", [1.0, 1.0 / 3.0])
def test_hidden_effect_has_the_requested_size_in_the_file(tmp_path, effect, size):
    # Fit the baseline's free parameters (Coulomb level, offset) to the written force with the
    # stated mass: what is left is the effect's visible part, size * 3 % of the force range.
    run = truth.simulate(effect, np.random.default_rng(11), size=size, noise=0.0)
    truth.write_run(tmp_path, run)
    data, t = columns(tmp_path), run.truth
    mass = tomllib.loads((tmp_path / "rig.toml").read_text())["rig"]["moving_mass"]
    sign = coulomb_sign(t["velocity"])
    basis = np.column_stack([sign, np.ones_like(sign)])
    _, left = moving_fit(data["drive_force"] - mass * t["acceleration"], basis, t["moving"])
    target = size * truth.VISIBLE_FRACTION * np.ptp(mass * t["acceleration"]
                                                    + run.info.parameters["coulomb_level"] * sign)
    assert np.sqrt(np.mean(left ** 2)) == pytest.approx(target, rel=2e-3)
    assert run.info.effect_rms == pytest.approx(target, rel=2e-3)


def test_null_run_is_mass_times_acceleration_plus_coulomb_within_noise(tmp_path):
    run = truth.simulate("none", np.random.default_rng(5), noise=0.01)
    truth.write_run(tmp_path, run)
    data, p, noise_rms = columns(tmp_path), run.info.parameters, run.info.noise_rms
    # with the rig's own (quantised, differentiated) velocity and acceleration channels: the
    # acceleration's quantisation noise adds a little to the force noise
    sign = coulomb_sign(data["feed_velocity"])
    moving = np.abs(data["feed_velocity"]) > 5e-3
    left = data["drive_force"] - p["moving_mass"] * data["feed_acceleration"]
    coef, rest = moving_fit(left, np.column_stack([sign, np.ones_like(sign)]), moving)
    assert coef[0] == pytest.approx(p["coulomb_level"], rel=0.01)
    assert coef[1] == pytest.approx(p["offset"], abs=0.1 * noise_rms)
    assert noise_rms < np.sqrt(np.mean(rest ** 2)) < 1.25 * noise_rms
    # with the true motion, the rest is the noise alone
    t = run.truth
    rest = (data["drive_force"] - p["moving_mass"] * t["acceleration"]
            - p["coulomb_level"] * coulomb_sign(t["velocity"]) - p["offset"])
    assert np.sqrt(np.mean(rest ** 2)) == pytest.approx(noise_rms, rel=0.03)
    assert abs(np.mean(rest)) < 0.05 * noise_rms
    assert p["moving_mass_true"] == p["moving_mass"] and run.info.effect_rms == 0.0


@pytest.mark.parametrize("uneven", [False, True])
@pytest.mark.parametrize("noise", [0.003, 0.015])
def test_noise_rms_matches_the_requested_level(tmp_path, noise, uneven):
    run = truth.simulate("none", np.random.default_rng(8), noise=noise, uneven=uneven)
    truth.write_run(tmp_path, run)
    force = columns(tmp_path)["drive_force"]
    d2 = force[2:] - 2 * force[1:-1] + force[:-2]  # the smooth force drops out
    estimate = 1.4826 * np.median(np.abs(d2 - np.median(d2))) / np.sqrt(6.0)
    clean_range = np.ptp(run.truth["baseline"] + run.truth["hidden"])
    assert estimate / clean_range == pytest.approx(noise, rel=0.06)
    assert run.info.noise_rms == pytest.approx(noise * clean_range)


@pytest.mark.parametrize("step", [1e-6, 1e-5])
def test_position_is_quantised_and_velocity_carries_the_quantisation(tmp_path, step):
    run = truth.simulate("none", np.random.default_rng(2), encoder_step=step, n_samples=4000)
    truth.write_run(tmp_path, run)
    data = columns(tmp_path)
    counts = data["feed_position"] / step
    assert np.allclose(counts, np.round(counts), atol=1e-3)
    jumps = np.abs(np.diff(data["feed_position"]))
    assert jumps[jumps > 0].min() == pytest.approx(step, rel=1e-3)
    error = data["feed_velocity"] - run.truth["velocity"]
    window = 6 / 1000.0  # +-3 samples at 1 kHz
    assert 0.05 * step / window < error.std() < step / window


def test_record_with_velocity_but_no_position(tmp_path):
    info = truth.make_run(tmp_path, "position_dependent_friction", np.random.default_rng(4),
                          with_position=False, with_acceleration=False, n_samples=SMALL)
    rig, _, header, _ = read(tmp_path)
    assert header == ["time", "feed_velocity", "drive_force"]
    assert rig["channels"]["inputs"] == ["feed_velocity"]
    assert info.channels == ("feed_velocity", "drive_force")


def test_uneven_sampling_jitters_the_time_stamps(tmp_path):
    truth.make_run(tmp_path, "none", np.random.default_rng(4), uneven=True, n_samples=SMALL)
    dt = np.diff(columns(tmp_path)["time"])
    assert dt.min() > 0.0003 and dt.max() < 0.0017 and dt.std() / dt.mean() > 0.15


@pytest.mark.parametrize("effect", ["lubrication", "ball_to_ball_contact"])
def test_same_seed_shares_rig_motion_and_noise_whatever_the_effect(effect):
    none = truth.simulate("none", np.random.default_rng(9), n_samples=SMALL)
    other = truth.simulate(effect, np.random.default_rng(9), n_samples=SMALL)
    for name in ("time", "feed_position", "feed_velocity", "feed_acceleration"):
        assert np.array_equal(none.columns[name], other.columns[name])
    assert none.rig["load"] == other.rig["load"]
    assert none.info.parameters["moving_mass"] == other.info.parameters["moving_mass"]
    assert none.info.parameters["offset"] == other.info.parameters["offset"]
    assert np.allclose(none.truth["noise"] / none.info.noise_rms,
                       other.truth["noise"] / other.info.noise_rms)


def dahl_by_integration(x, elements, alpha):
    """Generalised Dahl force [N] along the sampled path x [m], integrated numerically (LSODA)
    over each run of samples of one direction; elements: [(F_c [N], x_c [m]), ...]."""
    direction = np.sign(np.diff(x))
    moves = np.flatnonzero(direction != 0)
    runs = np.split(moves, np.flatnonzero(np.diff(direction[moves]) != 0) + 1)
    total = np.zeros_like(x)
    for f_c, x_c in elements:
        force, state = np.zeros_like(x), 0.0
        for run in runs:
            d, samples = direction[run[0]], np.arange(run[0] + 1, run[-1] + 2)
            reach = d * (x[samples] - x[run[0]])
            rhs = lambda D, F: [f_c / x_c * max(1.0 - d * F[0] / f_c, 0.0) ** alpha * d]
            sol = solve_ivp(rhs, (0.0, reach[-1]), [state], method="BDF", rtol=1e-9,
                            atol=1e-9 * f_c, dense_output=True)
            force[samples] = sol.sol(reach)[0]
            state = force[samples[-1]]
            force[samples[-1] + 1:] = state  # held at standstill until the next run
        total += force
    return total


def test_presliding_truth_is_a_two_element_dahl_model_with_lag_after_reversals():
    run = truth.simulate("presliding_hysteresis", np.random.default_rng(1), n_samples=4000)
    p, t = run.info.parameters, run.truth
    f_c, w = p["coulomb_level"], p["dahl_weight"]
    friction = f_c * coulomb_sign(t["velocity"]) + t["hidden"]
    expected = dahl_by_integration(t["position"], [(w * f_c, p["presliding_distance_1"]),
                                                   ((1 - w) * f_c, p["presliding_distance_2"])],
                                   p["dahl_exponent"])
    assert np.max(np.abs(friction - expected)) < 1e-5 * f_c
    # lag: right after each reversal the friction still points the old way; late in a long
    # stroke it has settled at the Coulomb level
    v, x = t["velocity"], t["position"]
    starts = np.flatnonzero((v[1:] != 0) & (v[:-1] == 0)) + 1
    early, late = [], []
    for k in starts:
        d, stop = np.sign(v[k]), k + np.argmax(np.append(v[k:], 0.0) == 0.0)
        travel = d * (x[k:stop] - x[k - 1])
        early += list(d * friction[k:stop][travel < 0.3 * p["presliding_distance_1"]])
        late += list(d * friction[k:stop][travel > 5e-3])
    assert len(early) > 10 and len(late) > 100
    assert np.mean(early) < 0.0 and np.min(late) > 0.98 * f_c


def test_preload_loss_decays_exponentially_with_running_distance():
    run = truth.simulate("preload_loss", np.random.default_rng(6), n_samples=5000)
    p, t = run.info.parameters, run.truth
    sign = coulomb_sign(t["velocity"])
    level = (p["coulomb_level"] * sign + t["hidden"])[t["moving"]] / sign[t["moving"]]
    law = p["coulomb_level"] * (1 - p["loss_fraction"]
                                * (1 - np.exp(-t["running_distance"] / p["decay_distance"])))
    assert np.allclose(level, law[t["moving"]], rtol=1e-9)
    assert 0 < p["loss_fraction"] < truth.MAX_LOSS and level[-1] < level[0]


def test_position_dependence_repeats_at_the_same_positions_and_ball_contact_does_not():
    for effect, repeats in (("position_dependent_friction", True), ("ball_to_ball_contact", False)):
        run = truth.simulate(effect, np.random.default_rng(7))
        t = run.truth
        sign = coulomb_sign(t["velocity"])
        moving = np.abs(t["velocity"]) > 0.01
        profile = t["hidden"][moving] / sign[moving]
        x = t["position"][moving]
        # friction change at the same position (to 20 um) in different passes
        order = np.argsort(x)
        close = np.abs(np.diff(x[order])) < 2e-5
        spread = np.abs(np.diff(profile[order]))[close]
        if repeats:
            assert np.percentile(spread, 95) < 0.05 * np.std(profile)
        else:
            assert np.all(profile > 0)  # ball contact only ever adds friction
            assert np.percentile(spread, 95) > 0.5 * np.std(profile)


def test_unmodeled_mass_and_the_out_of_vocabulary_effects(tmp_path):
    mass = truth.simulate("unmodeled_mass", np.random.default_rng(12), noise=0.0)
    p, t = mass.info.parameters, mass.truth
    slope = np.polyfit(t["acceleration"], t["hidden"], 1)[0]
    assert slope == pytest.approx(p["missing_mass"]) and slope > 0
    assert p["moving_mass_true"] == pytest.approx(p["moving_mass"] + slope)

    hum = truth.simulate("mains_disturbance", np.random.default_rng(12), noise=0.0)
    q, h = hum.info.parameters, hum.truth
    phase = 2 * np.pi * q["hum_frequency"] * h["time"]
    amp = np.linalg.lstsq(np.column_stack([np.sin(phase), np.cos(phase)]), h["hidden"],
                          rcond=None)[0]
    assert np.hypot(*amp) == pytest.approx(q["hum_amplitude"], rel=0.01)
    assert hum.info.expected == "unknown"

    info = truth.make_run(tmp_path, "normal_load_friction", np.random.default_rng(12))
    data, r = columns(tmp_path), info.parameters
    rig = tomllib.loads((tmp_path / "rig.toml").read_text())
    assert "normal_force" in rig["channels"]["inputs"]
    load = data["normal_force"]
    assert np.ptp(load) > 0.3 * rig["load"]["normal_force"] and load.min() > 0
    sign = coulomb_sign(data["feed_velocity"])
    moving = np.abs(data["feed_velocity"]) > 5e-3
    left = data["drive_force"] - r["moving_mass"] * data["feed_acceleration"]
    coef, _ = moving_fit(left, np.column_stack([sign, sign * load, np.ones_like(sign)]), moving)
    assert coef[1] == pytest.approx(r["load_friction_coefficient"], rel=0.1)
    assert info.expected == "unknown"


def test_make_suite_and_example(tmp_path):
    out = truth.make_suite(tmp_path / "suite", [3, 4], effects=("none", "mains_disturbance"),
                           n_samples=2000, noise=0.005)
    assert [(d.name, i.seed, i.expected) for d, i in out] == [
        ("none_3", 3, "none"), ("mains_disturbance_3", 3, "unknown"),
        ("none_4", 4, "none"), ("mains_disturbance_4", 4, "unknown")]
    index = json.loads((tmp_path / "suite" / "truth.json").read_text())
    assert [e["run"] for e in index] == [d.name for d, _ in out]
    assert index[1]["parameters"]["hum_amplitude"] == out[1][1].parameters["hum_amplitude"]
    for run_dir, _ in out:
        read(run_dir)

    info = truth.write_example(tmp_path / "example")
    assert info.effect == "presliding_hysteresis" and info.effect_rms > 5 * info.noise_rms
    assert truth.write_example(tmp_path / "again") == info
    assert (tmp_path / "example" / "data.csv").read_bytes() == \
        (tmp_path / "again" / "data.csv").read_bytes()


@pytest.mark.parametrize("kwargs, name", [
    ({"effect": "stiction"}, "effect"),
    ({"rng": 3}, "rng"),
    ({"size": 0.0}, "size"),
    ({"size": 5.0}, "size"),
    ({"noise": -0.01}, "noise"),
    ({"noise": float("nan")}, "noise"),
    ({"n_samples": 10}, "n_samples"),
    ({"n_samples": 5000.0}, "n_samples"),
    ({"rate": 10.0}, "rate"),
    ({"with_position": False, "with_velocity": False}, "with_position"),
    ({"encoder_step": -1e-6}, "encoder_step"),
    ({"offset": "zero"}, "offset"),
    ({"derivative_half_window": 0}, "derivative_half_window"),
])
def test_bad_arguments_raise_value_error_naming_the_argument(kwargs, name):
    args = {"effect": "none", "rng": np.random.default_rng(0), **kwargs}
    with pytest.raises(ValueError, match=f"^{name} "):
        truth.simulate(args.pop("effect"), args.pop("rng"), **args)


def test_make_suite_refuses_bad_effects_and_seeds(tmp_path):
    with pytest.raises(ValueError, match="^effects "):
        truth.make_suite(tmp_path, [1], effects=("none", "wear"))
    with pytest.raises(ValueError, match="^seeds "):
        truth.make_suite(tmp_path, [-1])


def test_first_stroke_ends_by_half_the_record_so_every_record_moves_both_ways():
    # 2 s records: a slow first stroke (top speed a tenth of 0.1-0.3 m/s over up to 0.1 m) would
    # fill them; the rule shortens it, and the return stroke starts after at most one dwell
    for seed in range(40):
        run = truth.simulate("none", np.random.default_rng(seed), n_samples=2000)
        t, v = run.truth["time"], run.truth["velocity"]
        assert np.any(v < -truth.MOVING_SPEED)
        assert t[np.argmax(v < 0)] < 0.5 * t[-1] + 0.25
