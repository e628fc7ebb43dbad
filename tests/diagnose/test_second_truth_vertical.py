"""The second, independent generator of vertical measured runs
(guideway_synthetic/second_truth_vertical.py): each test names the independent check it makes."""
import math
import re
import warnings

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from guideway_synthetic import second_truth_vertical as sv
from guideway_fmu.diagnose.run_io import load_run

N = 600  # samples per record in these tests (draws for the workflow have 5,000-20,000)
PLAIN_DECIMAL = re.compile(r"^-?\d+\.\d+$")
VOCABULARY = {"lubrication", "presliding_hysteresis", "position_dependent_friction",
              "unmodeled_mass", "preload_loss", "ball_to_ball_contact", "lubricant_film", "none",
              "unknown"}
# A guide with round numbers: 10 mm rollers at 100 N each (10000 N over 4 x 25 rollers)
GUIDE = sv.Guide(rows=4, elements=25, radius=2.5e-3, length=10e-3, angle_deg=45.0,
                 preload=10000.0)


def _hand_palmgren_load(approach_m, length_mm=10.0):
    """Palmgren in its published units (mm, N), a roller's two raceway contacts in series each
    taking half its approach: Q = (delta / 2 l^0.8 / 3.84e-5)^(1/0.9)."""
    approach_mm = max(approach_m * 1e3, 0.0)
    return (0.5 * approach_mm * length_mm ** 0.8 / 3.84e-5) ** (1 / 0.9)


# ----------------------------------------------------------------------------- physics


def test_preload_approach_is_palmgren_by_hand():
    """Hand calculation: 100 N on a 10 mm roller gives 3.84e-5 * 100^0.9 / 10^0.8 = 3.84e-4 mm
    at each of its two raceway contacts (100^0.9 / 10^0.8 = 10^1.8 / 10^0.8 = 10): 7.68e-4 mm."""
    assert GUIDE.preload_approach == pytest.approx(7.68e-7, rel=1e-12)
    assert sv.palmgren_load(7.68e-7, 10e-3) == pytest.approx(100.0, rel=1e-12)
    assert sv.palmgren_load(-1e-9, 10e-3) == 0.0  # an opened contact carries nothing


@pytest.mark.parametrize("load", [0.0, 800.0, 4000.0, 40000.0])
def test_static_equilibrium_balances_the_hand_palmgren_rows(load):
    """Hand calculation of the rows: at the equilibrium the two upper rows (loaded) less the two
    lower rows (unloaded, open at the largest load) carry m g + N vertically, each roller's load
    from Palmgren in mm/N units at delta_0 +- y sin(45 deg)."""
    plant = sv.Plant(GUIDE, mass=4.0)
    y, v = plant.equilibrium(load, 0.0)
    s = math.sin(math.radians(45.0))
    upper = _hand_palmgren_load(7.68e-7 + y * s)
    lower = _hand_palmgren_load(7.68e-7 - y * s)
    assert v == 0.0
    assert 2 * 25 * s * (upper - lower) == pytest.approx(4.0 * 9.81 + load, rel=1e-9)
    if load == 40000.0:
        assert lower == 0.0  # the lower rows have lifted off


@pytest.mark.parametrize("angle", [45.0, 40.0])
def test_small_free_vibration_has_the_frequency_of_the_row_force_slope(angle):
    """Natural frequency: a small free vibration about the equilibrium (integrated with the
    generator's own right-hand side) has the period 2 pi sqrt(m / k), k the slope of the roller
    force from a central difference taken here."""
    guide = sv.Guide(rows=4, elements=25, radius=2.5e-3, length=10e-3, angle_deg=angle,
                     preload=10000.0)
    plant = sv.Plant(guide, mass=4.0)
    y0, _ = plant.equilibrium(500.0, 0.0)
    h = 1e-11
    k = (guide.vertical_force(y0 + h) - guide.vertical_force(y0 - h)) / (2 * h)
    expected = math.sqrt(k / 4.0) / (2 * math.pi)
    cycles = 20
    duration = cycles / expected
    t = np.linspace(0.0, duration, 40001)
    solution = solve_ivp(plant.derivative, (0.0, duration), [y0 + 1e-12, 0.0], t_eval=t,
                         method="DOP853", rtol=1e-12, atol=[1e-22, 1e-18],
                         args=(lambda _: 500.0, lambda _: 0.0))
    swing = solution.y[0] - y0
    rising = np.flatnonzero((swing[:-1] < 0) & (swing[1:] >= 0))
    crossings = t[rising] - swing[rising] * (t[rising + 1] - t[rising]) / (swing[rising + 1]
                                                                          - swing[rising])
    measured = (len(crossings) - 1) / (crossings[-1] - crossings[0])
    assert measured == pytest.approx(expected, rel=1e-6)
    # the consistent geometry at y = 0: 100 rollers of stiffness dQ/d delta = Q / (0.9 delta),
    # each seen through sin^2(theta)
    roller = 100.0 / (0.9 * 7.68e-7)
    k0 = (guide.vertical_force(h) - guide.vertical_force(-h)) / (2 * h)
    assert k0 == pytest.approx(100 * roller * math.sin(math.radians(angle)) ** 2, rel=1e-6)


FILM = sv.Film(viscosity=0.195, pressure_viscosity=2.2e-8, radius=2.5e-3, length=10e-3,
               modulus=2.0e11)


def test_unsqueezed_film_is_eq_4_by_hand():
    """Hand evaluation of eq. 4 without squeeze (Table 3's lubricant, 100 N at 0.3 m/s)."""
    f_bar = 100.0 / (2e11 * 2.5e-3 * 10e-3)
    u_bar = 0.195 * 0.3 / (2e11 * 2.5e-3)
    g = 2.2e-8 * 2e11
    hand = 2.5e-3 * 13.924 * f_bar ** -0.045 * u_bar ** 0.647 * g ** 0.46
    assert FILM.unsqueezed(100.0, 0.3) == pytest.approx(hand, rel=1e-12)
    assert FILM.unsqueezed(100.0, -0.3) == FILM.unsqueezed(100.0, 0.3)  # speed magnitude
    assert FILM.unsqueezed(100.0, 0.0) == 0.0


def test_steady_film_is_a_quarter_of_the_unsqueezed_law():
    """The squeeze term: h' = 0 exactly at h_s / 4; a film below it grows, above it squeezes
    out; integrated from no film at constant load and speed it settles at h_s / 4."""
    h_s = float(FILM.unsqueezed(100.0, 0.2))
    assert FILM.steady(100.0, 0.2) == pytest.approx(0.25 * h_s, rel=1e-15)
    assert sv.Film.rate(0.25 * h_s, h_s, 0.2) == pytest.approx(0.0, abs=1e-18)
    assert sv.Film.rate(0.1 * h_s, h_s, 0.2) > 0 > sv.Film.rate(0.5 * h_s, h_s, 0.2)
    solution = solve_ivp(lambda t, h: sv.Film.rate(h, h_s, 0.2), (0.0, 0.05), [0.0],
                         rtol=1e-10, atol=1e-20)
    assert solution.y[0, -1] == pytest.approx(0.25 * h_s, rel=1e-6)


def test_the_record_starts_at_rest_in_static_equilibrium_with_a_steady_film():
    """The format's start: the film plant's first state is the equilibrium (acceleration 0,
    velocity 0, both films steady at their loads and the first feed velocity) and, with
    constant load and speed, it stays there."""
    plant = sv.Plant(GUIDE, mass=4.0, film=FILM)
    times = np.linspace(0.0, 2e-3, 201)
    states, accel = plant.simulate(times, lambda t: 800.0 + 0.0 * np.asarray(t),
                                   lambda t: 0.2 + 0.0 * np.asarray(t))
    q_up, q_low = plant.loads(states[:, :1])
    assert states[1, 0] == 0.0 and abs(accel[0]) < 1e-6
    assert states[2, 0] == pytest.approx(float(FILM.steady(q_up[0], 0.2)), rel=1e-10)
    assert states[3, 0] == pytest.approx(float(FILM.steady(q_low[0], 0.2)), rel=1e-10)
    assert np.ptp(states[0]) < 1e-6 * GUIDE.preload_approach


@pytest.mark.slow
def test_integration_error_is_far_below_the_finest_noise(tmp_path):
    """Tolerance: the record's integration (RTOL) differs from one 100 times tighter by far
    less than FINEST_NOISE of the channel's range, for the film plant (the hardest)."""
    rig = sv._draw_rig(4)
    times, rate, _ = sv._draw_times(4, 800)
    _, feed = sv._draw_feed(4, times[-1])
    plant = sv.Plant(rig.guide, rig.mass, film=sv.Film(rig.viscosity, rig.pressure_viscosity,
                                                       rig.guide.radius, rig.guide.length, 2e11))
    natural = math.sqrt(plant.stiffness() / rig.mass) / (2 * math.pi)
    _, force, _ = sv._draw_load(4, rig, natural, rate, times[-1])

    def speed(t):
        return feed(np.atleast_1d(np.asarray(t, dtype=float)))[1].reshape(np.shape(t))

    loose, _ = plant.simulate(times, force, speed)
    tolerances = sv.RTOL, sv.ATOL_SCALE
    try:
        sv.RTOL, sv.ATOL_SCALE = tolerances[0] / 100, tolerances[1] / 100
        tight, _ = plant.simulate(times, force, speed)
    finally:
        sv.RTOL, sv.ATOL_SCALE = tolerances
    assert np.max(np.abs(loose[0] - tight[0])) < 0.01 * sv.FINEST_NOISE * np.ptp(tight[0])


# ----------------------------------------------------------------------------- records


def _load(path):
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # every column must be in the format's vocabulary
        return load_run(path)


@pytest.mark.parametrize("effect", list(sv.EFFECTS))
def test_every_effect_writes_a_run_that_follows_the_format(tmp_path, effect):
    """Format: load_run accepts the record, a vertical_response compared on a vertical channel,
    driven by the feed and normal_force, dry_hertz stated, plain decimals, and the visible
    effect 8 size times the noise."""
    seed = list(sv.EFFECTS).index(effect) + 11
    truth = sv.draw(tmp_path, effect, seed, n_samples=N, size=1.5)
    run = _load(tmp_path)
    assert truth.expected == sv.EFFECTS[effect] and truth.channel in sv.CHANNELS
    assert run.kind == "vertical_response" and run.time.size == N
    assert np.all(np.diff(run.time) > 0)
    assert run.model == {"friction": "coulomb", "contact": "dry_hertz"}
    assert run.outputs == [truth.channel]
    assert "normal_force" in run.inputs and "feed_position" in run.inputs
    assert set(run.columns) == set(run.inputs) | {truth.channel}
    guideway = run.sections["guideway"]
    assert guideway["type"] == "roller" and guideway["rows"] in (2, 4)
    assert 2000.0 <= guideway["preload"] <= 12000.0 and 1.0 <= run.moving_mass <= 10.0
    assert {"viscosity", "pressure_viscosity"} <= set(run.sections["lubricant"])
    cells = [cell for line in (tmp_path / "data.csv").read_text().splitlines()[1:]
             for cell in line.split(",")]
    assert all(PLAIN_DECIMAL.match(cell) for cell in cells)
    assert all(isinstance(v, float) for v in truth.parameters.values())
    if effect == "none":
        assert truth.effect_rms == 0.0
    else:
        assert truth.effect_rms / truth.noise_rms == pytest.approx(8 * 1.5, rel=0.1)
    if effect == "unmodeled_mass":
        assert truth.parameters["mass"] == pytest.approx(run.moving_mass
                                                         + truth.parameters["missing_mass"])
    if effect == "preload_loss":
        assert truth.parameters["preload"] == pytest.approx(
            guideway["preload"] * truth.parameters["preload_kept"])


def test_the_same_seed_gives_the_same_bytes(tmp_path):
    """Determinism per seed: same arguments, same bytes and truth; another seed differs."""
    first = sv.draw(tmp_path / "a", "contact_damping", 5, n_samples=N)
    second = sv.draw(tmp_path / "b", "contact_damping", 5, n_samples=N)
    sv.draw(tmp_path / "c", "contact_damping", 6, n_samples=N)
    for name in ("rig.toml", "data.csv"):
        assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes()
    assert (tmp_path / "a" / "data.csv").read_bytes() != (tmp_path / "c" / "data.csv").read_bytes()
    assert first == second


def test_the_expected_answers_are_in_the_vocabulary():
    """The answers: every expected answer is a word of the format's vocabulary, and the one
    out-of-vocabulary effect (contact damping) expects 'unknown'."""
    assert set(sv.EFFECTS.values()) <= VOCABULARY
    assert [e for e, answer in sv.EFFECTS.items() if answer == "unknown"] == ["contact_damping"]


@pytest.mark.parametrize("arguments,name", [
    (("friction", 1, N, 1.0), "effect"),
    (("none", -1, N, 1.0), "seed"),
    (("none", 1.5, N, 1.0), "seed"),
    (("none", True, N, 1.0), "seed"),
    (("none", 1, 20, 1.0), "n_samples"),
    (("none", 1, 1000.0, 1.0), "n_samples"),
    (("none", 1, N, 0.0), "size"),
    (("none", 1, N, math.nan), "size"),
    (("none", 1, N, "1"), "size"),
])
def test_bad_arguments_raise_naming_the_argument(tmp_path, arguments, name):
    """Refusals: a bad argument is a ValueError naming it, and nothing is written."""
    effect, seed, n_samples, size = arguments
    with pytest.raises(ValueError, match=name):
        sv.draw(tmp_path / "run", effect, seed, n_samples=n_samples, size=size)
    assert not (tmp_path / "run").exists()


def test_a_size_beyond_the_finest_sensor_raises_naming_size(tmp_path):
    """Refusals: a size that asks for noise finer than FINEST_NOISE of the range is refused."""
    with pytest.raises(ValueError, match="size"):
        sv.draw(tmp_path, "unmodeled_mass", 1, n_samples=N, size=1e6)


def test_the_load_spectrum_stays_in_its_documented_band_away_from_resonance():
    """Spectrum of the drawn load (Hann-windowed FFT, independent of how it is built): at least
    95 % of the dynamic part's energy lies in 0.15-0.65 or 1.3-2 times the stated natural
    frequency (the module doc), under 1 % within 5 % of resonance, and both bands occur."""
    above = 0
    for seed in range(24):
        rig = sv._draw_rig(seed)
        times, rate, _ = sv._draw_times(seed, 4000)
        natural = math.sqrt(sv.Plant(rig.guide, rig.mass).stiffness() / rig.mass) / (2 * math.pi)
        _, force, _ = sv._draw_load(seed, rig, natural, rate, times[-1])
        grid = np.linspace(0.0, times[-1], 2**16)
        dynamic = force(grid) - np.mean(force(grid))
        power = np.abs(np.fft.rfft(dynamic * np.hanning(grid.size))) ** 2
        ratio = np.fft.rfftfreq(grid.size, grid[1]) / natural
        inside = ((ratio > 0.14) & (ratio < 0.66)) | ((ratio > 1.29) & (ratio < 2.01))
        assert power[inside].sum() > 0.95 * power.sum(), seed
        assert power[np.abs(ratio - 1.0) < 0.05].sum() < 0.01 * power.sum(), seed
        above += power[ratio > 1.0].sum() > 0.5 * power.sum()
    assert 0 < above < 24
