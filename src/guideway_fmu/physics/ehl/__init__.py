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
nodes, the dense rows (film at the ends, load) eliminated by a 3 x 3 Schur complement.
With s = sqrt(2 H_c) [Hertz half-widths] the inlet length (H_c estimated), Newton starts
from the Hertz pressure on a coarse grid (>= 129 nodes, spacing <= s/4) and
each solution starts the grid with twice the nodes (nested iteration); the damping keeps the
viscosity change per step below a factor e. Measured at W = 1e-4, U = 1e-11, G = 4500, on
this 2-core machine under a load average of 4-6 (so the absolute times carry a factor ~2):

    BAND (nodes)              4      8     16     32
    N = 513:  time [ms]     133    118    129    182
    N = 2049: time [ms]     339    311    355    563
    N = 2049: GMRES its     193    144    106     83   (24 Newton steps on all grids)

GMRES needs 2-11 iterations per Newton step, growing slowly with N (75, 104, 144 in total for
N = 513, 1025, 2049). The nested start does 5 of its 24 Newton steps on the finest grid;
Newton from the Hertz pressure on the N = 2049 grid itself needs 19 there (benchmark (b)).
At heavy load Newton from the Hertz pressure diverges on grids coarser than about s/4
(W = 5e-4, U = 1e-12: fails on 257 nodes, spacing 0.37 s; 6 steps on 513, 0.19 s), where the
exit constriction is not resolved, hence the coarsest-grid rule.
benchmarks/ehl_speed.py, two runs: N = 513 in 0.10-0.11 s, N = 2049 in 0.29-0.30 s (t ratio
2.6-3.0 < N log N ratio 4.9); the dense-matrix Newton of the same equations from the Hertz
start takes 20.5-21.1 s at N = 2049 (70x), the dense LU inside the same nested iteration
8.6-10.7 s (28-37x).

Validation (tests/test_ehl.py) and Pan-Hamrock agreement
--------------------------------------------------------
Independent checks: Hertz's flat film for the Hertz pressure (elastic kernel, closed form);
Martin's rigid-isoviscous film 4.9 U/W (0.7 %); Hertz pressure at heavy load (M = 500, within
0.01 p_H); grid convergence (second order; the default grid, spacing s/40, keeps H_c and
H_min within ~1 % of the grid limit); load balance and constant mass flow equal to u_m rho h
where dp/dx = 0; rigid-isoviscous pure squeeze (film history within 0.5 %) and friction
(1 %) by quadrature; the paper's check point with Table 4 (asperity share 4 % at
lambda = 0.1, matching the Greenwood-Tripp pressure on a Hertz gap). The film rises a little
with roughness at a fixed load (the fluid carries less of it; eq. 18 has no flow factors).
With ``average_flow`` (module ``flow_factors``, Patir and Cheng's average Reynolds equation)
and ridges along the motion (peklenik 9) it falls monotonically: 45.9 nm smooth, 45.1 / 40.7 /
31.2 / 9.0 nm at sigma = 0.01 / 0.03 / 0.05 / 0.1 um (lambda 4.5 / 1.4 / 0.6 / 0.1).

Pan and Hamrock (1989): H_c = 2.922 W^-0.166 U^0.692 G^0.470, H_min = 1.714 W^-0.128 U^0.694
G^0.568; deviation of this solver (default grid, E' = 2e11 Pa, mu0 = 0.195 Pa s) in %:

==========  ======  ======  ======  ======  ======  ======  ======  ======  ======
W \\ U, G    1e-12                   1e-11                   1e-10
\\           3500    4500    5000    3500    4500    5000    3500    4500    5000
==========  ======  ======  ======  ======  ======  ======  ======  ======  ======
2e-5 H_c    +1.6    +3.3    +4.4    +1.0    +3.9    +5.3    -7.2    -1.8    +0.3
2e-5 H_min  +2.9    +2.1    +2.2    +1.5    +2.4    +3.0    +0.2    +1.9    +2.9
1e-4 H_c    -0.4    +2.7    +4.3    +2.2    +7.0    +9.4    +4.8    +10.6   +13.3
1e-4 H_min  -0.2    +0.4    +1.1    +1.0    +3.6    +5.0    +3.1    +7.0    +8.7
3e-4 H_c    -1.4    +2.3    +4.2    +2.9    +8.6    +11.3   +8.1    +15.1   +18.3
3e-4 H_min  -2.3    -0.9    -0.0    +0.5    +3.9    +5.5    +4.6    +9.3    +11.4
==========  ======  ======  ======  ======  ======  ======  ======  ======  ======

Within 10 % at 22 of the 27 points. H_c exceeds the fit by 10.6-18.3 % at five points of high
load, speed and G, (W, U, G) = (1e-4, 1e-10, 4500 | 5000), (3e-4, 1e-11, 5000) and
(3e-4, 1e-10, 4500 | 5000), H_min only at the last (11.4 %). Toward that corner the film grows with G as G^0.72 against the fit's G^0.47, close to
inlet theory (Grubin G^(8/11), Moes' asymptote L^(3/4)); grid and domain are converged to
0.2 %, and other Roelands parameters (mu0, or E' at fixed G) move it by about 3 % only.
Dowson and Higginson's H_min = 2.65 U^0.70 G^0.54 W^-0.13, a regression independent of Pan and
Hamrock's, agrees within -8.5 % to +3.3 % at all 27 points (+3.3 % at that corner).
"""
from .inputs import LineContactEHL, lubricant_state, martin, pan_hamrock
from .results import EHLResult, TransientResult, friction
from .solver import EHLConvergenceError, solve_dimensionless, solve_steady, solve_transient

__all__ = ["EHLConvergenceError", "EHLResult", "LineContactEHL", "TransientResult", "friction",
           "lubricant_state", "martin", "pan_hamrock", "solve_dimensionless", "solve_steady",
           "solve_transient"]
