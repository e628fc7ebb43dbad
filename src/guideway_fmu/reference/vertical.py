"""The vertical rig's equations fused into one right-hand side, for fits that simulate it often.

The system is that of the vertical diagnosis (``diagnose/vertical.py``): a feed replay and a
force table drive a VerticalDynamics carriage coupled to a roller contact (dry or with its two
film states), y and y_dot to the contact and its force back. Its models are the monolithic
reference's own (``monolithic._Assembly``: each component's continuous-time model from its
FMU's start values and the scenario's parameters), so the equations are those of ``physics/``;
only the assembly is fused. The right-hand side calls the models on plain floats
(CarriageModel.acceleration, RollerContact.evaluate, the replay's velocity_at, the table) in
place of the generic assembly's dictionaries of inputs and topological walk: about a fifth of
its cost.

The measured inputs are tables on the sample times, linear between them: their slopes jump at
every sample. A multistep method (LSODA, the generic reference's) carries its history across
those kinks, which keeps it at order 2-4 and about 12 steps per sample interval. A one-step
method restarted at every sample sees only smooth pieces: Hairer's DOP853 (``scipy.integrate.ode``,
Fortran) takes one 12-stage step per interval, about half the right-hand sides, and comes out
two to three orders of magnitude closer to the exact solution at the same tolerance.
"""
from __future__ import annotations

import numpy as np
from scipy.integrate import ode

from .monolithic import _Assembly

#: the wiring the fused model stands for: (target, input) -> (source, output)
WIRING = {("Contact", "y"): ("Carriage", "y"), ("Contact", "y_dot"): ("Carriage", "y_dot"),
          ("Contact", "u"): ("Feed", "u"), ("Carriage", "F_contact"): ("Contact", "F_contact"),
          ("Carriage", "F_ext"): ("Load", "F")}
COLUMNS = ("Carriage.y", "Carriage.y_ddot")
MAX_STEPS = 100_000  # DOP853 steps within one sample interval, at most


class FusedVertical:
    """The vertical system of FMUs ``system`` (a cosim.system.System wired as WIRING, its
    components named Feed, Load, Carriage and Contact) as one right-hand side. Raises
    ValueError naming the component or connection that differs."""

    def __init__(self, system):
        assembly = _Assembly(system)
        wiring = {(c.target, c.input): (c.source, c.output) for c in system.connections}
        for key, source in WIRING.items():
            if wiring.get(key) != source:
                raise ValueError(f"{system.name}: the fused vertical model needs "
                                 f"{'.'.join(source)} -> {'.'.join(key)}, got "
                                 f"{'.'.join(wiring[key]) if key in wiring else 'none'}")
        models = {name: assembly.blocks[name].model for name in ("Feed", "Load", "Carriage",
                                                                   "Contact")}
        self.carriage, self.contact = models["Carriage"], models["Contact"]
        self.velocity = models["Feed"].profile.velocity_at
        self.load = models["Load"].table
        self.t_start = system.experiment.start
        self.start = assembly.initial_state(self.t_start)
        self.scales = np.asarray([s for name in ("Carriage", "Contact")
                                  for s in models[name].state_scales()], dtype=float)
        self.films = len(self.contact.states)

    def rhs(self, t: float, x) -> tuple:
        """d(y, y_dot[, h_upper, h_lower])/dt at the time t [s]."""
        x = x.tolist()  # floats: the models' arithmetic is several times faster on them
        y, y_dot = x[0], x[1]
        rates, out = self.contact.evaluate(t, x[2:], {"y": y, "y_dot": y_dot,
                                                      "u": self.velocity(t)})
        return (y_dot, self.carriage.acceleration(t, out["F_contact"], self.load(t)),
                *rates[:self.films])

    def simulate(self, times, rtol: float, columns=COLUMNS) -> dict[str, np.ndarray]:
        """``columns`` (of COLUMNS) at the sample times ``times`` [s] (increasing, the first the
        system's start): DOP853 from sample to sample (module doc) at the relative tolerance
        ``rtol`` and the absolute tolerance rtol x the smallest nominal scale of the states
        (dop853 takes one). Raises ValueError for times it cannot take, RuntimeError when the
        integration fails."""
        times = np.asarray(times, dtype=float)
        steps = np.diff(times)
        if times.ndim != 1 or times.size < 2 or times[0] != self.t_start or np.any(steps <= 0):
            raise ValueError(f"times must increase from the start time {self.t_start} s, got "
                             f"{times!r}")
        for name in columns:
            if name not in COLUMNS:
                raise ValueError(f"column {name!r}: the fused vertical model gives "
                                 f"{', '.join(COLUMNS)}")
        solver = ode(self.rhs).set_integrator(
            "dop853", rtol=rtol, atol=rtol * float(self.scales.min()),
            first_step=float(steps.max()), nsteps=MAX_STEPS)
        solver.set_initial_value(self.start, times[0])
        states = np.empty((times.size, self.start.size))
        states[0] = self.start
        for i in range(1, times.size):
            states[i] = solver.integrate(times[i])
            if not solver.successful():
                raise RuntimeError(f"fused vertical model: DOP853 failed at t = {solver.t} s "
                                   f"(rtol {rtol}, return code {solver.get_return_code()})")
        out = {"Carriage.y": states[:, 0].copy()}
        if "Carriage.y_ddot" in columns:
            out["Carriage.y_ddot"] = np.array([self.rhs(t, x)[1] for t, x in zip(times, states)])
        return {name: out[name] for name in columns}
