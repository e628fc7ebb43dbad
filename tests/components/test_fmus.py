"""The six guideway FMUs, built with pythonfmu and driven through fmpy as a co-simulation host.

The FMUs are built once per session (``fmu_dir`` fixture in conftest.py). Physics checks compare
with values computed by hand here, from the formulas quoted in each test, not with the project's
physics code.
"""
from __future__ import annotations

import json
import math
import os
import shutil
import site
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from fmpy import extract, read_model_description, simulate_fmu
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Slave
from fmpy.validation import validate_fmu
from support import capturing_callbacks

from guideway_fmu.components import registry
from guideway_fmu.physics.roller_guide.roller_law import OpposedRows

NAMES = registry.names("guideway")
STATUS_DISCARD = 2
STATUS_ERROR = 3  # status of the log messages that explain a discarded step
NAN = float("nan")

# -- hand values -------------------------------------------------------------------------------
# Default guideway (Soleimanian et al. 2020, Table 2): N = 20 rollers per groove, 4 grooves, theta = 45 deg,
# preload F0 = 36800 N shared by all 4N rollers (9200 N per groove), roller length l = 8 mm; Palmgren's deflection of
# one line contact, delta[mm] = 3.84e-5 Q^0.9 / l[mm]^0.8, two contacts in series per roller.
ROLLERS = 20
SIN45 = math.sin(math.radians(45.0))
Q0 = 36800.0 / (4 * ROLLERS)  # 460 N per roller
K_PALMGREN = (1e3 * 8**0.8 / (2 * 3.84e-5)) ** (1 / 0.9)  # N/m^(10/9) of F = k delta^(10/9)
DELTA0 = (Q0 / K_PALMGREN) ** 0.9  # preload approach of one roller [m]
GRAVITY = 9.80665
MASS = 3.302


def hand_dry_loads(y):
    """(F_U, F_L) [N]: F = k delta^(10/9), delta = delta0 +- y sin(45 deg), 0 if delta <= 0."""
    def load(delta):
        return K_PALMGREN * max(delta, 0.0) ** (10 / 9)
    return load(DELTA0 + y * SIN45), load(DELTA0 - y * SIN45)


def hand_dry_net_force(y):
    """2 N sin(45 deg) (F_U - F_L) [N]."""
    f_upper, f_lower = hand_dry_loads(y)
    return 2 * ROLLERS * SIN45 * (f_upper - f_lower)


def hand_biharmonic_velocity(t):
    """Paper eq. (1a) with the third harmonic:

    u = 0.2919 sin(2 pi 5 t + 2.0588) + 0.0178 sin(2 pi 15 t + 1.2679).
    """
    return (0.2919 * math.sin(2 * math.pi * 5 * t + 2.0588)
            + 0.0178 * math.sin(2 * math.pi * 15 * t + 1.2679))


# -- driving an FMU by variable name -----------------------------------------------------------
class Slave:
    """One initialised co-simulation instance; variables addressed by name, log captured."""

    def __init__(self, path, instance_name, start_values):
        md = read_model_description(str(path))
        self.variables = {v.name: v for v in md.modelVariables}
        self.output_names = [v.name for v in md.modelVariables if v.causality == "output"]
        self.unzip_dir = extract(str(path))
        self.messages = []
        self._callbacks = capturing_callbacks(self.messages)
        self.fmu = FMU2Slave(guid=md.guid, unzipDirectory=self.unzip_dir,
                             modelIdentifier=md.coSimulation.modelIdentifier,
                             instanceName=instance_name)
        # pythonfmu forwards the components' error messages only with logging on
        self.fmu.instantiate(callbacks=self._callbacks, loggingOn=True)
        self.set(**start_values)
        self.fmu.setupExperiment(startTime=0.0)
        self.fmu.enterInitializationMode()
        self.fmu.exitInitializationMode()
        self.time = 0.0

    def set(self, **values):
        for name, value in values.items():
            var = self.variables[name]
            setter = {"Real": self.fmu.setReal, "Integer": self.fmu.setInteger,
                      "Boolean": self.fmu.setBoolean, "String": self.fmu.setString}[var.type]
            setter([var.valueReference], [value])

    def get(self, name):
        var = self.variables[name]
        getter = {"Real": self.fmu.getReal, "Integer": self.fmu.getInteger,
                  "Boolean": self.fmu.getBoolean, "String": self.fmu.getString}[var.type]
        return getter([var.valueReference])[0]

    def outputs(self):
        return {name: self.get(name) for name in self.output_names}

    def step(self, h, n=1):
        for _ in range(n):
            self.fmu.doStep(self.time, h)
            self.time += h
        return self

    def error_messages(self):
        return [text for status, text in self.messages if status >= STATUS_ERROR]

    def free(self):
        try:
            self.fmu.terminate()
        finally:
            self.fmu.freeInstance()
            shutil.rmtree(self.unzip_dir, ignore_errors=True)


@pytest.fixture
def open_fmu(fmu_dir):
    """open_fmu(name, instance_name=None, **start_values): an initialised Slave, freed later."""
    opened = []

    def open_(name, instance_name=None, **start_values):
        slave = Slave(fmu_dir / f"{name}.fmu", instance_name or name, start_values)
        opened.append(slave)
        return slave

    yield open_
    for slave in reversed(opened):
        slave.free()


def assert_discarded(slave, h, name):
    """doStep from the current time returns fmi2Discard and an error message names ``name``."""
    slave.messages.clear()
    with pytest.raises(FMICallException) as info:
        slave.step(h)
    assert info.value.status == STATUS_DISCARD
    assert any(name in text for text in slave.error_messages()), slave.messages


# -- 1. validation ------------------------------------------------------------------------------
@pytest.mark.parametrize("name", NAMES)
def test_fmu_passes_fmpy_validation(fmu_dir, name):
    assert validate_fmu(str(fmu_dir / f"{name}.fmu")) == []


# -- 2. modelDescription -------------------------------------------------------------------------
# Base-unit exponents (kg, m, s) worked out by hand for the units of the FMU contracts.
HAND_BASE_UNITS = {"m": (0, 1, 0), "m/s": (0, 1, -1), "m/s2": (0, 1, -2), "N": (1, 1, -2),
                   "N/m": (1, 0, -2), "N.s/m": (1, 0, -1), "N.m": (1, 2, -2), "kg.m2": (1, 2, 0),
                   "W": (1, 2, -3)}

_CONTACT = {"y": ("input", "m"), "y_dot": ("input", "m/s"), "u": ("input", "m/s"),
            "F_contact": ("output", "N"), "F_upper": ("output", "N"), "F_lower": ("output", "N"),
            "h_upper": ("output", "m"), "h_lower": ("output", "m"),
            "K_contact": ("output", "N/m"), "C_contact": ("output", "N.s/m"),
            "law_force_1um": ("output", "N"), "law_exponent": ("output", "1"),
            "law_sine": ("output", "1"), "law_approach_upper": ("output", "m"),
            "law_approach_lower": ("output", "m"), "law_rate_upper": ("output", "m/s"),
            "law_rate_lower": ("output", "m/s")}
_LAW_INPUTS = {name: ("input", unit) for name, (_, unit) in _CONTACT.items()
               if name.startswith("law_")}  # the body takes the contact's force law
CONTRACT = {
    "FeedKinematics": {"u_cmd": ("input", "m/s"), "x": ("output", "m"), "u": ("output", "m/s"),
                       "a": ("output", "m/s2")},
    "VerticalDynamics": {"F_contact": ("input", "N"), "F_ext": ("input", "N"),
                         "K_contact": ("input", "N/m"), "C_contact": ("input", "N.s/m"),
                         "y": ("output", "m"), "y_dot": ("output", "m/s"),
                         "y_ddot": ("output", "m/s2"), **_LAW_INPUTS},
    "ContactDryHertz": _CONTACT,
    "ContactEHL": _CONTACT,
    "FrictionMixedEHL": {"F_upper": ("input", "N"), "F_lower": ("input", "N"),
                         "h_upper": ("input", "m"), "h_lower": ("input", "m"),
                         "u": ("input", "m/s"), "F_friction": ("output", "N"),
                         "F_boundary": ("output", "N"), "F_viscous": ("output", "N")},
    "FrictionCoulomb": {"F_upper": ("input", "N"), "F_lower": ("input", "N"),
                        "u": ("input", "m/s"), "F_friction": ("output", "N")},
    "BallCarriage5DOF": {"F_y": ("input", "N"), "F_z": ("input", "N"), "M_x": ("input", "N.m"),
                         "M_y": ("input", "N.m"), "M_z": ("input", "N.m"),
                         "u_feed": ("input", "m/s"), "u": ("output", "m"), "v": ("output", "m"),
                         "phi": ("output", "rad"), "theta": ("output", "rad"),
                         "psi": ("output", "rad"), "v_dot": ("output", "m/s"),
                         "theta_dot": ("output", "rad/s"), "row_load_1": ("output", "N"),
                         "row_load_2": ("output", "N")},
    "FeedUnitErrors": {"F_x": ("input", "N"), "F_y": ("input", "N"), "F_z": ("input", "N"),
                       "point_x": ("input", "m"), "point_y": ("input", "m"),
                       "point_z": ("input", "m"), "x_feed": ("input", "m"),
                       "delta_y": ("output", "m"), "delta_z": ("output", "m"),
                       "epsilon_x": ("output", "rad"), "epsilon_y": ("output", "rad"),
                       "epsilon_z": ("output", "rad"), "tool_d_y": ("output", "m"),
                       "tool_d_z": ("output", "m"), "max_ball_load": ("output", "N")},
    "MillingForce": {"u_feed": ("input", "m/s"), "F_x": ("output", "N"), "F_y": ("output", "N"),
                     "F_z": ("output", "N")},
    "BallToBallFriction": {"u": ("input", "m/s"), "x": ("input", "m"),
                           "F_normal": ("input", "N"), "F_side": ("input", "N"),
                           "M_yaw": ("input", "N.m"), "F_friction": ("output", "N"),
                           "contact_force": ("output", "N"), "friction_loss": ("output", "W")},
    "ForceTable": {"F": ("output", "N")},
    "Wear": {"F_load": ("input", "N"), "distance": ("input", "m"),
             "preload_deformation": ("output", "m"), "preload": ("output", "N"),
             "wear_depth": ("output", "m"), "vertical_displacement": ("output", "m")},
}


@pytest.mark.parametrize("name", NAMES)
def test_model_description_has_units_descriptions_and_structure(fmu_dir, name):
    md = read_model_description(str(fmu_dir / f"{name}.fmu"))
    units = {u.name: u for u in md.unitDefinitions}
    for var in md.modelVariables:
        assert var.description, f"{var.name} has no description"
        if var.type == "Real":
            assert var.unit in units, f"{var.name}: unit {var.unit!r} not in UnitDefinitions"
    for unit in units.values():
        assert unit.baseUnit is not None, f"unit {unit.name} has no BaseUnit"
        if unit.name in HAND_BASE_UNITS:
            base = unit.baseUnit
            assert (base.kg, base.m, base.s) == HAND_BASE_UNITS[unit.name], unit.name
    outputs = {v.name for v in md.modelVariables if v.causality == "output"}
    assert {u.variable.name for u in md.outputs} == outputs
    assert outputs <= {u.variable.name for u in md.initialUnknowns}
    assert md.coSimulation.canGetAndSetFMUstate


@pytest.mark.parametrize("name", NAMES)
def test_model_description_declares_contract_variables(fmu_dir, name):
    md = read_model_description(str(fmu_dir / f"{name}.fmu"))
    declared = {v.name: (v.causality, v.unit) for v in md.modelVariables}
    for var, expected in CONTRACT[name].items():
        assert declared.get(var) == expected, var


# -- 3. physics ---------------------------------------------------------------------------------
def test_dry_contact_at_zero_displacement_carries_preload_shared_by_all_rollers(open_fmu):
    dry = open_fmu("ContactDryHertz")
    assert dry.get("F_contact") == pytest.approx(0.0, abs=1e-9)
    assert dry.get("F_upper") == pytest.approx(460.0, rel=1e-12)  # 36800 N / 80 rollers
    assert dry.get("F_lower") == pytest.approx(460.0, rel=1e-12)
    assert dry.get("h_upper") == 0.0 and dry.get("h_lower") == 0.0


def test_dry_contact_matches_hand_calculation(open_fmu):
    dry = open_fmu("ContactDryHertz", y=1e-6)
    f_upper, f_lower = hand_dry_loads(1e-6)
    assert dry.get("F_upper") == pytest.approx(f_upper, rel=1e-10)
    assert dry.get("F_lower") == pytest.approx(f_lower, rel=1e-10)
    assert dry.get("F_contact") == pytest.approx(hand_dry_net_force(1e-6), rel=1e-10)
    dry.step(1e-4)  # algebraic: stepping changes nothing
    assert dry.get("F_contact") == pytest.approx(hand_dry_net_force(1e-6), rel=1e-10)


def test_roller_load_1um_parameter_matches_hand_conversion(open_fmu):
    # k = 1.5 x Palmgren given as the roller load at 1 um, k (1e-6 m)^(10/9); hand law at that k.
    k = 1.5 * K_PALMGREN
    dry = open_fmu("ContactDryHertz", roller_load_1um=k * 1e-6 ** (10 / 9), y=1e-6)
    delta0 = (Q0 / k) ** 0.9
    f_upper = k * (delta0 + 1e-6 * SIN45) ** (10 / 9)
    assert dry.get("F_upper") == pytest.approx(f_upper, rel=1e-9)


@pytest.mark.parametrize("name, start", [
    ("ContactDryHertz", {}),
    ("ContactEHL", {"u": 0.29}),  # films held: K is the frozen-film stiffness
    ("ContactEHL", {"u": 0.29, "film_model": "pan_hamrock"}),  # quasi-static, film included
], ids=["dry", "ehl-extrapolated", "ehl-pan_hamrock"])
def test_contact_stiffness_matches_central_finite_difference(open_fmu, name, start):
    contact = open_fmu(name, y=1e-6, **start)
    stiffness = contact.get("K_contact")
    dy = 1e-10
    contact.set(y=1e-6 + dy)
    f_plus = contact.get("F_contact")  # direct feedthrough: no step needed
    contact.set(y=1e-6 - dy)
    f_minus = contact.get("F_contact")
    assert stiffness > 0.0
    assert stiffness == pytest.approx((f_plus - f_minus) / (2 * dy), rel=1e-5)


@pytest.mark.parametrize("name", ["ContactDryHertz", "ContactEHL"])
@pytest.mark.parametrize("y", [-3e-6, 1e-6, 1e-4])
def test_contact_law_outputs_reproduce_the_net_force_hand_calculation(open_fmu, name, y):
    # the law the body integrates (OpposedRows) gives the contact's own F_contact at its input y
    contact = open_fmu(name, y=y, u=0.29)
    out = contact.outputs()
    law = {k[4:]: v for k, v in out.items() if k.startswith("law_")}
    assert law["force_1um"] == pytest.approx(2 * ROLLERS * SIN45 * K_PALMGREN * 1e-6 ** (10 / 9),
                                             rel=1e-12)
    assert (law["exponent"], law["sine"]) == pytest.approx((10 / 9, SIN45), rel=1e-14)
    assert law["approach_upper"] == pytest.approx(DELTA0 + out["h_upper"], rel=1e-12)
    assert OpposedRows(**law).force(y) == pytest.approx(out["F_contact"], rel=1e-10, abs=1e-9)


def test_ehl_law_rates_match_the_film_change_over_a_short_step_numerical_derivative(open_fmu):
    ehl = open_fmu("ContactEHL", y=0.0, u=0.29)  # steady films at y = 0 ...
    ehl.set(y=1e-6)  # ... squeezed (upper) and relieved (lower) by the new load
    before = ehl.outputs()
    dt = 1e-9
    ehl.step(dt)
    after = ehl.outputs()
    for row in ("upper", "lower"):
        rate = (after[f"h_{row}"] - before[f"h_{row}"]) / dt
        assert before[f"law_rate_{row}"] != 0.0
        assert before[f"law_rate_{row}"] == pytest.approx(rate, rel=1e-4)


def test_ehl_interpolated_inputs_limiting_case_straight_motion_equals_extrapolation(open_fmu):
    # a body moving at constant speed: the Hermite curve from the previous inputs (y = 0) to the
    # present ones (y = v h, at the END of the step) is the line the extrapolating contact
    # follows from y = 0 (inputs at the START): the films must agree to round-off.
    v, h = 0.05, 2e-5
    start = open_fmu("ContactEHL", "start", y=0.0, y_dot=v, u=0.29)
    end = open_fmu("ContactEHL", "end", y=0.0, y_dot=v, u=0.29, interpolate_inputs=True)
    end.set(y=v * h)
    start.step(h)
    end.step(h)
    for film in ("h_upper", "h_lower"):
        assert end.get(film) == pytest.approx(start.get(film), rel=1e-13)
    plain = open_fmu("ContactEHL", "plain", y=v * h, y_dot=v, u=0.29)  # extrapolating from v h
    plain.step(h)
    assert abs(plain.get("h_upper") - end.get("h_upper")) > 1e-6 * end.get("h_upper")


def test_ehl_interpolated_inputs_convergence_on_a_curved_motion_against_scipy(open_fmu):
    # constant acceleration from rest, y = a t^2 / 2 (the cubic Hermite curve through the inputs
    # at both ends of each step reproduces it exactly), reaching 1 um after 20 us. The films
    # after 20 us, stepped in n steps given the exact end-of-step inputs, against an independent
    # DOP853 solution of the film equation along that path. Interpolated, the error is Heun's
    # (measured: 3.4e-11 m at n = 1, 1.5e-12 m at n = 10, below 1 % of the films' change);
    # extrapolating from end-of-step inputs leads the path by a step: 40-70x worse.
    from scipy.integrate import solve_ivp

    from guideway_fmu.physics.roller_guide import four_rows

    span, u = 2e-5, 0.29
    a = 2e-6 / span**2  # m/s^2
    g = four_rows.Guideway()
    _, _, hu0, hl0 = four_rows.quasi_static_state(g, 0.0, u)
    ref = solve_ivp(lambda t, f: np.ravel(four_rows.film_rates(g, 0.5 * a * t * t, f[0], f[1], u)),
                    (0.0, span), [float(hu0), float(hl0)], method="DOP853", rtol=1e-12, atol=1e-20)
    error = {}
    for interpolate in (True, False):
        for n in (1, 10):
            ehl = open_fmu("ContactEHL", f"i{interpolate}{n}", y=0.0, y_dot=0.0, u=u,
                           interpolate_inputs=interpolate)
            for k in range(1, n + 1):
                t = k * span / n
                ehl.set(y=0.5 * a * t * t, y_dot=a * t)
                ehl.step(span / n)
            error[interpolate, n] = max(abs(ehl.get("h_upper") - ref.y[0, -1]),
                                        abs(ehl.get("h_lower") - ref.y[1, -1]))
    change = np.max(np.abs(ref.y[:, -1] - ref.y[:, 0]))
    assert change > 1e-4 * hu0  # the films really move (by about 5e-4)
    assert error[True, 10] < error[True, 1] / 15  # faster than first order
    assert error[True, 10] < 0.02 * change
    for n in (1, 10):
        assert error[False, n] > 20 * error[True, n]


def test_dry_contact_loss_unloads_lower_rollers_exactly(open_fmu):
    dry = open_fmu("ContactDryHertz", y=1e-4)  # 1e-4 sin 45 deg far beyond delta0
    out = dry.outputs()
    assert out["F_lower"] == 0.0
    assert all(math.isfinite(v) for v in out.values()), out
    assert out["F_upper"] == pytest.approx(hand_dry_loads(1e-4)[0], rel=1e-10)
    assert out["F_contact"] == pytest.approx(hand_dry_net_force(1e-4), rel=1e-10)


@pytest.mark.parametrize("film_model", ["extrapolated", "pan_hamrock"])
def test_ehl_film_in_submicron_range_adds_to_dry_approach(open_fmu, film_model):
    ehl = open_fmu("ContactEHL", film_model=film_model, y=1e-6, u=0.29)
    ehl.step(1e-5, n=3)
    out = ehl.outputs()
    for film in ("h_upper", "h_lower"):
        assert 0.1e-6 < out[film] < 1e-6, out
    f_upper, f_lower = hand_dry_loads(1e-6)
    assert out["F_upper"] > f_upper and out["F_lower"] > f_lower


def test_feed_biharmonic_matches_eq_1a_with_third_harmonic(open_fmu):
    feed = open_fmu("FeedKinematics")
    assert feed.get("u") == pytest.approx(0.2919 * math.sin(2.0588) + 0.0178 * math.sin(1.2679),
                                          rel=1e-12)
    feed.step(0.01, n=5)
    assert feed.get("u") == pytest.approx(hand_biharmonic_velocity(0.05), abs=1e-12)


def test_vertical_dynamics_matches_uniform_acceleration(open_fmu):
    body = open_fmu("VerticalDynamics", F_ext=1000.0, F_contact=0.0, gravity=GRAVITY, mass=MASS)
    body.step(1e-4, n=10)
    acceleration = GRAVITY + 1000.0 / MASS
    assert body.get("y") == pytest.approx(0.5 * acceleration * 1e-3**2, rel=1e-10)
    assert body.get("y_dot") == pytest.approx(acceleration * 1e-3, rel=1e-10)
    assert body.get("y_ddot") == pytest.approx(acceleration, rel=1e-12)


def test_vertical_dynamics_harmonic_oscillator_returns_after_one_period(open_fmu):
    # F_contact is the force at the start of each step, extrapolated over the step with K_contact;
    # a linear spring F = K y coupled that way is integrated to RK4 accuracy (5e-8 rad per rad,
    # physics/roller_guide/carriage.py): y = 1e-6 cos(omega t).
    stiffness = 1e6
    body = open_fmu("VerticalDynamics", K_contact=stiffness, gravity=0.0, y_start=1e-6)
    period = 2 * math.pi * math.sqrt(MASS / stiffness)
    for i in range(100):
        body.set(F_contact=stiffness * body.get("y"))
        body.step(period / 100)
        if i == 49:
            assert body.get("y") == pytest.approx(-1e-6, rel=1e-9)
    assert body.get("y") == pytest.approx(1e-6, rel=1e-9)
    assert body.get("y_dot") == pytest.approx(0.0, abs=1e-6 * 1e-6 * 2 * math.pi / period)


def test_vertical_dynamics_harmonic_load_parameters_hand_calculation(open_fmu):
    # free body, F_e = 50 + 100 sin(2 pi 50 t + 0.3): y'' = g + F_e / M at every instant
    body = open_fmu("VerticalDynamics", gravity=GRAVITY, mass=MASS, load_static=50.0,
                    load_amplitude=100.0, load_frequency=50.0, load_phase=0.3)
    body.step(1e-3, n=7)
    load = 50.0 + 100.0 * math.sin(2 * math.pi * 50.0 * 7e-3 + 0.3)
    assert body.get("y_ddot") == pytest.approx(GRAVITY + load / MASS, rel=1e-12)
    # v = g t + (static t + A / W (cos(phase) - cos(W t + phase))) / M
    w = 2 * math.pi * 50.0
    v = GRAVITY * 7e-3 + (50.0 * 7e-3 + 100.0 / w * (math.cos(0.3) - math.cos(w * 7e-3 + 0.3))) / MASS
    # the RK4 substeps (omega h <= 0.1, physics/roller_guide/carriage.py) leave 7e-9 of it
    assert body.get("y_dot") == pytest.approx(v, rel=2e-8)


def test_coulomb_friction_matches_hand_calculation(open_fmu):
    friction = open_fmu("FrictionCoulomb", coefficient=0.005, F_upper=115.0, F_lower=115.0, u=0.1)
    # -mu 2N (F_U + F_L) tanh(u / 1e-4), tanh(1000) = 1 in double precision
    assert friction.get("F_friction") == pytest.approx(-0.005 * 40 * 230, rel=1e-12)
    friction.set(u=-0.1)
    assert friction.get("F_friction") == pytest.approx(46.0, rel=1e-12)


def test_mixed_ehl_friction_opposes_feed_and_sums_its_parts(open_fmu):
    friction = open_fmu("FrictionMixedEHL", F_upper=115.0, F_lower=115.0,
                        h_upper=1e-7, h_lower=1e-7)
    parts = {}
    for u in (0.29, -0.29):
        friction.set(u=u)
        parts[u] = friction.outputs()
        total, boundary, viscous = (parts[u][k] for k in ("F_friction", "F_boundary", "F_viscous"))
        assert math.copysign(1.0, total) == -math.copysign(1.0, u)
        assert boundary != 0.0 and viscous != 0.0
        assert boundary + viscous == pytest.approx(total, rel=1e-12)
    assert parts[-0.29]["F_friction"] == pytest.approx(-parts[0.29]["F_friction"], rel=1e-12)


# -- 4. several instances in one process --------------------------------------------------------
def test_two_instances_of_one_fmu_are_independent(open_fmu):
    heavy = open_fmu("VerticalDynamics", "heavy", mass=2 * MASS, F_ext=0.0)
    pushed = open_fmu("VerticalDynamics", "pushed", mass=MASS, F_ext=1000.0)
    pushed.step(1e-4, n=10)
    assert heavy.get("y") == 0.0 and heavy.get("y_dot") == 0.0  # not stepped
    heavy.step(1e-4, n=10)
    assert heavy.get("y") == pytest.approx(0.5 * GRAVITY * 1e-6, rel=1e-10)
    assert pushed.get("y") == pytest.approx(0.5 * (GRAVITY + 1000.0 / MASS) * 1e-6, rel=1e-10)


def test_two_different_contact_fmus_side_by_side(open_fmu):
    dry = open_fmu("ContactDryHertz", y=1e-6, u=0.29)
    ehl = open_fmu("ContactEHL", y=1e-6, u=0.29)
    for _ in range(3):
        dry.step(1e-5)
        ehl.step(1e-5)
    assert dry.get("F_contact") == pytest.approx(hand_dry_net_force(1e-6), rel=1e-10)
    assert dry.get("h_upper") == 0.0
    assert 0.1e-6 < ehl.get("h_upper") < 1e-6
    assert ehl.get("F_upper") > dry.get("F_upper")


#: a row whose rear balls catch up: rail groove wave and a yaw moment
B2B = {"wave_amplitude": 0.02, "wavelength": 5e-3, "deviation_BL": -0.03, "F_normal": 420.0,
       "M_yaw": 0.3}
SIMULATIONS = {  # name -> start values of a short simulate_fmu run
    "FeedKinematics": {},
    "VerticalDynamics": {"F_ext": 1000.0},
    "ContactDryHertz": {"y": 1e-6},
    "ContactEHL": {"y": 1e-6, "u": 0.29},
    "FrictionCoulomb": {"F_upper": 115.0, "F_lower": 115.0, "u": 0.1},
    "BallCarriage5DOF": {"static_M_y": 1.45, "u_feed": 0.3},
    "FeedUnitErrors": {"F_z": -2000.0, "point_x": 0.05, "point_z": 0.1},
    "MillingForce": {"u_feed": 0.1},
    "BallToBallFriction": {**B2B, "u": 0.1},
    "Wear": {"F_load": 2000.0, "wear_coefficient": 0.5},
}


@pytest.mark.slow
def test_fmus_instantiate_again_after_a_previous_instance_was_freed(fmu_dir):
    def run(name):
        result = simulate_fmu(str(fmu_dir / f"{name}.fmu"), start_values=SIMULATIONS[name],
                              stop_time=1e-3, output_interval=1e-4)
        return [tuple(row) for row in result]

    first = {name: run(name) for name in SIMULATIONS}
    for _ in range(4):
        for name in SIMULATIONS:
            assert run(name) == first[name], name
    assert first["ContactDryHertz"][-1][1] == pytest.approx(hand_dry_net_force(1e-6), rel=1e-10)


# -- 5. FMU state --------------------------------------------------------------------------------
@pytest.mark.parametrize("name, start, h, ramp", [
    ("VerticalDynamics", {"K_contact": 1e6, "C_contact": 50.0, "F_contact": 200.0, "F_ext": 1000.0},
     1e-4, {}),
    ("ContactEHL", {"film_model": "extrapolated", "u": 0.29, "y": 1e-6, "y_dot": 1e-3}, 1e-5, {}),
    ("FeedKinematics", {}, 1e-3, {}),
    ("BallCarriage5DOF", {"static_M_y": 2.9, "F_z": -5.0, "u_feed": 0.3}, 1e-5, {}),
    ("MillingForce", {"u_feed": 0.1, "start_angle": 0.1}, 1e-4, {}),
    ("BallToBallFriction", {**B2B, "u": 0.3}, 2e-3, {}),
    ("Wear", {"F_load": 2000.0, "wear_coefficient": 0.5}, 1.0, {"distance": 1e5}),
], ids=["VerticalDynamics", "ContactEHL", "FeedKinematics", "BallCarriage5DOF", "MillingForce",
        "BallToBallFriction", "Wear"])
def test_restored_fmu_state_replays_identically(open_fmu, name, start, h, ramp):
    # ``ramp``: inputs that grow by the given amount each step (the Wear FMU follows its
    # running-distance input, not the time)
    slave = open_fmu(name, **start)

    def steps(first, count):
        out = []
        for k in range(first, first + count):
            slave.set(**{key: rate * k for key, rate in ramp.items()})
            out.append(slave.step(h).outputs())
        return out

    steps(1, 3)
    state, time = slave.fmu.getFMUstate(), slave.time
    recorded = steps(4, 5)
    assert recorded[0] != recorded[-1]  # the state really evolves
    slave.fmu.setFMUstate(state)
    slave.time = time
    assert steps(4, 5) == recorded
    slave.fmu.freeFMUstate(state)


# -- 6. bad inputs and parameters ----------------------------------------------------------------
LOADS = {"F_upper": 115.0, "F_lower": 115.0, "u": 0.1}
FILMS = {"h_upper": 1e-7, "h_lower": 1e-7}


def case(*values, id):
    return pytest.param(*values, id=id)


@pytest.mark.parametrize("name, start, bad, name_in_message", [
    case("ContactEHL", {"u": 0.29, "y": 1e-6}, {"y": NAN}, "input y", id="ContactEHL-y-nan"),
    case("FrictionCoulomb", LOADS, {"F_upper": -1.0}, "F_upper",
         id="FrictionCoulomb-F_upper-negative"),
    case("FrictionMixedEHL", {**LOADS, **FILMS}, {"F_lower": -1.0}, "F_lower",
         id="FrictionMixedEHL-F_lower-negative"),
    case("VerticalDynamics", {"F_ext": 1000.0}, {"K_contact": -1.0}, "K_contact",
         id="VerticalDynamics-K_contact-negative"),
    case("VerticalDynamics", {"F_ext": 1000.0}, {"law_force_1um": -1.0}, "law_force_1um",
         id="VerticalDynamics-law_force_1um-negative"),
    case("VerticalDynamics", {"F_ext": 1000.0}, {"law_approach_upper": NAN}, "law_approach_upper",
         id="VerticalDynamics-law_approach_upper-nan"),
    case("BallCarriage5DOF", {"static_M_y": 1.0}, {"M_z": NAN}, "M_z",
         id="BallCarriage5DOF-M_z-nan"),
    case("FeedUnitErrors", {"F_z": -1000.0}, {"point_y": float("inf")}, "point_y",
         id="FeedUnitErrors-point_y-inf"),
    case("MillingForce", {"u_feed": 0.1}, {"u_feed": NAN}, "u_feed", id="MillingForce-u_feed-nan"),
    case("BallToBallFriction", {**B2B, "u": 0.1}, {"M_yaw": 50.0}, "F_side, M_yaw",
         id="BallToBallFriction-M_yaw-two-point-contact"),
    case("BallToBallFriction", {**B2B, "u": 0.1}, {"F_normal": -1.0}, "F_normal",
         id="BallToBallFriction-F_normal-negative"),
    case("Wear", {"F_load": 2000.0}, {"distance": -1.0}, "distance", id="Wear-distance-negative"),
    case("Wear", {"F_load": 2000.0}, {"F_load": NAN}, "F_load", id="Wear-F_load-nan"),
])
def test_bad_input_discards_step_and_keeps_last_valid_outputs(open_fmu, name, start, bad,
                                                              name_in_message):
    slave = open_fmu(name, **start).step(1e-5)
    last_valid = slave.outputs()
    slave.set(**bad)
    assert_discarded(slave, 1e-5, name_in_message)
    after = slave.outputs()
    assert all(math.isfinite(v) for v in after.values()), after
    assert after == last_valid
    slave.set(**{k: start.get(k, 0.0) for k in bad})  # the instance is not fatal
    slave.step(1e-5)
    assert all(math.isfinite(v) for v in slave.outputs().values())


@pytest.mark.parametrize("name, bad, good, name_in_message", [
    case("VerticalDynamics", {"mass": -1.0}, {"mass": MASS}, "mass", id="VerticalDynamics-mass"),
    case("ContactDryHertz", {"rollers_per_groove": 0}, {"rollers_per_groove": 20},
         "rollers_per_groove", id="ContactDryHertz-rollers_per_groove"),
    case("FeedKinematics", {"profile": "nope"}, {"profile": "biharmonic"}, "profile",
         id="FeedKinematics-profile"),
    case("BallCarriage5DOF", {"conformity": 0.45}, {"conformity": 0.534}, "conformity",
         id="BallCarriage5DOF-conformity"),
    case("BallCarriage5DOF", {"ball_stiffness": "1e7 x"}, {"ball_stiffness": ""},
         "ball_stiffness", id="BallCarriage5DOF-ball_stiffness"),
    case("FeedKinematics", {"profile": "table"}, {"profile": "biharmonic"}, "table_file",
         id="FeedKinematics-table_file-empty"),
    case("FeedUnitErrors", {"balls_per_row": 60}, {"balls_per_row": 12}, "balls_per_row",
         id="FeedUnitErrors-balls_per_row-overlap"),
    case("FeedUnitErrors", {"poisson_ratio": 0.6}, {"poisson_ratio": 0.3}, "poisson_ratio",
         id="FeedUnitErrors-poisson_ratio"),
    case("MillingForce", {"exit_angle": 5.0}, {"exit_angle": math.pi}, "exit_angle",
         id="MillingForce-exit_angle"),
    case("BallToBallFriction", {"zone_length": 0.04}, {"zone_length": 0.043}, "zone_length",
         id="BallToBallFriction-zone_length-no-clearance"),
    case("Wear", {"fractal_dimension": 3.5}, {"fractal_dimension": 2.8}, "fractal dimension",
         id="Wear-fractal_dimension"),
    case("Wear", {"rolling_resistance": False, "tangential_ratio": 1.2},
         {"tangential_ratio": 0.1}, "tangential_ratio", id="Wear-tangential_ratio-sliding"),
    case("FeedKinematics", {"profile": "table", "table_file": "/nonexistent_dir/feed.csv"},
         {"profile": "biharmonic"}, "table_file", id="FeedKinematics-table_file-no-such-file"),
])
def test_bad_parameter_discards_step_naming_it_until_fixed(open_fmu, name, bad, good,
                                                           name_in_message):
    slave = open_fmu(name).step(1e-4)
    last_valid = slave.outputs()
    slave.set(**bad)
    assert_discarded(slave, 1e-4, name_in_message)
    assert slave.outputs() == last_valid
    slave.set(**good)
    slave.step(1e-4)  # not fatal: works again once the value is fixed
    assert all(math.isfinite(v) for v in slave.outputs().values())


@pytest.mark.parametrize("name, start, bad, good", [
    # omega = sqrt(K / m) = sqrt(1e30 / 3.302) = 5.5e14 rad/s: 1e-4 s would take 1.1e12 substeps
    case("VerticalDynamics", {}, {"K_contact": 1e30}, {"K_contact": 0.0},
         id="VerticalDynamics-K_contact-huge"),
    case("VerticalDynamics", {}, {"load_frequency": 1e15}, {"load_frequency": 0.0},
         id="VerticalDynamics-load_frequency-huge"),
    # the film's substep 13.2 h / |u| = 13.2 * 2.3e-7 / 1e4 = 3e-10 s: 1e-4 s takes 3.3e5
    case("ContactEHL", {"u": 0.29}, {"u": 1e4}, {"u": 0.29}, id="ContactEHL-u-huge"),
])
def test_work_inside_one_step_is_bounded_hand_values(open_fmu, name, start, bad, good):
    # more than MAX_SUBSTEPS (1e5) substeps: the step is discarded at once, naming why
    slave = open_fmu(name, **start).step(1e-4)
    slave.set(**bad)
    assert_discarded(slave, 1e-4, "substeps")
    slave.set(**good)
    slave.step(1e-4)
    assert all(math.isfinite(v) for v in slave.outputs().values())


def test_vertical_dynamics_resumes_exactly_after_bad_mass_is_fixed(open_fmu):
    body = open_fmu("VerticalDynamics", F_ext=1000.0).step(1e-4, n=5)
    body.set(mass=-1.0)
    assert_discarded(body, 1e-4, "mass")
    body.set(mass=MASS)
    body.step(1e-4, n=5)  # the discarded step did not advance the state: retry from t = 5e-4
    assert body.get("y") == pytest.approx(0.5 * (GRAVITY + 1000.0 / MASS) * 1e-3**2, rel=1e-10)


def test_feed_table_profile_replays_csv(open_fmu, tmp_path):
    table = tmp_path / "feed.csv"
    table.write_text("time,feed_velocity\n0.0,0.0\n0.1,0.2\n0.2,0.2\n")
    feed = open_fmu("FeedKinematics", profile="table", table_file=str(table))
    feed.step(0.01, n=5)  # t = 0.05: ramp at 2 m/s2
    assert feed.get("u") == pytest.approx(0.1, rel=1e-9)
    assert feed.get("a") == pytest.approx(2.0, rel=1e-9)
    assert feed.get("x") == pytest.approx(0.5 * 2.0 * 0.05**2, rel=1e-9)
    feed.step(0.01, n=10)  # t = 0.15: cruising at 0.2 m/s after 0.01 m of ramp
    assert feed.get("u") == pytest.approx(0.2, rel=1e-9)
    assert feed.get("a") == 0.0
    assert feed.get("x") == pytest.approx(0.01 + 0.2 * 0.05, rel=1e-9)


# -- 7. self-contained ---------------------------------------------------------------------------
# Runs with -I -S: no PYTHONPATH, no user site, no .pth files (so not the editable guideway_fmu);
# the host's site-packages are appended only for numpy, scipy, fmpy and pythonfmu.
_CLEAN_HOST = r"""
import json, sys
from pathlib import Path
sys.path.extend(json.loads(sys.argv[1]))
try:
    import guideway_fmu
except ImportError:
    pass
else:
    raise SystemExit(f"guideway_fmu is importable from {guideway_fmu.__file__}")
from fmpy import extract, simulate_fmu
unzip = Path(extract("ContactDryHertz.fmu", unzipdir="extracted")).resolve()
result = simulate_fmu(str(unzip), start_values={"y": 1e-6}, stop_time=1e-4, output_interval=1e-4)
modules = {name: getattr(module, "__file__", None) for name, module in sys.modules.items()
           if name.startswith(("ContactDryHertz", "guideway_fmu"))}
print(json.dumps({"F_contact": float(result["F_contact"][-1]), "modules": modules,
                  "resources": str(unzip / "resources")}), flush=True)
import os
os._exit(0)  # no interpreter finalisation: pythonfmu 0.7 with SciPy loaded may crash there
"""


def test_fmu_runs_from_its_own_resources_in_a_clean_process(fmu_dir, tmp_path):
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    shutil.copy(fmu_dir / "ContactDryHertz.fmu", elsewhere)
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    site_dirs = [d for d in site.getsitepackages() if os.path.isdir(d)]
    run = subprocess.run([sys.executable, "-I", "-S", "-c", _CLEAN_HOST, json.dumps(site_dirs)],
                         cwd=elsewhere, env=env, capture_output=True, text=True, timeout=60)
    assert run.returncode == 0, run.stderr
    report = json.loads(run.stdout.strip().splitlines()[-1])
    assert report["F_contact"] == pytest.approx(hand_dry_net_force(1e-6), rel=1e-10)
    modules = report["modules"]
    slave_scripts = [n for n in modules if n.startswith("ContactDryHertz_")]
    shipped = [n for n in modules if n.startswith("guideway_fmu_ContactDryHertz_")]
    assert slave_scripts and shipped, modules
    assert "guideway_fmu" not in modules
    for name in slave_scripts + shipped:
        assert modules[name].startswith(report["resources"] + os.sep), (name, modules[name])


# -- 8. README -----------------------------------------------------------------------------------
def _readme_units(text):
    """{FMU name: {variable: unit}} from the tables of the generated README."""
    sections = {}
    for block in text.split("\n## ")[1:]:
        title, *lines = block.splitlines()
        cells = [[c.strip() for c in line.strip("|").split("|")] for line in lines
                 if line.startswith("| `")]
        sections[title.strip()] = {row[0].strip("`"): row[3] for row in cells}
    return sections


def test_readme_lists_every_fmu_variable_with_its_unit(fmu_dir):
    sections = _readme_units((fmu_dir / "README.md").read_text())
    assert set(sections) == set(registry.names())
    for name in registry.names():
        md = read_model_description(str(fmu_dir / f"{name}.fmu"))
        assert sections[name] == {v.name: v.unit or "" for v in md.modelVariables}
        for var, (_, unit) in CONTRACT.get(name, {}).items():
            assert sections[name][var] == unit, (name, var)


def test_committed_fmus_readme_is_up_to_date(fmu_dir):
    committed = Path(__file__).resolve().parents[2] / "fmus" / "README.md"
    assert committed.read_text() == (fmu_dir / "README.md").read_text(), (
        "fmus/README.md is stale: run `guideway-fmu build` and commit it")


def test_ehl_film_integration_matches_tight_scipy_solution_of_the_array_physics(open_fmu):
    # Films start steady at u = 0.05 m/s, then the feed jumps to 0.29 m/s with the body moving
    # at 2 mm/s: the FMU's Heun substeps against solve_ivp (DOP853, rtol 1e-11) of
    # four_rows.film_rates, the array functions (independent of the float kernel).
    from scipy.integrate import solve_ivp

    from guideway_fmu.physics.roller_guide import four_rows as gw
    y0, v, u, h, n = 1e-7, 2e-3, 0.29, 2e-6, 250
    contact = open_fmu("ContactEHL", y=y0, y_dot=v, u=0.05)
    films = [contact.get("h_upper"), contact.get("h_lower")]
    contact.set(u=u)
    g = gw.Guideway()
    for i in range(n):
        contact.set(y=y0 + v * i * h)
        contact.step(h)
    sol = solve_ivp(lambda t, f: gw.film_rates(g, y0 + v * t, f[0], f[1], u), (0.0, n * h), films,
                    method="DOP853", rtol=1e-11, atol=1e-20)
    change = abs(sol.y[0, -1] - films[0])
    assert change > 1e-8  # the film really moved (from its 0.05 m/s value towards 0.29 m/s)
    assert contact.get("h_upper") == pytest.approx(sol.y[0, -1], abs=1e-4 * change)
    assert contact.get("h_lower") == pytest.approx(sol.y[1, -1], abs=1e-4 * abs(sol.y[1, -1] - films[1]))


# -- 7. the ball carriage ------------------------------------------------------------------------
def test_ball_carriage_starts_in_equilibrium_under_the_moment_hand_check(open_fmu):
    # Wu et al. (2012): M_y tilts the carriage (theta > 0); the rows share the load alike; at
    # rest nothing moves
    slave = open_fmu("BallCarriage5DOF", static_M_y=2.9)
    before = slave.outputs()
    slave.step(1e-5, n=20)
    after = slave.outputs()
    assert after["theta"] > 0.0 and after["theta"] == pytest.approx(before["theta"], rel=1e-9)
    assert after["row_load_1"] == pytest.approx(after["row_load_2"], rel=1e-12)
    assert after["row_load_1"] == pytest.approx(9 * 46.6, rel=0.02)  # ~ 9 balls at preload


def test_ball_carriage_vertical_oscillation_has_the_modal_frequency_limiting_case(open_fmu):
    # undamped, released from equilibrium under F_z = -5 N when the force drops to 0: the
    # vertical mode alone, at the frequency of the tangent stiffness (3.6 kHz for Table 2)
    from guideway_fmu.physics.ball_guides import carriage_5dof as bc
    slave = open_fmu("BallCarriage5DOF", F_z=-0.5, ball_damping=0.0)
    slave.set(F_z=0.0)
    h, v = 2e-6, []
    for _ in range(1500):
        slave.step(h)
        v.append(slave.get("v"))
    v = np.array(v) - np.mean(v)
    crossings = np.flatnonzero(np.sign(v[:-1]) != np.sign(v[1:]))
    t = (crossings - v[crossings] / (v[crossings + 1] - v[crossings])) * h
    frequency = (len(t) - 1) / (2 * (t[-1] - t[0]))
    model = bc.from_parameters(**{**slave_parameters(), "ball_damping": 0.0})
    balls = bc.HertzBalls(model.body, bc.ball_positions(9, 43e-3 / 9), model.k_h, 46.6)
    expected = bc.modes(balls.tangent(np.zeros(5)), model.body.mass_matrix()).frequencies[3]
    assert frequency == pytest.approx(expected, rel=5e-3)


def slave_parameters():
    """The BallCarriage5DOF defaults, as its model factory takes them."""
    from guideway_fmu.components.ball_guides.carriage_5dof import BallCarriage5DOF
    return BallCarriage5DOF(instance_name="defaults", resources=None).parameter_values()


def test_ball_carriage_without_equilibrium_at_the_start_fails_initialisation_saying_why(fmu_dir):
    # a lateral force alone drives the motion two rows of balls do not resist (Wu et al.'s model):
    # no start in static equilibrium, an error of exitInitializationMode (before: fmi2OK, then
    # every step discarded)
    from guideway_fmu.cosim.fmu_instance import FmuInstance

    inst = FmuInstance(fmu_dir / "BallCarriage5DOF.fmu", "carriage")
    try:
        with pytest.raises(FMICallException) as info:
            inst.initialise(0.0, {"static_F_y": 5.0})
        assert info.value.status == STATUS_ERROR
        assert any("no ball resists" in line for line in inst.log), list(inst.log)
    finally:
        inst.close()  # the instance is kept after fmi2Error: terminated and freed as usual


def test_feed_unit_fmu_under_a_central_vertical_load_hand_calculation(open_fmu):
    # 16 n balls at 45 deg share a small central load F equally: each ball's approach grows by
    # w sin 45 for the upper rows and shrinks by it for the lower ones, so to first order
    # F = 16 n k0 sin^2(45) w with k0 = 1.5 Q0 / delta_p the rest stiffness of one ball, plus
    # the turning of the preloaded lines (Q0 / L0 cos^2 45 per ball) with the angle change.
    # Ball: 3/16 in, f = 0.52, steel (2 / E' = 2 (1 - nu^2) / E); delta_p from Q0 = 20 N.
    from scipy.optimize import brentq
    from scipy.special import ellipe, ellipk
    d, f, q0, n = 4.7625e-3, 0.52, 20.0, 12
    curvature_sum = (4 - 1 / f) / d
    difference = 1 / (4 * f - 1)
    kappa = brentq(lambda k: ((k**2 + 1) * ellipe(1 - k**-2) - 2 * ellipk(1 - k**-2))
                   / ((k**2 - 1) * ellipe(1 - k**-2)) - difference, 1.0001, 100.0)
    e_red = 206e9 / (1 - 0.3**2)
    m = 1 - kappa**-2
    one = ellipk(m) * (9 / (2 * ellipe(m) / curvature_sum) * (q0 / (math.pi * kappa * e_red)) ** 2) ** (1 / 3)
    rest = 2 * one  # two equal contacts in series carry the same load
    k0 = 1.5 * q0 / rest
    turn = q0 / ((2 * f - 1) * d + rest)
    force = 20.0
    for change, extra in ((False, 0.0), (True, turn)):
        slave = open_fmu("FeedUnitErrors", F_z=-force, angle_change=change).step(1e-3)
        w = force / (16 * n * (k0 * 0.5 + extra * 0.5))
        assert slave.outputs()["delta_z"] == pytest.approx(-w, rel=1e-3)
        assert abs(slave.outputs()["epsilon_y"]) < 1e-15


def test_milling_force_fmu_follows_the_spindle_hand_calculation(open_fmu):
    # one tooth at phi = pi/2 at t = 0: the table takes (F_r, -F_t, -F_a); a quarter turn later
    # (phi = pi, the exit of a slot) h = 0 and only the edge forces act, F_t along -x on the tool
    slave = open_fmu("MillingForce", u_feed=0.1, teeth=1, start_angle=math.pi / 2)
    c = 0.1 / 200.0
    out = slave.outputs()
    assert out["F_x"] == pytest.approx(170e6 * 2e-3 * c + 31e3 * 2e-3, rel=1e-12)
    assert out["F_y"] == pytest.approx(-(800e6 * 2e-3 * c + 28e3 * 2e-3), rel=1e-12)
    slave.step(1.0 / 800.0 - 1e-12)
    out = slave.outputs()
    assert out["F_x"] == pytest.approx(-28e3 * 2e-3, rel=1e-5)
    assert out["F_z"] == pytest.approx(-2e3 * 2e-3, rel=1e-5)


# -- 8. wear ------------------------------------------------------------------------------------
def test_wear_fmu_stepped_along_the_distance_matches_the_wear_command_physics(open_fmu):
    # 40 steps of 1e5 m against one solve_ivp over 4e6 m with the preload loss as an event:
    # independent integrations of the same rates
    from guideway_fmu.physics.wear import raceway_wear
    guide = raceway_wear.Guide(wear_coefficient=0.5)
    run = raceway_wear.simulate(guide, 2000.0, 4e6, 41)
    slave = open_fmu("Wear", F_load=2000.0, wear_coefficient=0.5)
    got = []
    for k in range(1, 41):
        slave.set(distance=1e5 * k)
        got.append(slave.step(10.0).outputs())
    for key in ("wear_depth", "preload_deformation", "vertical_displacement", "preload"):
        ours = np.array([row[key] for row in got])
        np.testing.assert_allclose(ours, run.columns[key][1:], rtol=2e-6,
                                   atol=1e-6 * np.ptp(run.columns[key]), err_msg=key)
    assert run.preload_lost_at is not None  # the run crosses the loss: preload reaches 0
    assert got[-1]["preload"] == 0.0 and got[-1]["preload_deformation"] < 0


def test_wear_fmu_refuses_a_running_distance_that_goes_back(open_fmu):
    slave = open_fmu("Wear", F_load=2000.0, distance=10.0)
    slave.set(distance=100.0)
    slave.step(1.0)
    slave.set(distance=50.0)
    assert_discarded(slave, 1.0, "must not decrease")
    slave.set(distance=150.0)
    slave.step(1.0)  # not fatal
    assert slave.get("wear_depth") > 0
