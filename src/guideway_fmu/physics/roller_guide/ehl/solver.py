"""Newton-Krylov solution of the discrete mixed-EHL equations: steady and transient."""
from __future__ import annotations

import math
from dataclasses import replace
from typing import Callable

import numpy as np
from scipy.sparse.linalg import LinearOperator, gmres

from ... import checks
from .discretisation import Equations, Grid, Jacobian
from .inputs import LineContactEHL, martin, pan_hamrock
from .results import EHLResult, TransientResult

NODES_PER_INLET_LENGTH = 40  # default grid: spacing <= s / 40 (H_c, H_min within ~1 %)
MIN_NODES, MAX_NODES = 513, 16385  # bounds of the default grid
COARSEST = 129  # fewest nodes of the nested (coarse-to-fine) iteration
COARSEST_SPACING = 0.25  # ... and its largest spacing, in inlet lengths s
COARSE_TOLERANCE = 1e-4  # Newton tolerance on the coarser grids (only a start for the next)
COARSE_ITERATIONS = 100  # iteration limit on the coarsest grid (damped start from Hertz)
GMRES_RTOL = 1e-4  # relative tolerance of each left-preconditioned linear solve
GMRES_RESTART, GMRES_MAX_RESTARTS = 40, 10
LOAD_TOLERANCE = 1e-9  # relative load-balance residual accepted at convergence
SUBSTEP_HALVINGS = 6  # a failed time step is halved at most this often
#: Newton limit of each step of a transient (solve_transient): a falling load opens the film
#: faster than the inlet fills it, the inlet cavitates and the front of the cavitated stretch
#: moves a few nodes per iteration (the exit condition frees only nodes beside pressurised
#: ones), whatever the time step; up to 67 iterations on the default grids of the shipped
#: lubricated scenarios' records, where 50 failed
STEP_ITERATIONS = 200


class EHLConvergenceError(RuntimeError):
    """The Newton iteration did not reach the requested tolerance."""


def inlet_length(contact: LineContactEHL) -> float:
    """s = sqrt(2 H) [Hertz half-widths], H the estimated central film in Hertz units: where
    the rigid gap has doubled; the length over which the inlet pressure builds up."""
    return math.sqrt(2.0 * contact.film_estimate() * math.pi / (8.0 * contact.W))


def _domain(contact: LineContactEHL, inlet, outlet):
    """Domain ends [Hertz half-widths]: by default [-4.5, 1.5] widened by s, upstream by 4 s in
    the EHL regime and up to 20 s for a rigid contact (Martin's film > Pan-Hamrock's), whose
    inlet pressure decays only like x^-2 (Martin's film within 1 % at 20 s, 12 % low at 4 s)."""
    s = inlet_length(contact)
    if inlet is None:
        pan = pan_hamrock(contact.W, contact.U, contact.G)[0]
        rigid = martin(contact.W, contact.U) / pan if pan > 0.0 else math.inf
        inlet = -(4.5 + (4.0 + 16.0 * (1.0 if rigid == math.inf else rigid / (1.0 + rigid))) * s)
    outlet = 1.5 + s if outlet is None else outlet
    checks.finite("inlet", inlet)
    checks.finite("outlet", outlet)
    if not inlet < -1.0:
        raise ValueError(f"inlet must be < -1 (Hertz half-widths), got {inlet!r}")
    if not outlet > 1.0:
        raise ValueError(f"outlet must be > 1 (Hertz half-widths), got {outlet!r}")
    return float(inlet), float(outlet)


def _default_nodes(length: float, s: float) -> int:
    """2^k + 1 nodes giving a spacing <= s / NODES_PER_INLET_LENGTH, within the bounds."""
    cells = max(length * NODES_PER_INLET_LENGTH / s, 1.0)
    return int(min(max(2 ** math.ceil(math.log2(cells)) + 1, MIN_NODES), MAX_NODES))


def transient_grid(first: LineContactEHL, peak_load: float) -> tuple[float, float, int]:
    """(inlet, outlet, nodes) of a transient that starts at ``first`` and reaches ``peak_load``
    [N/m]: ends in Hertz half-widths of ``first`` holding the default domains of both contacts,
    at the finer of their default spacings (a transient keeps the grid of its first state)."""
    heavy = replace(first, load=peak_load)
    r = heavy.half_width / first.half_width
    inlet0, outlet0 = _domain(first, None, None)
    inlet1, outlet1 = _domain(heavy, None, None)
    inlet, outlet = min(inlet0, r * inlet1), max(outlet0, r * outlet1)
    spacing = min(inlet_length(first), r * inlet_length(heavy))
    return inlet, outlet, _default_nodes(outlet - inlet, spacing)


def krylov_step(jac: Jacobian, F):
    """Newton step d of J d = -F: GMRES on M^-1 J d = -M^-1 F with J applied by FFT and M^-1
    the bordered-band LU (discretisation.Jacobian.preconditioner). Returns (d, iterations)."""
    precondition = jac.preconditioner()
    operator = LinearOperator((jac.size, jac.size), dtype=float,
                              matvec=lambda v: precondition(jac.matvec(v)))
    counter = []
    step, _ = gmres(operator, -precondition(F), rtol=GMRES_RTOL, restart=GMRES_RESTART,
                    maxiter=GMRES_MAX_RESTARTS, callback=counter.append, callback_type="pr_norm")
    return step, len(counter)


def newton(eq: Equations, P, H, H00, tol: float, max_iterations: int, linear_step=krylov_step):
    """Damped Newton iteration from (P, H, H00); returns (P, H, H00, iterations, linear its).

    ``linear_step(jacobian, F) -> (d, iterations)`` solves J d = -F (default
    :func:`krylov_step`; benchmarks/ehl_speed.py passes its dense baseline).
    A step is shortened so that the viscosity changes by at most a factor e at any node and the
    film keeps > 10 % of its value: from the Hertz start, full steps through the exponential
    viscosity diverge. The exit-condition penalty is not differentiable at P = 0; where the
    cavitation point falls on a node whose P and Reynolds residual are both ~0, Newton can cycle
    between penalising that node and not. A set of penalised nodes met before is therefore
    pinned (held at P = 0), with the nodes of the cycle, for the rest of the iteration.
    Converged when a full step changes P by <= tol (P ~ 1 at the Hertz peak) and H by
    <= tol * min(H), and the load balance holds to LOAD_TOLERANCE.
    """
    n = eq.grid.n
    linear = 0
    pinned = np.zeros(n - 2, dtype=bool)
    seen = []
    for iteration in range(1, max_iterations + 1):
        F, jac = eq.residual(P, H, H00, pinned=pinned)
        if not np.all(np.isfinite(F)):
            break
        key = jac.penalised.tobytes()
        if key in seen:
            for earlier in seen[seen.index(key):]:
                pinned |= np.frombuffer(earlier, dtype=bool)
            seen.clear()
            F, jac = eq.residual(P, H, H00, pinned=pinned)
        seen.append(key)
        step, its = linear_step(jac, F)
        linear += its
        dP, dH, dH00 = step[:n], step[n:2 * n], step[2 * n]
        growth = np.max(np.abs(dP) * eq.lubricant(P)[1])
        shrink = np.max(-dH / np.maximum(H, 1e-300))
        a = min(1.0, 1.0 / max(growth, 1e-300), 0.9 / max(shrink, 1e-300))
        P, H, H00 = P + a * dP, H + a * dH, H00 + a * dH00
        film = max(np.min(H), 1e-6 * np.max(H))
        if a == 1.0 and np.max(np.abs(dP)) <= tol and np.max(np.abs(dH)) <= tol * film:
            load_error = abs(eq.residual(P, H, H00, jacobian=False)[-1]) / eq.load_target
            if load_error <= LOAD_TOLERANCE:
                return P, H, H00, iteration, linear
    raise EHLConvergenceError(
        f"EHL Newton iteration did not converge in {max_iterations} iterations on {n} nodes "
        f"(spacing {eq.grid.dx:.3g} b; W={eq.contact.W:.3g}, U={eq.contact.U:.3g}, "
        f"G={eq.contact.G:.3g}); more nodes may help at heavy loads")


def _hertz_start(eq: Equations):
    """The Hertz pressure of the current load (a semi-ellipse, widened to >= 4 cells and to
    s / 2 where the film is thick), the film it deforms to with the estimated central film,
    and H00."""
    g = eq.grid
    width = max(math.sqrt(eq.load_target / (0.5 * math.pi)), 4.0 * g.dx,
                0.5 * math.sqrt(2.0 * eq.film_scale))
    P = np.sqrt(np.clip(1.0 - (g.X / width) ** 2, 0.0, None))
    P *= eq.load_target / (g.dx * np.sum(P))
    deformation = g.deformation(P)
    H00 = eq.film_scale - np.interp(0.0, g.X, deformation)
    return P, H00 + 0.5 * g.X**2 + deformation, H00


def _levels(nodes: int, length: float, spacing: float):
    """Grid sizes of the nested iteration: ``nodes`` halved while the grid keeps at least
    COARSEST nodes and a spacing <= ``spacing`` on the domain ``length``."""
    sizes = [nodes]
    while True:
        coarser = (sizes[-1] - 1) // 2 + 1
        if coarser < COARSEST or length / (coarser - 1) > spacing:
            return sizes[::-1]
        sizes.append(coarser)


def _check_numerics(nodes, tol, max_iterations):
    if nodes is not None:
        checks.positive_integer("nodes", nodes)
        if nodes < 33:
            raise ValueError(f"nodes must be >= 33, got {nodes!r}")
    checks.in_range("tol", tol, 1e-13, 1e-3)
    checks.positive_integer("max_iterations", max_iterations)


def _result(eq: Equations, contact: LineContactEHL, P, H, iterations, linear, time=0.0):
    """EHLResult of the state (P, H) of ``eq`` for the conditions of ``contact``."""
    P = np.maximum(P, 0.0)  # the penalty leaves P ~ -1e-8 where the film cavitates
    flux, _ = eq.fluxes(P, H)
    pa, _ = eq.asperity(H)
    return EHLResult(contact=contact, x=eq.grid.X * eq.contact.half_width,
                     p_h=P * eq.p_scale, p_a=pa * eq.p_scale, h=H * eq.h_unit,
                     mass_flow=-eq.flux_unit * flux, iterations=iterations,
                     linear_iterations=linear, time=time)


def steady_state(contact: LineContactEHL, *, nodes=None, inlet=None, outlet=None,
                 tol: float = 1e-8, max_iterations: int = 50, linear_step=krylov_step,
                 nested: bool = True):
    """(Equations on the final grid, P, H, H00, Newton iterations, linear iterations).

    Nested iteration: Newton from the Hertz start on the coarsest grid, each solution
    interpolated as the start on the grid with twice the nodes, up to ``nodes``.
    ``nested=False``: Newton from the Hertz start on the final grid only (the textbook
    approach; benchmarks/ehl_speed.py times it as the baseline).
    """
    contact.validate()
    _check_numerics(nodes, tol, max_iterations)
    if not contact.entrainment_velocity > 0.0:
        raise ValueError("entrainment_velocity must be > 0 for a steady solution")
    inlet, outlet = _domain(contact, inlet, outlet)
    s = inlet_length(contact)
    nodes = _default_nodes(outlet - inlet, s) if nodes is None else nodes
    film_scale = contact.film_estimate() * math.pi / (8.0 * contact.W)
    total = linear = 0
    state = None
    for size in _levels(nodes, outlet - inlet, COARSEST_SPACING * s) if nested else [nodes]:
        eq = Equations(contact, Grid(inlet, outlet, size), film_scale)
        level_tol = tol if size == nodes else max(tol, COARSE_TOLERANCE)
        if state is None:
            P, H, H00, its, lin = newton(eq, *_hertz_start(eq), level_tol,
                                         max(max_iterations, COARSE_ITERATIONS), linear_step)
        else:
            X, P, H, H00 = state
            P, H = np.interp(eq.grid.X, X, P), np.interp(eq.grid.X, X, H)
            P, H, H00, its, lin = newton(eq, P, H, H00, level_tol, max_iterations, linear_step)
        total, linear = total + its, linear + lin
        state = (eq.grid.X, P, H, H00)
    return eq, P, H, H00, total, linear


def solve_steady(contact: LineContactEHL, *, nodes: int | None = None, inlet: float | None = None,
                 outlet: float | None = None, tol: float = 1e-8,
                 max_iterations: int = 50) -> EHLResult:
    """Steady mixed-EHL solution of ``contact``.

    nodes: uniform grid nodes (default: 2^k + 1 with spacing <= s/40, 513..16385, which keeps
    H_c and H_min within ~1 % of the grid limit); inlet, outlet: domain ends in Hertz
    half-widths (default from the estimated film); tol: Newton tolerance (see :func:`newton`).
    Raises ValueError naming an invalid input, EHLConvergenceError if Newton does not converge.
    """
    eq, P, H, _, its, lin = steady_state(contact, nodes=nodes, inlet=inlet, outlet=outlet,
                                         tol=tol, max_iterations=max_iterations)
    return _result(eq, contact, P, H, its, lin)


def solve_dimensionless(W: float, U: float, G: float, **options) -> EHLResult:
    """Steady solution for Hamrock's W, U, G.

    ``options``: those of :func:`solve_steady` (nodes, inlet, outlet, tol, max_iterations) and
    of :meth:`LineContactEHL.from_dimensionless` (radius, e_reduced, viscosity, roughness, ...).
    """
    numerics = {k: options.pop(k) for k in ("nodes", "inlet", "outlet", "tol", "max_iterations")
                if k in options}
    return solve_steady(LineContactEHL.from_dimensionless(W, U, G, **options), **numerics)


def _history(name, values, size, default):
    if values is None:
        return np.full(size, float(default))
    arr = checks.finite(name, values)
    if arr.shape != (size,):
        raise ValueError(f"{name} must have one value per time ({size}), got shape {arr.shape}")
    return arr


def solve_transient(contact: LineContactEHL, times, loads, *, entrainment_velocities=None,
                    sliding_velocities=None, nodes: int | None = None,
                    inlet: float | None = None, outlet: float | None = None,
                    tol: float = 1e-8, max_iterations: int = STEP_ITERATIONS,
                    progress: Callable[[float], None] | None = None) -> TransientResult:
    """Transient (squeeze-film) solution for the load history ``loads`` [N/m] at ``times`` [s].

    Velocity histories [m/s] default to the contact's constant velocities; the first
    entrainment velocity must be > 0 (later ones may be 0: pure squeeze). steps[0] is the
    steady state at times[0]; the later steps solve eqs. 15-23 with d(rho h)/dt by the
    variable-step BDF2 formula (backward Euler on the first step), on the grid and in the
    Hertz units of the first state. A step whose Newton iteration fails is split in two, with
    the histories interpolated linearly, up to SUBSTEP_HALVINGS times; ``max_iterations``
    bounds the Newton iteration of each (see STEP_ITERATIONS). contact.load and its
    velocities are replaced by the histories. ``progress``, if given, is called with each time
    [s] once its state is solved (times[0] included). Raises EHLConvergenceError naming the
    time of a step that still does not converge.
    """
    times = checks.finite("times", times)
    if times.ndim != 1 or times.size < 2 or np.any(np.diff(times) <= 0.0):
        raise ValueError("times must be a strictly increasing 1-D array of at least 2 values")
    loads = checks.positive("loads", _history("loads", loads, times.size, 0.0))
    u_m = checks.non_negative("entrainment_velocities", _history(
        "entrainment_velocities", entrainment_velocities, times.size, contact.entrainment_velocity))
    u_s = _history("sliding_velocities", sliding_velocities, times.size, contact.sliding_velocity)

    def at(k):
        return replace(contact, load=float(loads[k]), entrainment_velocity=float(u_m[k]),
                       sliding_velocity=float(u_s[k]))

    eq, P, H, H00, its, lin = steady_state(at(0), nodes=nodes, inlet=inlet, outlet=outlet,
                                           tol=tol, max_iterations=max_iterations)
    steps = [_result(eq, at(0), P, H, its, lin, float(times[0]))]
    reached = progress or (lambda time: None)
    reached(float(times[0]))
    march = _March(eq, (P, H, H00), float(times[0]), tol, max_iterations)
    for k in range(1, times.size):
        march.advance(float(times[k]), loads[k] / loads[0], u_m[k], SUBSTEP_HALVINGS)
        steps.append(_result(eq, at(k), *march.state[:2], march.iterations, march.linear,
                             float(times[k])))
        march.iterations = march.linear = 0
        reached(float(times[k]))
    return TransientResult(tuple(steps))


class _March:
    """Time stepping of one transient: the state, its BDF history and the iteration counts."""

    def __init__(self, eq: Equations, state, time: float, tol: float, max_iterations: int):
        self.eq, self.state, self.time = eq, state, time
        self.tol, self.max_iterations = tol, max_iterations
        self.load_ratio, self.velocity = 1.0, eq.contact.entrainment_velocity
        self.q, self.q_before, self.dt_before = self.eq.content(*state[:2]), None, None
        self.iterations = self.linear = 0

    def advance(self, time: float, load_ratio: float, velocity: float, halvings: int):
        """Step to ``time``, where the load ratio and velocity reach the given values."""
        dt = time - self.time
        if self.dt_before is None:  # backward Euler
            gain, history = 1.0 / dt, -self.q / dt
        else:  # BDF2 with the step ratio w
            w = dt / self.dt_before
            gain = (1.0 + 2.0 * w) / ((1.0 + w) * dt)
            history = (w * w / (1.0 + w) * self.q_before - (1.0 + w) * self.q) / dt
        self.eq.set_conditions(load_ratio, velocity, gain, history)
        try:
            *state, its, lin = newton(self.eq, *self.state, self.tol, self.max_iterations)
        except EHLConvergenceError as exc:
            if halvings == 0:
                raise EHLConvergenceError(f"at t = {time:.6g} s: {exc}") from None
            middle = self.time + 0.5 * dt
            self.advance(middle, 0.5 * (self.load_ratio + load_ratio),
                         0.5 * (self.velocity + velocity), halvings - 1)
            self.advance(time, load_ratio, velocity, halvings - 1)
            return
        self.iterations += its
        self.linear += lin
        self.q_before, self.q, self.dt_before = self.q, self.eq.content(*state[:2]), dt
        self.state, self.time = tuple(state), time
        self.load_ratio, self.velocity = load_ratio, velocity
