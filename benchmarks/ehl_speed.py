"""Wall time of the mixed-EHL solver (physics/roller_guide/ehl) against a dense-matrix Newton baseline.

Steady smooth line contact at W = 1e-4, U = 1e-11, G = 4500 (Soleimanian et al.'s check point) on
N = 513, 1025 and 2049 nodes, all measured in one run (wall time: the least of REPEAT runs):

(a) the solver as shipped: nested iteration from the Hertz start, Newton-Krylov steps
    (GMRES, FFT matrix-vector products, bordered-band preconditioner);
(b) the dense baseline, the anchor: the same discretisation and the same damped Newton
    iteration, started from the Hertz pressure on the N-node grid itself, each step assembled
    as a dense (N+1) x (N+1) matrix (film eliminated: dR/dP + dR/dH D, D the elastic
    influence matrix) and solved by LAPACK LU (numpy.linalg.solve);
(c) the dense linear solve inside the solver's nested iteration: (a) with its linear
    solver swapped for (b)'s, separating the gain of the linear algebra from the gain of the
    nested start.

Prints the times, iteration counts, H_c of each (they must agree), the ratios (b)/(a) and
(c)/(a) at N = 2049, and the scaling check t(2049)/t(513) against the N log N ratio 4.9.
Usage: ``python benchmarks/ehl_speed.py [--out docs/ehl-speed.md]``; the printout is also written
to that page.
"""
from __future__ import annotations

import argparse
import builtins
import math
import sys
import time
import weakref
from pathlib import Path

import numpy as np
from scipy.linalg import solve_banded, toeplitz

from guideway_fmu.physics.roller_guide.ehl import LineContactEHL, solver

import pages

W, U, G = 1e-4, 1e-11, 4500.0
SIZES = (513, 1025, 2049)
REPEAT = 5  # runs of the fast solver; the wall time printed is the least (CPU time alongside)
REPEAT_DENSE = 1  # the dense runs take seconds each
_INFLUENCE = weakref.WeakKeyDictionary()  # dense elastic matrix per grid, built once per grid


def dense_step(jac, F):
    """Newton step of J d = -F by dense LU on the film-eliminated (N+1) x (N+1) system."""
    eq = jac.eq
    g = eq.grid
    n = g.n
    if np.any(jac.dpa):
        raise ValueError("the dense baseline handles smooth surfaces only")
    D = _INFLUENCE.get(g)
    if D is None:
        D = _INFLUENCE.setdefault(g, toeplitz(g.column))
    # film residual r = H - H00 - X^2/2 - D P from its rows [r_0, second differences, r_n-1]
    tri = np.zeros((3, n))
    tri[0, 2:], tri[1, :], tri[2, :-2] = 1.0, -2.0, 1.0
    tri[1, [0, -1]] = 1.0
    r = solve_banded((1, 1), tri, F[n:2 * n])
    # Reynolds rows: R_P dP + R_H dH = -F_rey, with dH = -r + dH00 + D dP
    R_P = np.zeros((n, n))
    R_P[[0, n - 1], [0, n - 1]] = 1.0
    R_H_D = np.zeros((n, n))
    R_H_one = np.zeros(n)
    R_H_r = np.zeros(n)
    rows = np.arange(1, n - 1)
    for o in jac.cP:
        cols = (rows + o).clip(0)
        R_P[rows, cols] += jac.cP[o]
        R_H_D[1:-1] += jac.cH[o][:, None] * D[cols]
        R_H_one[1:-1] += jac.cH[o]
        R_H_r[1:-1] += jac.cH[o] * r[cols]
    A = np.empty((n + 1, n + 1))
    A[:n, :n] = R_P + R_H_D
    A[:n, n] = R_H_one
    A[n, :n], A[n, n] = g.dx, 0.0
    rhs = np.concatenate([-F[:n] + R_H_r, [-F[-1]]])
    solution = np.linalg.solve(A, rhs)
    dP, dH00 = solution[:n], solution[n]
    return np.concatenate([dP, -r + dH00 + D @ dP, [dH00]]), 0


def timed(run, repeat):
    """(least wall time [s], its CPU time [s], result) of ``repeat`` calls of ``run``."""
    best, out = (math.inf, math.inf), None
    for _ in range(repeat):
        wall, cpu = time.perf_counter(), time.process_time()
        out = run()
        best = min(best, (time.perf_counter() - wall, time.process_time() - cpu))
    return best[0], best[1], out


FAST, DENSE, DENSE_NESTED = "(a) Newton-Krylov, nested", "(b) dense Newton, Hertz start", \
    "(c) dense steps, nested"
VARIANTS = {FAST: {}, DENSE: {"linear_step": dense_step, "nested": False},
            DENSE_NESTED: {"linear_step": dense_step}}


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path,
                        default=Path(__file__).resolve().parents[1] / "docs" / "ehl-speed.md")
    args = parser.parse_args(argv)
    lines = []

    def print(text):  # noqa: A001 - the printout is the page
        builtins.print(text)
        lines.append(text)

    contact = LineContactEHL.from_dimensionless(W, U, G)
    times = {}
    print(f"Steady smooth line contact W={W:g} U={U:g} G={G:g}; wall time: least of {REPEAT} "
          f"runs for (a), {REPEAT_DENSE} for (b) and (c); CPU: process time of that run")
    print(f"{'variant':31s} {'N':>5s} {'wall [s]':>9s} {'CPU [s]':>8s} {'Newton':>7s} "
          f"{'GMRES':>6s} {'H_c':>12s}")
    for size in SIZES:
        for name, options in VARIANTS.items():
            if name != FAST and size != SIZES[-1]:
                continue
            seconds, cpu, (eq, P, H, H00, its, lin) = timed(
                lambda: solver.steady_state(contact, nodes=size, **options),
                REPEAT if name == FAST else REPEAT_DENSE)
            times[name, size] = seconds
            h_c = np.interp(0.0, eq.grid.X, H) * 8.0 * W / math.pi
            print(f"{name:31s} {size:5d} {seconds:9.3f} {cpu:8.3f} {its:7d} {lin:6d} {h_c:12.6e}")
    n0, n1 = SIZES[0], SIZES[-1]
    fast, small = times[FAST, n1], times[FAST, n0]
    for name in (DENSE, DENSE_NESTED):
        print(f"ratio {name} / (a) at N={n1}: {times[name, n1] / fast:.1f}")
    nlogn = n1 * math.log(n1) / (n0 * math.log(n0))
    verdict = "within" if fast / small <= nlogn else "ABOVE"
    print(f"scaling of (a): t({n1}) / t({n0}) = {fast / small:.2f}; N log N ratio {nlogn:.2f}, "
          f"N^2 ratio {(n1 / n0) ** 2:.0f}: {verdict} N log N")
    print(f"targets: t({n0}) = {small:.3f} s (< 0.2 s), t({n1}) = {fast:.3f} s (< 1 s), "
          f"(b) / (a) = {times[DENSE, n1] / fast:.1f} (>= 20)")
    command = " ".join(["python", "benchmarks/ehl_speed.py", *(argv or sys.argv[1:])])
    pages.write(args.out, "\n".join([
        "# Speed of the mixed-EHL solver", "",
        "Wall times depend on the machine and its load; the ratios, measured side by side in one "
        "run, much less.", "",
        __doc__.split("Prints")[0].split("\n", 2)[2].strip(), "", "```", *lines, "```", ""]),
        command, __file__)


if __name__ == "__main__":
    main()
