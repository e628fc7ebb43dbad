"""Checks of the carriage's step, M y'' = M g + F_e(t) + F_ext - F_contact (Soleimanian et al. 2020, eq. 1b).

RK4 on substeps with omega h <= SUBSTEP_PHASE = 0.1 has a phase error of (omega h)^4 / 120 =
8.3e-7 rad per radian, amplitude error far below that: over 30 periods (188 rad) 1.6e-4 of the
amplitude.
"""
import dataclasses
import math

import numpy as np
import pytest

from guideway_fmu.physics.roller_guide import carriage
from guideway_fmu.physics.roller_guide.roller_law import OpposedRows

BODY = carriage.Carriage(mass=2.9)  # M = 2.9 kg, g = 9.80665 m/s^2
K = 4.98e9  # N/m, about the lubricated guideway stiffness at y = 0
PERIOD = 2 * math.pi * math.sqrt(BODY.mass / K)  # 1.517e-4 s
F_EXT = 1500.0  # N
Y_EQ = (BODY.mass * BODY.gravity + F_EXT) / K  # equilibrium of the spring force K y
Y0, V0 = Y_EQ + 1e-6, 2e-3  # m, m/s
PHASE_BOUND = 2 * carriage.SUBSTEP_PHASE**4 / 120  # rad per radian: twice RK4's phase error


def step(y, v, h, f_ext, f_contact, k_contact=0.0, c_contact=0.0, t=0.0, load=None, rows=None):
    """One step of the default carriage under ``load`` (none by default)."""
    model = carriage.CarriageModel(BODY, load or carriage.ExternalLoad())
    return model.step(y, v, t, h, f_ext, f_contact, k_contact, c_contact, rows)


def simulate(h, n_steps, k=K, c=0.0, y0=Y0, v0=V0):
    """Step a body on the linear contact F_contact = k y + c v; returns times and (y, v) rows."""
    ys, vs, y, v = [y0], [v0], y0, v0
    for _ in range(n_steps):
        y, v, _ = step(y, v, h, F_EXT, k * y + c * v, k, c)
        ys.append(y)
        vs.append(v)
    return h * np.arange(n_steps + 1), np.array(ys), np.array(vs)


@pytest.mark.parametrize("y0, v0, h, f_ext, f_contact", [
    (0.0, 0.0, 1e-3, 0.0, 0.0),
    (1e-6, -0.01, 1e-4, 1500.0, 2000.0),
    (-2e-6, 0.3, 0.05, -40.0, 10.0),
])
def test_step_hand_calculation_held_force(y0, v0, h, f_ext, f_contact):
    a = BODY.gravity + (f_ext - f_contact) / BODY.mass
    y1, v1, a1 = step(y0, v0, h, f_ext, f_contact)
    assert y1 == pytest.approx(y0 + v0 * h + 0.5 * a * h * h, rel=1e-12, abs=1e-20)
    assert v1 == pytest.approx(v0 + a * h, rel=1e-12, abs=1e-18)
    assert a1 == pytest.approx(a, rel=1e-14)


def test_step_hand_calculation_free_fall_one_second():
    # y = 1/2 g t^2 = 4.903325 m after 1 s from rest, v = g t.
    y1, v1, a1 = step(0.0, 0.0, 1.0, 0.0, 0.0)
    assert (y1, v1, a1) == pytest.approx((4.903325, 9.80665, 9.80665), rel=1e-12)


@pytest.mark.parametrize("h", [PERIOD / 100, PERIOD / 3, 1.7 * PERIOD, 10.3 * PERIOD],
                         ids=["T/100", "T/3", "1.7T", "10.3T"])
def test_step_linear_contact_matches_closed_form_harmonic_oscillator(h):
    # M y'' = M g + F_ext - K y:  y = y_eq + (y0 - y_eq) cos(w t) + (v0 / w) sin(w t).
    n_steps = max(int(30 * PERIOD / h), 20)
    t, y, v = simulate(h, n_steps)
    w = 2 * math.pi / PERIOD
    amplitude = math.hypot(Y0 - Y_EQ, V0 / w)
    y_exact = Y_EQ + (Y0 - Y_EQ) * np.cos(w * t) + V0 / w * np.sin(w * t)
    v_exact = -(Y0 - Y_EQ) * w * np.sin(w * t) + V0 * np.cos(w * t)
    bound = PHASE_BOUND * w * t[-1] * amplitude  # over the run
    np.testing.assert_allclose(y, y_exact, rtol=0, atol=bound)
    np.testing.assert_allclose(v, v_exact, rtol=0, atol=bound * w)


def test_step_convergence_substeps_make_results_independent_of_the_step():
    # Common times t = n T: every 3rd step of h = T/3 and every 100th step of h = T/100.
    _, coarse, _ = simulate(PERIOD / 3, 3 * 20)
    _, fine, _ = simulate(PERIOD / 100, 100 * 20)
    amplitude = math.hypot(Y0 - Y_EQ, V0 * PERIOD / (2 * math.pi))
    np.testing.assert_allclose(coarse[::3], fine[::100], rtol=0, atol=2e-5 * amplitude)
    # and after whole periods the body is back where it started
    np.testing.assert_allclose(coarse[::3], Y0, rtol=0, atol=2e-5 * amplitude)


@pytest.mark.parametrize("damping_ratio", [0.01, 0.3, 1.0, 3.0])
@pytest.mark.parametrize("h", [PERIOD / 20, 2.5 * PERIOD], ids=["T/20", "2.5T"])
def test_step_limiting_case_damping_dissipates_energy(damping_ratio, h):
    # dE/dt = -C v^2: E = M v^2 / 2 + K (y - y_eq)^2 / 2 never grows and decays at least like
    # exp(-2 zeta w t) (exactly that rate on average for light damping); over 60 periods
    # exp(-2 * 0.01 * 2 pi * 60) = 5.3e-4.
    c = 2 * damping_ratio * math.sqrt(K * BODY.mass)
    _, y, v = simulate(h, int(60 * PERIOD / h), c=c)
    energy = 0.5 * BODY.mass * v**2 + 0.5 * K * (y - Y_EQ) ** 2
    resolved = energy > 1e-20 * energy[0]  # above the round-off of y - y_eq (ulp(y) = 1e-22 m)
    assert np.all(np.diff(energy)[resolved[1:]] < 0.0)
    assert np.all(np.diff(energy) <= 1e-20 * energy[0])
    assert energy[-1] < 1e-3 * energy[0]


@pytest.mark.parametrize("h", [PERIOD / 100, PERIOD / 3, 4.0 * PERIOD], ids=["T/100", "T/3", "4T"])
def test_step_hand_calculation_critically_damped(h):
    # C = 2 sqrt(K M):  y = y_eq + (A + B t) exp(-w t), A = y0 - y_eq, B = v0 + w A.
    w = 2 * math.pi / PERIOD
    t, y, v = simulate(h, max(int(5 * PERIOD / h), 10), c=2 * math.sqrt(K * BODY.mass))
    a_coef, b_coef = Y0 - Y_EQ, V0 + w * (Y0 - Y_EQ)
    decay = np.exp(-w * t)
    np.testing.assert_allclose(y, Y_EQ + (a_coef + b_coef * t) * decay, rtol=0, atol=1e-7 * a_coef)
    np.testing.assert_allclose(v, (b_coef - w * (a_coef + b_coef * t)) * decay,
                               rtol=0, atol=1e-7 * a_coef * w)


@pytest.mark.parametrize("h", [PERIOD / 50, 7.3 * PERIOD], ids=["T/50", "7.3T"])
def test_step_harmonic_load_matches_closed_form_forced_oscillator(h):
    # M y'' = M g + A sin(W t) - K y from y = y_eq + y_p(0), v = v_p(0) stays on the particular
    # solution y_p = A / (K - M W^2) sin(W t): no free vibration is excited.
    load = carriage.ExternalLoad(amplitude=3000.0, frequency=4500.0)
    W = 2 * math.pi * load.frequency
    amp = load.amplitude / (K - BODY.mass * W**2)
    y_eq = BODY.mass * BODY.gravity / K
    y, v, t = y_eq, amp * W, 0.0
    for _ in range(int(20 * PERIOD / h)):
        y, v, _ = step(y, v, h, 0.0, K * y, K, 0.0, t=t, load=load)
        t += h
        assert y == pytest.approx(y_eq + amp * math.sin(W * t), abs=2e-5 * abs(amp))


def test_step_hand_calculation_harmonic_load_on_free_body():
    # y'' = g + (A / M) sin(W t), from rest: y = g t^2 / 2 + A / (M W^2) (W t - sin(W t)).
    load = carriage.ExternalLoad(amplitude=100.0, frequency=50.0)
    W, h = 2 * math.pi * 50.0, 0.0137
    y, v, a = step(0.0, 0.0, h, 0.0, 0.0, load=load)
    c = load.amplitude / (BODY.mass * W**2)
    # RK4 on substeps of W dt <= SUBSTEP_PHASE: relative errors 6e-9 in y, 2e-8 in v here
    assert y == pytest.approx(0.5 * BODY.gravity * h**2 + c * (W * h - math.sin(W * h)), rel=2e-8)
    assert v == pytest.approx(BODY.gravity * h + c * W * (1 - math.cos(W * h)), rel=5e-8)
    assert a == pytest.approx(BODY.gravity + load(h) / BODY.mass, rel=1e-12)


@pytest.mark.parametrize("field, value", [("amplitude", math.nan), ("frequency", -1.0)])
def test_external_load_validate_refuses_bad_field_naming_it(field, value):
    with pytest.raises(ValueError, match=f"ExternalLoad.{field}"):
        carriage.ExternalLoad(**{field: value}).validate()


@pytest.mark.parametrize("name, kwargs", [
    ("k_contact", {"k_contact": -1.0}),
    ("c_contact", {"c_contact": -1e-3}),
    ("k_contact", {"k_contact": math.nan}),
])
def test_step_refuses_negative_or_bad_gains_naming_them(name, kwargs):
    with pytest.raises(ValueError, match=name):
        step(0.0, 0.0, 1e-5, 0.0, 0.0, **kwargs)


def test_body_defaults_validate():
    BODY.validate()


@pytest.mark.parametrize("field, value", [
    ("mass", 0.0), ("mass", -2.9), ("mass", math.nan), ("gravity", math.inf)])
def test_carriage_validate_refuses_bad_field_naming_it(field, value):
    with pytest.raises(ValueError, match=f"Carriage.{field}"):
        dataclasses.replace(BODY, **{field: value}).validate()


# -- the contact's force law handed to the body (roller_law.OpposedRows) ---------------------
OFFSET = 1e-4  # m, upper approach at y = 0 of the linear law: the row never opens


def linear_rows(stiffness):
    """The spring K (y + OFFSET) as a law: exponent 1, upper row only (the lower never closes)."""
    return OpposedRows(force_1um=stiffness * 1e-6, exponent=1.0, sine=1.0,
                       approach_upper=OFFSET, approach_lower=-1.0)


@pytest.mark.parametrize("h", [PERIOD / 100, 1.7 * PERIOD], ids=["T/100", "1.7T"])
def test_step_law_limiting_case_linear_law_matches_closed_form_oscillator(h):
    # exponent 1 and one row: F = K (y + OFFSET), with K OFFSET added to F_in the oscillator of
    # test_step_linear_contact_matches_closed_form_harmonic_oscillator around (M g + F_EXT) / K.
    rows = linear_rows(K)
    n_steps = max(int(30 * PERIOD / h), 20)
    ys, y, v = [Y0], Y0, V0
    for _ in range(n_steps):
        y, v, _ = step(y, v, h, F_EXT + K * OFFSET, 123.0, 0.0, 0.0,
                                rows=rows)  # the held 123 N is not used
        ys.append(y)
    t = h * np.arange(n_steps + 1)
    w = 2 * math.pi / PERIOD
    y_exact = Y_EQ + (Y0 - Y_EQ) * np.cos(w * t) + V0 / w * np.sin(w * t)
    bound = PHASE_BOUND * w * t[-1] * math.hypot(Y0 - Y_EQ, V0 / w)
    np.testing.assert_allclose(ys, y_exact, rtol=0, atol=bound)


def test_step_law_with_lift_off_and_moving_films_matches_scipy_dop853():
    # One 20 us step of the 2.9 kg body on the guideway's law (n = 10/9) while the films move
    # at 5 mm/s and 2 mm/s and the lower row opens within the step: against an independent
    # DOP853 solution of the same ODE at rtol 1e-12.
    from scipy.integrate import solve_ivp

    rows = OpposedRows(force_1um=2.6e3, exponent=10 / 9, sine=math.sqrt(0.5),
                       approach_upper=1.2e-6, approach_lower=3e-8, rate_upper=5e-3,
                       rate_lower=2e-3)
    load = carriage.ExternalLoad(static=100.0, amplitude=3000.0, frequency=4500.0)
    t0, h, y0, v0 = 1e-4, 2e-5, 0.0, 0.02

    def rhs(t, s):
        return [s[1], BODY.gravity + (load(t) - rows.force(s[0], t - t0)) / BODY.mass]

    ref = solve_ivp(rhs, (t0, t0 + h), [y0, v0], method="DOP853", rtol=1e-12, atol=1e-16)
    y1, v1, _ = step(y0, v0, h, 0.0, 0.0, t=t0, load=load, rows=rows)
    assert rows.approach_lower + rows.rate_lower * h - rows.sine * y1 < 0  # the row opened
    # RK4 loses its order at the kink where the row opens (F'' is unbounded there): 2e-5 in y
    assert y1 == pytest.approx(ref.y[0, -1], rel=5e-5)
    assert v1 == pytest.approx(ref.y[1, -1], rel=1e-4)


def test_convergence_study_substep_phase_on_the_undamped_dry_guideway_law(monkeypatch):
    # The worst case for the substeps' phase error: the carriage on the dry guideway's law (no
    # damping, the free vibration never decays) under 9000 N at 2500 Hz, 4 us steps for 2 ms
    # (80 rad of the 6.6 kHz vibration), against an independent DOP853 solution. RK4's error
    # falls with the fourth power of the substep (16x per halving): 3e-7, 4e-6 and 7e-5 of the
    # motion's range at half, once and twice SUBSTEP_PHASE (the whole 0.2 s cycle against the
    # reference: docs/speed.md).
    from scipy.integrate import solve_ivp

    from guideway_fmu.physics.roller_guide.four_rows import Guideway, RowKernel

    kernel = RowKernel(Guideway())
    rows = OpposedRows(force_1um=kernel.force_1um, sine=kernel.sin,
                       approach_upper=kernel.delta0, approach_lower=kernel.delta0)
    body = carriage.Carriage()
    model = carriage.CarriageModel(body, carriage.ExternalLoad(amplitude=9000.0, frequency=2500.0))
    h, n_steps = 4e-6, 500
    t = h * np.arange(n_steps + 1)
    exact = solve_ivp(lambda tt, s: [s[1], model.acceleration(tt, rows.force(s[0]), 0.0)],
                      (0.0, t[-1]), [0.0, 0.0], method="DOP853", t_eval=t, rtol=1e-12,
                      atol=1e-18).y[0]
    span = np.ptp(exact)
    errors = {}
    for phase in (carriage.SUBSTEP_PHASE / 2, carriage.SUBSTEP_PHASE, 2 * carriage.SUBSTEP_PHASE):
        monkeypatch.setattr(carriage, "SUBSTEP_PHASE", phase)
        ys, y, v = [0.0], 0.0, 0.0
        for i in range(n_steps):
            y, v, _ = model.step(y, v, t[i], h, 0.0, 0.0, rows=rows)
            ys.append(y)
        errors[phase] = np.max(np.abs(np.array(ys) - exact)) / span
    fine, chosen, coarse = errors.values()
    assert 10 < chosen / fine < 25 and 10 < coarse / chosen < 25  # fourth order
    assert chosen < 1e-5
