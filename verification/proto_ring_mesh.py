"""Prototype of the ring-following resolution: an ellipse-aligned graded mesh with a dense operator, on the sphere.

One of the options of the issue "The ground truth where practitioners work" (resolution on the
cohesive ring, not a uniform grid), measured before any of it enters the library.

The mesh
    Panels of the even-even quadrant between the ellipses ``x^2/a^2 + y^2/b^2 = s^2`` (s graded:
    a uniform step of ``(m - 1)/cells_across`` on the band from the contact's rim, s = 1, to the
    cohesive zone's rim, s = m, growing by ``growth`` per cell inward and outward) and the rays of
    the elliptic angle (``n_phi`` per quadrant).  Each panel is the straight-sided quadrilateral
    of its four corners, so the panels tile the quadrant exactly.
The operator
    Collocation at each panel's centroid, constant traction per panel; the displacement of a
    uniformly loaded polygon has the closed form
    ``pi E* u = sum over edges h (asinh(t2/|h|) - asinh(t1/|h|))`` (h the signed distance of the
    point to the edge's line, t1, t2 its ends along it); the three mirror images give the
    quadrant's symmetry.  Dense, about n^2 x 8 bytes.
The state
    The same equations as :mod:`dhfield.bem.newton` (``h = z - delta + K q``, ``p = q + sigma(h)``,
    ``min(c h, p) = 0``), solved by a semismooth Newton with dense direct solves and a backtracking
    line search on ``|F|^2``; the Dugdale edge a ramp of width ``1.5 sigma0`` times the compliance
    of the panel's ring (the collective mode of a ring of edge panels), capped at 2 h0; the start is
    :func:`dhfield.bem.newton.cold_start`'s (sigma0 on the predicted zone, the contact it implies).

What it prints (references: Hertz's load 4/3 at delta = 1 and the uniform disc's displacement
``(4/pi) E(r^2)``, closed forms; Maugis-Dugdale's W*, :mod:`dhfield.models.maugis_dugdale`):

1. the operator on the ring mesh against the closed forms;
2. at mu = 1, W*(delta) along a continuation in delta on the ring mesh, beside the uniform grid's
   Newton states (N = 128) at the same approaches: the spread of W* over the window;
3. at mu = 10, at Maugis-Dugdale's pull-off approach: the Newton iterations and W* against
   Maugis-Dugdale, for the linear ramp and a C1 (smoothstep) ramp, and two band resolutions.

Usage::

    DHFIELD_THREADS=1 .venv/bin/python -m verification.proto_ring_mesh        # ~2 min
"""
from __future__ import annotations

import argparse
import math
import time

import numpy as np
import scipy.linalg as sla


def _w_asinh(w, t):
    aw = np.abs(w)
    with np.errstate(divide="ignore", invalid="ignore"):
        v = w * np.arcsinh(t / aw)
    return np.where(aw > 0.0, v, 0.0)


def graded_nodes(band, fine, growth, s_max):
    """s nodes: step ``fine`` on ``[band[0] - 4 fine, band[1] + 4 fine]``, growing by ``growth`` outside."""
    lo, hi = band[0] - 4 * fine, band[1] + 4 * fine
    mid = np.linspace(lo, hi, max(2, int(math.ceil((hi - lo) / fine))) + 1)
    inner, s, d = [], lo, fine
    while True:
        d *= growth
        s -= d
        if s <= 0.5 * d:
            break
        inner.append(s)
    outer, s, d = [], hi, fine
    while s < s_max:
        d *= growth
        s += d
        outer.append(s)
    return np.concatenate([[0.0], inner[::-1], mid, outer])


class RingMesh:
    """Quadrilateral panels between scaled ellipses and elliptic-angle rays (even-even quadrant)."""

    def __init__(self, a, b, s, n_phi):
        phi = np.linspace(0.0, 0.5 * np.pi, n_phi + 1)
        S, P = np.meshgrid(s, phi, indexing="ij")
        X, Y = S * a * np.cos(P), S * b * np.sin(P)
        corners = np.stack([np.stack([X[:-1, :-1], Y[:-1, :-1]], -1), np.stack([X[1:, :-1], Y[1:, :-1]], -1),
                            np.stack([X[1:, 1:], Y[1:, 1:]], -1), np.stack([X[:-1, 1:], Y[:-1, 1:]], -1)], -2)
        self.shape = corners.shape[:2]
        c = corners.reshape(-1, 4, 2)
        x, y = c[..., 0], c[..., 1]
        x1, y1 = np.roll(x, -1, 1), np.roll(y, -1, 1)
        cross = x * y1 - x1 * y
        self.area = 0.5 * cross.sum(1)                            # shoelace (counter-clockwise: > 0)
        safe = np.where(self.area > 0, self.area, 1.0)
        self.cx = ((x + x1) * cross).sum(1) / (6 * safe)
        self.cy = ((y + y1) * cross).sum(1) / (6 * safe)
        self.corners = c
        self.n = len(self.area)

    def operator(self, chunk=256):
        """Dense K[i, j] [length/stress]: displacement at centroid i per unit traction on panel j and its images (E* = 1)."""
        A = self.corners
        B = np.roll(A, -1, 1)
        d = B - A
        L = np.hypot(d[..., 0], d[..., 1])
        Ls = np.where(L > 0, L, 1.0)
        tx, ty = d[..., 0] / Ls, d[..., 1] / Ls
        nx, ny = ty, -tx
        K = np.zeros((self.n, self.n))
        for sx in (1.0, -1.0):
            for sy in (1.0, -1.0):
                for i0 in range(0, self.n, chunk):
                    qx = sx * self.cx[i0:i0 + chunk, None, None]
                    qy = sy * self.cy[i0:i0 + chunk, None, None]
                    ax, ay = A[None, ..., 0] - qx, A[None, ..., 1] - qy
                    bx, by = B[None, ..., 0] - qx, B[None, ..., 1] - qy
                    h = ax * nx + ay * ny
                    v = (_w_asinh(h, bx * tx + by * ty) - _w_asinh(h, ax * tx + ay * ty)) * (L > 0)
                    K[i0:i0 + chunk] += v.sum(-1)
        return K / np.pi

    def ring_compliance(self, K):
        """Per panel: the displacement of its ring of panels (all phi) under unit traction on the ring."""
        ns, nphi = self.shape
        i = np.arange(ns)
        return K.reshape(ns, nphi, ns, nphi)[i, :, i, :].sum(-1).reshape(-1)


def ramp(h, sigma0, h0, w, smooth):
    """Dugdale's edge as a ramp of width w centred on h0: linear, or C1 (smoothstep); work sigma0 h0 kept."""
    r = np.clip((h0 + 0.5 * w - h) / w, 0.0, 1.0)
    if smooth:
        return sigma0 * r * r * (3.0 - 2.0 * r), -sigma0 * 6.0 * r * (1.0 - r) / w
    return sigma0 * r, np.where((r > 0) & (r < 1), -sigma0 / w, 0.0)


def contact_start(K, z, delta, stress):
    """Contact under a fixed adhesive stress: semismooth Newton on min(h, q + stress) (exact, dense)."""
    n = len(z)
    q = -stress.copy()
    for it in range(200):
        h = z - delta + K @ q
        p = q + stress
        F = np.minimum(h, p)
        if np.sqrt(F @ F / n) < 1e-13 * max(1.0, float(np.max(np.abs(stress)))):
            return q, it
        A = h < p
        dq = np.where(A, 0.0, -p)
        ia = np.flatnonzero(A)
        dq[ia] = sla.solve(K[np.ix_(ia, ia)], -h[ia] - K[ia][:, ~A] @ dq[~A], check_finite=False)
        q = q + dq
    return q, 200


def adhesive_state(K, z, delta, q, sigma0, h0, w, smooth, tol=1e-10, max_newton=60):
    """Semismooth Newton (dense) on min(c h, q + sigma(h)); returns (q, Newton iterations, converged)."""
    c = sigma0 / h0
    n = len(z)
    for it in range(max_newton):
        h = z - delta + K @ q
        s, ds = ramp(h, sigma0, h0, w, smooth)
        p = q + s
        F = np.minimum(c * h, p)
        merit = float(F @ F)
        if math.sqrt(merit / n) < tol * sigma0:
            return q, it, True
        A = c * h < p
        E = ~A & (ds != 0)
        U = A | E
        dq = np.where(U, 0.0, -p)
        iu = np.flatnonzero(U)
        Au, Eu = A[iu], E[iu]
        ko = K[iu][:, ~U] @ dq[~U]
        M = K[np.ix_(iu, iu)]
        M[Eu] *= ds[iu][Eu, None]
        ie = np.flatnonzero(Eu)
        M[ie, ie] += 1.0
        rhs = np.where(Au, -h[iu] - ko, -p[iu] - ds[iu] * ko)
        dq[iu] = sla.solve(M, rhs, check_finite=False)
        t = 1.0
        while True:
            qn = q + t * dq
            hn = z - delta + K @ qn
            Fn = np.minimum(c * hn, qn + ramp(hn, sigma0, h0, w, smooth)[0])
            if Fn @ Fn <= (1.0 - 1e-4 * t) * merit or t < 1e-4:
                break
            t *= 0.5
        q = qn
    return q, max_newton, False


class SphereCase:
    """The sphere at mu on a ring mesh placed on Maugis-Dugdale's pull-off rims."""

    def __init__(self, mu, n_phi, cells_across, growth=1.3, smooth=False):
        from dhfield.models import maugis_dugdale

        self.md = maugis_dugdale.pull_off_nondimensional(1.0, mu)
        a, c = float(self.md.a_star), float(self.md.c_star)
        m = c / a
        s = graded_nodes((1.0, m), (m - 1.0) / cells_across, growth, 1.6 * max(m, 1.0))
        self.mesh = RingMesh(a, a, s, n_phi)
        t0 = time.perf_counter()
        self.K = self.mesh.operator()
        self.assembly = time.perf_counter() - t0
        self.z = 0.5 * (self.mesh.cx ** 2 + self.mesh.cy ** 2)
        self.sigma0, self.h0 = float(mu), 1.0 / float(mu)
        factor = 1.5 * (1.5 if smooth else 1.0)                   # the smoothstep's steepest slope is 1.5/w
        self.w = np.minimum(factor * self.sigma0 * self.mesh.ring_compliance(self.K), 2.0 * self.h0)
        self.smooth = smooth
        self.zone = (self.mesh.cx ** 2 + self.mesh.cy ** 2 < c * c).astype(float) * self.sigma0

    def w_star(self, q):
        return 4.0 * float(q @ self.mesh.area) / (2.0 * math.pi)   # Eq. (34), R = dgamma = 1, sphere

    def solve(self, delta, q=None):
        if q is None:
            q, _ = contact_start(self.K, self.z, delta, self.zone)
        return adhesive_state(self.K, self.z, delta, q, self.sigma0, self.h0, self.w, self.smooth)


def uniform_w_star(mu, n, approaches):
    """W* of the uniform grid's Newton states (nested, from the analytic cold start) at the approaches."""
    from dhfield.analysis.bem_start import newton_problem
    from dhfield.bem.ladder import adhesive_problem, nested_levels
    from dhfield.bem.newton import NESTED_OPTIONS, cold_start, solve_state_nested

    nd = newton_problem(beta0=1.0, mu=mu, n=n)
    levels = nested_levels(nd.grid.nx, nd.grid.ny)
    probs = [adhesive_problem(nd.on_cells(nd.grid.nx // 2 ** i, nd.grid.ny // 2 ** i) if i else nd)
             for i in range(levels - 1, -1, -1)]
    out = []
    for d in approaches:
        st = solve_state_nested(probs, d, cold_start(probs[0], d, nd.pull_off_zone), NESTED_OPTIONS).state
        out.append(float(st.load) / (2.0 * math.pi) if st.converged else float("nan"))
    return out


def main(argv=None) -> int:
    from scipy.special import ellipe

    p = argparse.ArgumentParser(prog="python -m verification.proto_ring_mesh", description=__doc__.split("\n")[0])
    p.add_argument("--n-phi", type=int, default=32, help="rays per quadrant")
    p.parse_args(argv)
    t_all = time.perf_counter()

    print("1. The operator on the ring mesh (closed forms)")
    print(f"{'n_phi':>6} {'panels':>7} {'Hertz W(delta=1)/(4/3)-1':>26} {'max|u - (4/pi)E(r^2)|':>23}")
    for n_phi, across in ((16, 8), (32, 8), (64, 16)):
        mesh = RingMesh(1.0, 1.0, graded_nodes((1.0, 1.05), 0.05 / across, 1.3, 2.0), n_phi)
        K = mesh.operator()
        z = 0.5 * (mesh.cx ** 2 + mesh.cy ** 2)
        q, _ = contact_start(K, z, 1.0, np.zeros(mesh.n))
        disc = RingMesh(1.0, 1.0, np.linspace(0.0, 1.0, 41), n_phi)
        u = disc.operator() @ np.ones(disc.n)
        r2 = disc.cx ** 2 + disc.cy ** 2
        print(f"{n_phi:6d} {mesh.n:7d} {4.0 * float(q @ mesh.area) / (4.0 / 3.0) - 1.0:+26.2e} "
              f"{np.max(np.abs(u - 4.0 / np.pi * ellipe(r2))):23.2e}")

    print("\n2. mu = 1: W*(delta) along a continuation on the ring mesh (32 rays, 8 panels across the zone), "
          "and the uniform grid (N = 128)")
    case = SphereCase(1.0, p.parse_args(argv).n_phi, 8)
    approaches = np.round(np.arange(-0.70, -0.9401, -0.02), 4)
    ring, q = [], None
    for d in approaches:
        q, it, ok = case.solve(float(d), q)
        ring.append(case.w_star(q) if ok else float("nan"))
    uni = uniform_w_star(1.0, 128, [float(d) for d in approaches])
    md = float(case.md.W_star)
    print(f"{'delta':>7} {'W* ring':>10} {'W* uniform':>11}   (Maugis-Dugdale's pull-off W* {md:.6f} at "
          f"delta {float(case.md.delta_star):.4f})")
    for d, wr, wu in zip(approaches, ring, uni):
        print(f"{d:7.2f} {wr:10.5f} {wu:11.5f}")
    spread = lambda v: (np.nanmax(v) - np.nanmin(v)) / abs(md)          # noqa: E731
    print(f"spread of W* over the window / |W*_MD|: ring {spread(ring):.2%}, uniform {spread(uni):.2%}")

    print("\n3. mu = 10 at Maugis-Dugdale's pull-off approach, one state from the analytic start")
    print(f"{'ramp':>10} {'across':>6} {'panels':>6} {'w/h0':>6} {'newton':>6} {'conv':>5} {'W*':>10} {'vs MD':>9} "
          f"{'time':>6}")
    for smooth in (False, True):
        for across in (8, 16):
            t0 = time.perf_counter()
            case = SphereCase(10.0, 32, across, smooth=smooth)
            q, it, ok = case.solve(float(case.md.delta_star))
            band = np.abs(case.mesh.cx - float(case.md.a_star)) < 1e-3
            print(f"{'smoothstep' if smooth else 'linear':>10} {across:6d} {case.mesh.n:6d} "
                  f"{float(np.min(case.w[band])) / case.h0:6.2f} {it:6d} {str(ok):>5} {case.w_star(q):10.6f} "
                  f"{case.w_star(q) / float(case.md.W_star) - 1:+9.2e} {time.perf_counter() - t0:5.1f}s")
    print(f"\n(total {time.perf_counter() - t_all:.0f} s)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
