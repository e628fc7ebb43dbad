"""Discrete mixed-EHL line-contact equations in Hertz units, their Jacobian and preconditioner.

Hertz units: X = x / b, P = p / p_H, H = h R / b^2, with the scales b, p_H of a reference load.
Unknowns on a uniform grid X_0..X_{n-1}: hydrodynamic pressure P_i, film H_i, and the rigid
approach H_00. Equations (Soleimanian et al. 2020, eqs. 15-23):

* Reynolds (eq. 18): d/dX(eps dP/dX) - lam d(rho H)/dX - kappa d(rho H)/dt = 0,
  eps = rho H^3 / eta, lam = 12 mu0 u_m R^2 / (b^3 p_H), kappa = 12 mu0 R^2 / (b^2 p_H) [s]
  (with ``average_flow``: eps = phi_x rho H^3 / eta, and the mean gap H_T in place of H in the
  wedge and time terms; see :mod:`.flow_factors`);
  conservative finite volumes, central Poiseuille flux, second-order upwind wedge flux
  (3 q_i - q_{i-1}) / 2, q = rho H; P = 0 at both ends. Reynolds' exit condition (eq. 21,
  P >= 0 with the film ruptured where P would be negative) by a penalty: the row
  c L_i + PENALTY min(P_i, 0) = 0 leaves P ~ -1e-8 where the fluid cavitates.
* film (eq. 23): H = H_00 + X^2/2 + D P_t, P_t = P + P_a(H) the total pressure (eq. 15),
  D P_t = -(1/pi) int P_t ln|X - X'| dX' with piecewise-constant P_t on the cells: D is
  Toeplitz and applied by FFT (DC-FFT, zero-padded circular convolution), O(n log n).
  Kept as an equation with H as unknown, and differentiated twice between the end nodes:
  the second difference of D decays like 1/k^2 away from its diagonal (the "differential
  deflection" form), so a band of it is a good local approximation, unlike D itself.
* load (eq. 22): dX sum(P_t) = pi/2 * w / w_ref.
"""
from __future__ import annotations

import math

import numpy as np
from scipy import fft
from scipy.linalg import lapack

from .. import greenwood_tripp as gt
from . import flow_factors
from .inputs import LineContactEHL, lubricant_state

PENALTY = 1e8
BAND = 8  # half-width (in nodes) of the second-difference elastic band in the preconditioner
_H_FLOOR = 1e-12  # film [Hertz units] below which eps uses the floor (only Newton iterates)


class Grid:
    """Uniform grid on [inlet, outlet] (Hertz units) and its elastic influence operator."""

    def __init__(self, inlet: float, outlet: float, nodes: int):
        self.X = np.linspace(inlet, outlet, nodes)
        self.n = nodes
        self.dx = dx = self.X[1] - self.X[0]

        def primitive(s):  # int ln|s| ds
            return s * np.log(np.abs(s)) - s

        k = np.arange(nodes + 1)
        column = -(primitive((k + 0.5) * dx) - primitive((k - 0.5) * dx)) / math.pi
        self.column = column[:nodes]  # D_k = D_{i, i+k}
        self.n_fft = fft.next_fast_len(2 * nodes - 1, real=True)
        circulant = np.zeros(self.n_fft)
        circulant[:nodes] = self.column
        circulant[self.n_fft - nodes + 1:] = self.column[:0:-1]
        self.kernel = fft.rfft(circulant)
        ext = column[np.abs(np.arange(-BAND - 1, BAND + 2))]
        self.band = ext[:-2] - 2.0 * ext[1:-1] + ext[2:]  # dx^2 (d2 D)_k, k = -BAND..BAND
        self.pattern = None  # structure of the preconditioner, built on first use

    def deformation(self, p):
        """D p [Hertz units of film] for p on the nodes; O(n log n)."""
        return fft.irfft(fft.rfft(p, self.n_fft) * self.kernel, self.n_fft)[: self.n]


class Equations:
    """Residual and Jacobian of one contact on one grid.

    ``contact`` fixes the scales (its load is the reference w_ref) and the lubricant;
    ``load_ratio`` = w / w_ref, ``velocity`` = u_m [m/s] and the time term (``ddt_gain`` [1/s],
    ``ddt_history``) change from step to step: d(rho H)/dt = ddt_gain * rho H + ddt_history.
    """

    def __init__(self, contact: LineContactEHL, grid: Grid, film_scale: float):
        self.contact, self.grid = contact, grid
        b, ph, r = contact.half_width, contact.hertz_pressure, contact.radius
        self.p_scale = ph
        self.h_unit = b * b / r  # h [m] per unit H
        self.kappa = 12.0 * contact.viscosity * r * r / (b * b * ph)
        self.flux_unit = b**5 * ph / (12.0 * contact.viscosity * r**3)  # m^2/s per unit flux
        self.film_scale = film_scale  # typical H, scales the Reynolds rows
        self.surface = contact.surface()
        if self.surface is not None:
            self.asperity_gain = gt.asperity_pressure(0.0, self.surface) / gt.f52(0.0) / ph
        # roughness in Hertz units of film, if the average flow model applies
        self.sigma = contact.roughness / self.h_unit if contact.average_flow else 0.0
        self.set_conditions(1.0, contact.entrainment_velocity)

    def set_conditions(self, load_ratio, velocity, ddt_gain=0.0, ddt_history=0.0):
        c = self.contact
        self.load_target = 0.5 * math.pi * load_ratio
        self.lam = self.kappa * velocity / c.half_width
        self.ddt_gain, self.ddt_history = ddt_gain, ddt_history
        self.row_scale = 1.0 / ((self.lam + self.kappa * ddt_gain) * self.film_scale)

    def lubricant(self, P):
        """(eta, d ln eta / dP, rho, d rho / dP) in Hertz units."""
        c = self.contact
        eta, dln, rho, drho = lubricant_state(P * self.p_scale, c.viscosity, c.pressure_viscosity)
        return eta, dln * self.p_scale, rho, drho * self.p_scale

    def asperity(self, H):
        """Asperity pressure P_a(H) (eq. 16) and dP_a/dH, Hertz units; zeros if smooth."""
        if self.surface is None:
            return np.zeros_like(H), np.zeros_like(H)
        h = H * self.h_unit
        pa = gt.asperity_pressure(h, self.surface) / self.p_scale
        lam = np.maximum(h, 0.0) / self.surface.roughness
        # dF_5/2 / d lambda = -5/2 F_3/2; h <= 0 is clamped to 0 in the asperity law.
        slope = -2.5 * self.asperity_gain * gt.gt_function(1.5, lam) / self.surface.roughness
        return pa, np.where(h > 0.0, slope * self.h_unit, 0.0)

    def flow(self, H):
        """(phi_x, d phi_x / dH, H_T, d H_T / dH): pressure flow factor and the film the fluid
        fills [Hertz units]; 1, 0, H, 1 unless the average flow model applies."""
        if not self.sigma:
            return 1.0, 0.0, H, 1.0
        phi, dphi = flow_factors.pressure_flow_factor(H / self.sigma, self.contact.peklenik)
        gap, dgap = flow_factors.mean_gap(H / self.sigma)
        return phi, dphi / self.sigma, gap * self.sigma, dgap

    def content(self, P, H):
        """Lubricant per unit area rho H_T [Hertz units], the quantity the time term changes."""
        return self.lubricant(P)[2] * self.flow(H)[2]

    def fluxes(self, P, H):
        """Face fluxes f_{i+1/2} = eps dP/dX - lam q^ (n-1 values) and the lubricant state."""
        dx = self.grid.dx
        eta, dln, rho, drho = self.lubricant(P)
        phi, dphi, gap, dgap = self.flow(H)
        eps = phi * rho * np.maximum(H, _H_FLOOR) ** 3 / eta
        q = rho * gap
        qhat = np.empty(self.grid.n - 1)
        qhat[0] = 0.5 * (q[0] + q[1])
        qhat[1:] = 1.5 * q[1:-1] - 0.5 * q[:-2]
        f = 0.5 * (eps[1:] + eps[:-1]) * np.diff(P) / dx - self.lam * qhat
        return f, (eta, dln, rho, drho, eps, q, phi, dphi, gap, dgap)

    def residual(self, P, H, H00, jacobian=True, pinned=None):
        """Residual vector [Reynolds (n), film (n), load (1)] and, optionally, the Jacobian.

        ``pinned`` (interior nodes, optional): nodes whose penalty acts whatever the sign of P,
        i.e. held at P = 0 (see :func:`solver.newton`).
        """
        g = self.grid
        n, dx = g.n, g.dx
        f, (eta, dln, rho, drho, eps, q, phi, dphi, gap, dgap) = self.fluxes(P, H)
        hist = self.ddt_history[1:-1] if np.ndim(self.ddt_history) else self.ddt_history
        L = -np.diff(f) / dx + self.kappa * (self.ddt_gain * q[1:-1] + hist)
        penalised = P[1:-1] < 0.0 if pinned is None else (P[1:-1] < 0.0) | pinned
        penalty = PENALTY * np.where(penalised, P[1:-1], 0.0)
        reynolds = np.concatenate([[P[0]], self.row_scale * L + penalty, [P[-1]]])
        pa, dpa = self.asperity(H)
        total = P + pa
        r = H - H00 - 0.5 * g.X**2 - g.deformation(total)
        film = np.concatenate([[r[0]], r[:-2] - 2.0 * r[1:-1] + r[2:], [r[-1]]])
        F = np.concatenate([reynolds, film, [dx * np.sum(total) - self.load_target]])
        if not jacobian:
            return F
        # Reynolds stencil: d(row i)/d(P, H)_{i+o}, o = -2..1, for the interior rows.
        Hc = np.maximum(H, _H_FLOOR)
        deps_dP = eps * (drho / rho - dln)
        deps_dH = np.where(H > _H_FLOOR, 3.0 * eps / Hc, 0.0) + eps * dphi / phi
        a = 0.5 * (eps[1:-1] + eps[2:])
        b = 0.5 * (eps[:-2] + eps[1:-1])
        gp, gm = P[2:] - P[1:-1], P[1:-1] - P[:-2]
        dx2 = dx * dx
        direct = {-1: -b / dx2, 0: (a + b) / dx2, 1: -a / dx2}
        via_eps = {-1: 0.5 * gm / dx2, 0: -0.5 * (gp - gm) / dx2, 1: -0.5 * gp / dx2}
        wedge = {o: np.full(n - 2, w) for o, w in ((-2, 0.5), (-1, -2.0), (0, 1.5))}
        wedge[-2][0], wedge[-1][0], wedge[0][0] = 0.0, -1.0, 1.0
        dq_dP, dq_dH = drho * gap, rho * dgap
        cP, cH = {}, {}
        for o in (-2, -1, 0, 1):
            j = np.arange(1 + o, n - 1 + o).clip(0)
            w = self.lam * wedge.get(o, 0.0) / dx + (self.kappa * self.ddt_gain if o == 0 else 0.0)
            cP[o] = direct.get(o, 0.0) + via_eps.get(o, 0.0) * deps_dP[j] + w * dq_dP[j]
            cH[o] = via_eps.get(o, 0.0) * deps_dH[j] + w * dq_dH[j]
        for o in cP:
            cP[o] = self.row_scale * cP[o]
            cH[o] = self.row_scale * cH[o]
        cP[0] = cP[0] + np.where(penalised, PENALTY, 0.0)
        return F, Jacobian(self, cP, cH, dpa, penalised)


class Jacobian:
    """The exact Jacobian (matrix-free, FFT) and its banded-plus-border preconditioner."""

    def __init__(self, eq: Equations, cP, cH, dpa, penalised):
        self.eq, self.cP, self.cH, self.dpa, self.penalised = eq, cP, cH, dpa, penalised
        self.size = 2 * eq.grid.n + 1

    def matvec(self, v):
        g = self.eq.grid
        n = g.n
        dP, dH, dH00 = v[:n], v[n:2 * n], v[2 * n]
        out = np.empty(self.size)
        out[0], out[n - 1] = dP[0], dP[n - 1]
        rey = 0.0
        for o in self.cP:
            lo = 1 + o
            rey = rey + self.cP[o] * _shifted(dP, lo, n) + self.cH[o] * _shifted(dH, lo, n)
        out[1:n - 1] = rey
        dtotal = dP + self.dpa * dH
        dr = dH - dH00 - g.deformation(dtotal)
        out[n] = dr[0]
        out[n + 1:2 * n - 1] = dr[:-2] - 2.0 * dr[1:-1] + dr[2:]
        out[2 * n - 1] = dr[-1]
        out[2 * n] = g.dx * np.sum(dtotal)
        return out

    def preconditioner(self):
        """M^-1 as a function: the Jacobian with the twice-differenced elastic operator cut to
        BAND nodes either side, solved exactly. Interleaved ordering (P_0, P_1, H_1, ...,
        P_{n-1}) makes it banded, LU-factorised by LAPACK (dgbtrf); the film rows at both ends
        and the load row, which are dense, and their unknowns (H_0, H_{n-1}, H_00) form a
        3 x 3 border eliminated by a Schur complement."""
        return _BorderedBand(self)


def _shifted(v, lo, n):
    """v[lo : lo + n - 2] with v[-1] read as 0 (the wedge stencil at i = 1 has zero weight)."""
    if lo >= 0:
        return v[lo:lo + n - 2]
    return np.concatenate([[0.0], v[: n - 3]])


class _Group:
    """Where the entries (rows, cols) [global numbering, unique] go in the bordered band."""

    def __init__(self, pattern, rows, cols):
        r, c = pattern.pos[rows], pattern.pos[cols]
        ni, ldab = pattern.ni, pattern.ldab
        self.inner = np.nonzero((r < ni) & (c < ni))[0]
        self.flat = c[self.inner] * ldab + pattern.kl + pattern.ku + r[self.inner] - c[self.inner]
        self.side = np.nonzero((r < ni) & (c >= ni))[0]
        self.side_at = (r[self.side], c[self.side] - ni)

    def add(self, flat, side, values):
        flat[self.flat] += values[self.inner]
        side[self.side_at] += values[self.side]


class _Pattern:
    """The fixed structure of the preconditioner on one grid: unknown order, constant part
    (film second differences, elastic band, end conditions) and the places of the varying
    entries (Reynolds stencil, asperity terms)."""

    def __init__(self, g: Grid):
        n, m = g.n, BAND
        self.ni = ni = 2 * n - 2  # inner unknowns
        # position of each global unknown (P 0..n-1, H n..2n-1, H00 2n) in inner/border order
        pos = np.empty(2 * n + 1, dtype=np.intp)
        pos[0] = 0
        pos[1:n] = 2 * np.arange(1, n) - 1
        pos[n + 1:2 * n - 1] = 2 * np.arange(1, n - 1)
        pos[[n, 2 * n - 1, 2 * n]] = ni + np.arange(3)
        self.pos = pos
        self.kl, self.ku = 2 * m + 1, max(2 * m, 3)
        self.ldab = 2 * self.kl + self.ku + 1
        i = np.arange(1, n - 1)
        self.reynolds = {}
        for o in (-2, -1, 0, 1):
            j = (i + o).clip(0)
            self.reynolds[o] = (_Group(self, i, j), _Group(self, i, n + j))
        self.base = np.zeros((ni, self.ldab))  # transposed LAPACK band storage
        self.base_side = np.zeros((ni, 3))
        flat = self.base.reshape(-1)
        ends = np.array([0, n - 1])
        _Group(self, ends, ends).add(flat, self.base_side, np.ones(2))
        for o, w in ((-1, 1.0), (0, -2.0), (1, 1.0)):
            _Group(self, n + i, n + i + o).add(flat, self.base_side, np.full(n - 2, w))
        self.asperity = []
        for k in range(-m, m + 1):
            ok = (i + k >= 0) & (i + k < n)
            ii, jj = i[ok], i[ok] + k
            _Group(self, n + ii, jj).add(flat, self.base_side, np.full(ii.size, -g.band[k + m]))
            self.asperity.append((_Group(self, n + ii, n + jj), jj, -g.band[k + m]))
        # dense border rows: film at both ends (H - H00 - D P_t) and the load (dx sum P_t)
        C = np.zeros((3, 2 * n + 1))
        C[0, :n], C[1, :n], C[2, :n] = -g.column, -g.column[::-1], g.dx
        C[0, n] = C[1, 2 * n - 1] = 1.0
        C[:2, 2 * n] = -1.0
        self.border_rows = C


class _BorderedBand:
    def __init__(self, jac: Jacobian):
        g = jac.eq.grid
        if getattr(g, "pattern", None) is None:
            g.pattern = _Pattern(g)
        pat = self.pat = g.pattern
        n, ni = g.n, pat.ni
        band = pat.base.copy()
        side = pat.base_side.copy()
        flat = band.reshape(-1)
        for o, (group_p, group_h) in pat.reynolds.items():
            group_p.add(flat, side, jac.cP[o])
            group_h.add(flat, side, jac.cH[o])
        C = pat.border_rows
        if np.any(jac.dpa):
            for group, jj, coefficient in pat.asperity:
                group.add(flat, side, coefficient * jac.dpa[jj])
            C = C.copy()
            C[:, n:2 * n] += C[:, :n] * jac.dpa
        self.lu, self.piv, info = lapack.dgbtrf(band.T, pat.kl, pat.ku, overwrite_ab=1)
        if info != 0:
            raise np.linalg.LinAlgError("singular banded preconditioner")
        Cp = np.empty_like(C)
        Cp[:, pat.pos] = C
        self.C = Cp[:, :ni]
        self.AinvB = self._solve(side)
        self.schur = np.linalg.inv(Cp[:, ni:] - self.C @ self.AinvB)

    def _solve(self, rhs):
        x, _ = lapack.dgbtrs(self.lu, self.pat.kl, self.pat.ku, rhs, self.piv)
        return x

    def __call__(self, r):
        pat = self.pat
        rp = np.empty_like(r)
        rp[pat.pos] = r
        x1 = self._solve(rp[: pat.ni])
        y = self.schur @ (rp[pat.ni:] - self.C @ x1)
        return np.concatenate([x1 - self.AinvB @ y, y])[pat.pos]
