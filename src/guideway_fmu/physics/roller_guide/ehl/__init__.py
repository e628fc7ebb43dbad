"""Full numerical mixed-EHL line contact of one roller (Soleimanian et al. 2020, eqs. 15-31), SI units.

Entry points::

    solve_steady(contact, *, nodes=None, inlet=None, outlet=None, tol=1e-8, max_iterations=50)
    solve_dimensionless(W, U, G, **options)          # Hamrock's groups; options as above plus
                                                     # LineContactEHL.from_dimensionless's
    solve_transient(contact, times, loads, *, entrainment_velocities=None,
                    sliding_velocities=None, nodes=None, ...)

return an :class:`EHLResult` (x, p_h, p_a, p, h [SI] and X, P, H [Hertz units]; H_c, H_min,
P_max, asperity_load_ratio, friction_coefficient, boundary/viscous friction, iterations,
converged, to_dict()) or a :class:`TransientResult` of them. Invalid input raises ValueError
naming the parameter; a Newton iteration that does not converge raises EHLConvergenceError.

Model (modules ``inputs``, ``discretisation``, ``results``)
------------------------------------------------------------
Reynolds with wedge and squeeze terms (eq. 18), Reynolds exit condition (eq. 21), Dowson-
Higginson density (eq. 19, printed for p in GPa: 0.6e-9 and 1.7e-9 for p in Pa), Roelands
viscosity (eq. 20, garbled in the paper's text; the consistent form is used), Greenwood-Tripp
asperity pressure with the exact F_5/2 of :mod:`..greenwood_tripp` (eqs. 16-17), load sharing
p = p_h + p_a (eq. 15), load balance (eq. 22) and the film with the elastic deformation of the
total pressure (eq. 23). The asperity law uses E* = E'/2, the modulus of the Hertz asperity
contact Greenwood and Tripp start from (Soleimanian et al. 2020, writes E', which doubles p_a; see
LineContactEHL.surface). Friction: boundary tau_l0 A_a + beta_m W_a (eqs. 25, 27-28) and the
viscous shear of eq. 29 on surface 1, integrated over the full film and bounded by the
limiting shear stress tau_l0 + beta_m p_h (the paper does not bound it), total eq. 31.

Solver (module ``solver``) and why
----------------------------------
Unknowns P_i, H_i, H_00 on a uniform grid; the elastic operator is applied by FFT in
O(N log N) and never formed. Newton steps are solved by GMRES (scipy) on the system
left-preconditioned by an exact banded LU (LAPACK dgbtrf) of the Jacobian in which the film
equation is differenced twice (its elastic kernel then decays like 1/k^2) and cut to BAND
nodes, the dense rows (film at the ends, load) eliminated by a 3 x 3 Schur complement: a dense
Newton of the same equations costs O(N^3) per step. With s = sqrt(2 H_c) [Hertz half-widths]
the inlet length (H_c estimated), Newton starts from the Hertz pressure on a coarse grid
(>= 129 nodes, spacing <= s/4) and each solution starts the grid with twice the nodes (nested
iteration), so the finest grid needs a few Newton steps only; the damping keeps the viscosity
change per step below a factor e. At heavy load Newton from the Hertz pressure diverges on grids
that do not resolve the exit constriction, hence the coarsest-grid rule.

Validation
----------
Limiting cases in tests/physics/roller_guide/test_ehl.py: Hertz's flat film for the Hertz pressure
(elastic kernel, closed form); Martin's rigid-isoviscous film 4.9 U/W; Hertz pressure at heavy load;
grid convergence (second order; the default grid, spacing s/40, keeps H_c and H_min within
about 1 % of the grid limit); load balance and constant mass flow; rigid-isoviscous pure
squeeze and friction by quadrature; the paper's check point with Table 4. The comparison with
Pan and Hamrock's and Dowson and Higginson's film formulas over W, U, G, and the film over
roughness with the average flow model, are on docs/ehl-validation.md
(``benchmarks/ehl_validation.py``); the speed against a dense Newton on docs/ehl-speed.md
(``benchmarks/ehl_speed.py``).
"""
from .inputs import LineContactEHL, lubricant_state, martin, pan_hamrock
from .results import EHLResult, TransientResult, friction
from .solver import EHLConvergenceError, solve_dimensionless, solve_steady, solve_transient

__all__ = ["EHLConvergenceError", "EHLResult", "LineContactEHL", "TransientResult", "friction",
           "lubricant_state", "martin", "pan_hamrock", "solve_dimensionless", "solve_steady",
           "solve_transient"]
