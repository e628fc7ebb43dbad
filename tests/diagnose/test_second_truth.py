"""The second, independent generator of synthetic measured runs (guideway_synthetic/second_truth.py):
format, determinism, and physics checked against closed-form results."""
import math
import re
import warnings

import numpy as np
import pytest

from guideway_synthetic import second_truth as st
from guideway_fmu.diagnose.run_io import load_run

N = 2000  # samples per record in these tests (draw's default is 10000)
PLAIN_DECIMAL = re.compile(r"^-?\d+\.\d+$")
COMBINATIONS = [(e, c) for e in st.EFFECTS for c in st.CLASSES if st.allowed(e, c)]


def _load(path):
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # every column must be in the format's vocabulary
        return load_run(path)


def _velocity(run):
    if "feed_velocity" in run.columns:
        return run.columns["feed_velocity"]
    return np.gradient(run.columns["feed_position"], run.time)


def _visible_rms(values, velocity):
    """RMS of ``values`` after a least-squares fit of c1 sgn(v) + c0, on samples moving at 2 % of
    the top speed or more."""
    moving = np.abs(velocity) >= 0.02 * np.max(np.abs(velocity))
    basis = np.column_stack([np.sign(velocity[moving]), np.ones(np.sum(moving))])
    residual = values[moving] - basis @ np.linalg.lstsq(basis, values[moving], rcond=None)[0]
    return float(np.sqrt(np.mean(residual ** 2)))


# ----------------------------------------------------------------------------- format


@pytest.mark.parametrize("effect,record_class", COMBINATIONS)
def test_every_allowed_combination_writes_a_run_load_run_accepts(tmp_path, effect, record_class):
    seed = COMBINATIONS.index((effect, record_class))
    truth = st.draw(tmp_path, effect, record_class, seed, n_samples=N)
    run = _load(tmp_path)
    assert (truth.effect, truth.expected, truth.record_class) == (effect, st.EFFECTS[effect],
                                                                  record_class)
    assert run.kind == "horizontal_drive" and run.time.size == N
    assert run.model == {"friction": "coulomb", "contact": "dry_hertz"}
    assert run.outputs == [truth.channel]
    assert set(run.columns) == set(run.inputs) | {truth.channel}
    if record_class in st.DRIVE_CLASSES:
        assert truth.channel == "drive_force" and 2.0 <= run.moving_mass <= 25.0
        assert truth.friction_sign is None and not run.friction_sign_stated
    else:
        assert truth.channel == "friction_force" and run.moving_mass == 0.0
        assert truth.friction_sign in ("along_motion", "opposes_motion")
        assert run.friction_sign == (truth.friction_sign if run.friction_sign_stated else None)
    motion = {"velocity_only": ["feed_velocity"], "position_only": ["feed_position"]}
    if record_class in motion:
        assert [c for c in run.inputs if c.startswith("feed_")] == motion[record_class]
    assert ("normal_force" in run.inputs) == (effect == "load_dependent_friction")
    guideway = run.sections["guideway"]
    assert guideway["rows"] == 4 and 10 <= guideway["elements_per_row"] <= 30
    assert 1.5e-3 <= guideway["element_radius"] <= 4e-3 and guideway["contact_angle_deg"] == 45.0
    assert 300.0 <= guideway["preload"] <= 5000.0
    assert ("roller_length" in guideway) == (guideway["type"] == "roller")
    if effect == "ball_to_ball_contact":
        assert guideway["type"] == "ball"
    cells = [cell for line in (tmp_path / "data.csv").read_text().splitlines()[1:]
             for cell in line.split(",")]
    assert all(PLAIN_DECIMAL.match(cell) for cell in cells)
    assert all(isinstance(v, float) for v in truth.parameters.values())
    assert (truth.effect_rms == 0.0) == (effect == "none")


@pytest.mark.parametrize("record_class", ["friction_along", "friction_opposes", "tribometer"])
def test_a_missing_mass_cannot_hide_where_friction_is_measured(tmp_path, record_class):
    with pytest.raises(ValueError, match=record_class):
        st.draw(tmp_path, "unmodeled_mass", record_class, seed=1, n_samples=N)


def test_ball_to_ball_contact_is_not_drawn_on_tribometer_strokes(tmp_path):
    with pytest.raises(ValueError, match="far shorter than a ball"):
        st.draw(tmp_path, "ball_to_ball_contact", "tribometer", seed=1, n_samples=N)


@pytest.mark.parametrize("arguments,name", [
    (("stiction", "drive", 1, 1.0, N), "effect"),
    (("none", "rig", 1, 1.0, N), "record_class"),
    (("none", "drive", -1, 1.0, N), "seed"),
    (("none", "drive", 1.5, 1.0, N), "seed"),
    (("none", "drive", 1, -0.5, N), "size"),
    (("none", "drive", 1, math.nan, N), "size"),
    (("none", "drive", 1, 1.0, 20), "n_samples"),
])
def test_bad_arguments_raise_naming_the_argument(tmp_path, arguments, name):
    effect, record_class, seed, size, n_samples = arguments
    with pytest.raises(ValueError, match=name):
        st.draw(tmp_path, effect, record_class, seed, size=size, n_samples=n_samples)


def test_a_size_beyond_the_physical_bound_raises_naming_size(tmp_path):
    with pytest.raises(ValueError, match="size"):
        st.draw(tmp_path, "preload_loss", "drive", 1, size=100.0, n_samples=N)


def test_unknown_answers_are_the_two_out_of_vocabulary_effects():
    assert sorted(e for e, answer in st.EFFECTS.items() if answer == "unknown") == \
        ["load_dependent_friction", "periodic_disturbance"]


# ----------------------------------------------------------------------------- determinism


@pytest.mark.parametrize("effect,record_class", [("presliding_hysteresis", "bursty"),
                                                 ("load_dependent_friction", "tribometer")])
def test_the_same_seed_gives_the_same_bytes(tmp_path, effect, record_class):
    first, second = st.draw(tmp_path / "a", effect, record_class, 5, n_samples=N), \
        st.draw(tmp_path / "b", effect, record_class, 5, n_samples=N)
    st.draw(tmp_path / "c", effect, record_class, 6, n_samples=N)
    for name in ("rig.toml", "data.csv"):
        assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes()
    assert (tmp_path / "a" / "data.csv").read_bytes() != (tmp_path / "c" / "data.csv").read_bytes()
    assert first == second


# ----------------------------------------------------------------------------- friction laws


def test_lugre_steady_sliding_is_its_stribeck_curve():
    lugre = st.LuGre(sigma0=1e5, sigma1=300.0, sigma2=40.0, coulomb=10.0, static=15.0,
                     stribeck_velocity=1e-3)
    for speed in (-2e-2, -1e-3, -1e-4, 1e-4, 1e-3, 2e-2):
        time = np.linspace(0.0, 0.05 / abs(speed), 20001)  # 5 cm: 300 pre-sliding distances
        velocity = np.full(time.size, speed)
        z = lugre.bristle(speed * time, velocity)
        tustin = math.copysign(10.0 + 5.0 * math.exp(-abs(speed) / 1e-3), speed)
        assert lugre.force(z[-1], speed) == pytest.approx(tustin + 40.0 * speed, rel=1e-9)


def test_lugre_presliding_follows_the_dahl_exponential_on_any_grid():
    """With a constant level the bristle equation is rate independent (Dahl): from rest
    z = z_s (1 - exp(-x / z_s)); after a reversal at z_r, z = -z_s + (z_r + z_s) exp(-d / z_s)."""
    lugre = st.LuGre(sigma0=2e6, sigma1=0.0, sigma2=0.0, coulomb=8.0, static=8.0,
                     stribeck_velocity=1.0)
    z_s = 8.0 / 2e6
    phase = np.linspace(0.0, 2 * np.pi, 37)  # coarse: about 0.4 z_s per step near the peak
    position = 5 * z_s * (1 - np.cos(phase)) / 2  # out to 5 z_s and back
    velocity = 5 * z_s * np.sin(phase) / 2
    z = lugre.bristle(position, velocity)
    out, back = phase <= np.pi, phase >= np.pi
    assert z[out] == pytest.approx(z_s * (1 - np.exp(-position[out] / z_s)), rel=1e-12, abs=1e-18)
    z_r = z_s * (1 - math.exp(-5.0))
    expected = -z_s + (z_r + z_s) * np.exp(-(5 * z_s - position[back]) / z_s)
    assert z[back] == pytest.approx(expected, rel=1e-12)
    assert lugre.force(z[18], 0.0) == pytest.approx(8.0 * (1 - math.exp(-5.0)))


def test_rational_stribeck_curve_limits():
    def friction(v):
        return st.stribeck_rational(v, coulomb=10.0, static=16.0, stribeck_velocity=0.01,
                                    exponent=2.0, viscous=50.0)
    assert friction(1e-12) == pytest.approx(16.0)
    assert friction(0.01) == pytest.approx(10.0 + 3.0 + 0.5)  # half the fall at v_s
    assert friction(10.0) == pytest.approx(10.0 + 500.0, rel=1e-5)
    assert friction(-0.02) == pytest.approx(-friction(0.02))


# ----------------------------------------------------------------------------- record classes


def test_tribometer_strokes_span_50_to_500_um_and_dwell_at_reversals(tmp_path):
    for seed in range(8):
        truth = st.draw(tmp_path / str(seed), "none", "tribometer", seed, n_samples=1000)
        run = _load(tmp_path / str(seed))
        x = run.columns["feed_position"]
        assert 50e-6 <= (x.max() - x.min()) / 2 <= 500e-6
        for end in (x.max(), x.min()):
            at_end = np.flatnonzero(np.abs(x - end) < 1e-12)
            assert at_end.size >= 10 and np.any(np.diff(at_end) == 1)  # held there: a dwell
        assert 5e-5 <= truth.noise_rms / np.ptp(run.columns["friction_force"]) <= 2e-3


def test_the_two_friction_sign_conventions_are_exact_negatives(tmp_path):
    for seed in range(4):
        along, opposes = tmp_path / f"a{seed}", tmp_path / f"o{seed}"
        truth_a = st.draw(along, "position_dependent_friction", "friction_along", seed, n_samples=N)
        truth_o = st.draw(opposes, "position_dependent_friction", "friction_opposes", seed,
                          n_samples=N)
        run_a, run_o = _load(along), _load(opposes)
        assert np.array_equal(run_a.columns["friction_force"], -run_o.columns["friction_force"])
        for name in set(run_a.columns) - {"friction_force"}:
            assert np.array_equal(run_a.columns[name], run_o.columns[name])
        assert (truth_a.friction_sign, truth_o.friction_sign) == ("along_motion", "opposes_motion")
        resisting = np.mean(run_a.columns["friction_force"] * np.sign(_velocity(run_a)))
        assert resisting > 0.5 * truth_a.parameters["coulomb_level"]  # along the motion


def test_bursty_timing_has_microsecond_clusters_and_millisecond_gaps(tmp_path):
    for seed in range(4):
        st.draw(tmp_path / str(seed), "none", "bursty", seed, n_samples=N)
        spacing = np.diff(_load(tmp_path / str(seed)).time)
        assert spacing.min() > 0 and spacing.min() < 1e-5 and spacing.max() > 1e-3
        assert np.mean(spacing < 1e-5) > 0.3  # clusters, not a single odd sample
    st.draw(tmp_path / "even", "none", "drive", 0, n_samples=N)
    even = np.diff(_load(tmp_path / "even").time)
    assert even == pytest.approx(np.full(even.size, even[0]))


# ----------------------------------------------------------------------------- size


@pytest.fixture(scope="module")
def undelayed_reference(tmp_path_factory):
    """An effect-free velocity_only record whose force channel is not delayed (so the measured
    velocity lines up with the force), and its seed."""
    for seed in range(50):
        path = tmp_path_factory.mktemp(f"none{seed}")
        if st.draw(path, "none", "velocity_only", seed, n_samples=N).parameters["force_delay"] == 0:
            return seed, _load(path)
    raise AssertionError("no undelayed record among 50 seeds")


@pytest.mark.parametrize("effect", [e for e in st.EFFECTS if e != "none"])
def test_size_scales_the_visible_effect_over_the_noise(tmp_path, undelayed_reference, effect):
    """The stated ratio, and the same ratio measured on the records: an effect record less the
    effect-free record of the same seed is the effect (the noise is the same draw). Pre-sliding
    lives near the slow-speed cut, where the measured velocity's noise moves samples across it,
    so its measured ratio gets a wider tolerance."""
    seed, reference = undelayed_reference
    tolerance = 0.3 if effect == "presliding_hysteresis" else 0.1
    for size in (0.5, 1.0, 2.0):
        truth = st.draw(tmp_path / str(size), effect, "velocity_only", seed, size=size,
                        n_samples=N)
        assert truth.effect_rms / truth.noise_rms == pytest.approx(8 * size, rel=0.1)
        run = _load(tmp_path / str(size))
        assert np.array_equal(run.columns["feed_velocity"], reference.columns["feed_velocity"])
        difference = run.columns["drive_force"] - reference.columns["drive_force"]
        measured = _visible_rms(difference, run.columns["feed_velocity"])
        assert measured / truth.noise_rms == pytest.approx(8 * size, rel=tolerance)
