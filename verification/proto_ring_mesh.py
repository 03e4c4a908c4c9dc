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
3. at mu = 10, at Maugis-Dugdale's pull-off approach: the Newton iterations, W* against
   Maugis-Dugdale and the state's contact rim, for seven variants (linear or C1 ramp, panels
   across the zone, strips aligned or staggered, backtracked or full Newton steps, rays, arcs
   drawn as chords).

The measurements and the decision are in ``docs/theory/bem.rst`` ("Resolution on the cohesive
ring").

Usage::

    DHFIELD_THREADS=1 .venv/bin/python -m verification.proto_ring_mesh        # ~2.5 min
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


def graded_nodes(band, fine, growth, s_max, pad):
    """s nodes: step ``fine`` on ``[band[0] - pad, band[1] + pad]``, growing by ``growth`` outside."""
    lo, hi = band[0] - pad, band[1] + pad
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
    """Panels between scaled ellipses and elliptic-angle rays (even-even quadrant).

    ``jitter`` (n_phi x len(s)) shifts each ray strip's s nodes (staggered strips: the panels of
    one ring no longer share their s); ``arc_segments`` draws each panel's two arcs as that many
    chords (1: the straight-sided quadrilateral).
    """

    def __init__(self, a, b, s, n_phi, jitter=None, arc_segments=1):
        phi = np.linspace(0.0, 0.5 * np.pi, n_phi + 1)
        nodes = s[None, :] + (0.0 if jitter is None else jitter)                # (n_phi, ns + 1)
        t = np.linspace(0.0, 1.0, int(arc_segments) + 1)
        ph = phi[:-1, None] + np.diff(phi)[:, None] * t[None, :]               # (n_phi, k + 1)

        def arc(sk):
            return np.stack([sk[..., None] * a * np.cos(ph[:, None, :]), sk[..., None] * b * np.sin(ph[:, None, :])], -1)

        inner, outer = arc(nodes[:, :-1]), arc(nodes[:, 1:])
        # counter-clockwise: out along ray k, along the outer arc, in along ray k+1, back along the inner arc
        poly = np.concatenate([inner[..., :1, :], outer, inner[..., ::-1, :][..., :-1, :]], -2)
        poly = poly.transpose(1, 0, 2, 3)                                        # (ns, n_phi, vertices, 2)
        self.shape = poly.shape[:2]
        c = poly.reshape(-1, poly.shape[2], 2)
        x, y = c[..., 0], c[..., 1]
        x1, y1 = np.roll(x, -1, 1), np.roll(y, -1, 1)
        cross = x * y1 - x1 * y
        self.area = 0.5 * cross.sum(1)                            # shoelace (counter-clockwise: > 0)
        safe = np.where(self.area > 0, self.area, 1.0)
        self.cx = ((x + x1) * cross).sum(1) / (6 * safe)
        self.cy = ((y + y1) * cross).sum(1) / (6 * safe)
        self.corners = c
        self.n = len(self.area)

    def operator(self, chunk=None):
        """Dense K[i, j] [length/stress]: displacement at centroid i per unit traction on panel j and its images (E* = 1)."""
        A = self.corners
        B = np.roll(A, -1, 1)
        d = B - A
        L = np.hypot(d[..., 0], d[..., 1])
        Ls = np.where(L > 0, L, 1.0)
        tx, ty = d[..., 0] / Ls, d[..., 1] / Ls
        nx, ny = ty, -tx
        K = np.zeros((self.n, self.n))
        chunk = chunk or max(16, 1024 // A.shape[1])
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


def adhesive_state(K, z, delta, q, sigma0, h0, w, smooth, tol=1e-10, max_newton=60, full_steps=False):
    """Semismooth Newton (dense) on min(c h, q + sigma(h)); returns (q, Newton iterations, converged).

    A step is backtracked until the merit falls (Armijo), or, with ``full_steps``, taken whole.
    """
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
            if full_steps or Fn @ Fn <= (1.0 - 1e-4 * t) * merit or t < 1e-4:
                break
            t *= 0.5
        q = qn
    return q, max_newton, False


class SphereCase:
    """The sphere at mu on a ring mesh placed on Maugis-Dugdale's pull-off rims.

    ``pad`` (zone widths) extends the uniform band beyond both rims; ``stagger`` shifts each ray
    strip's nodes by a golden-ratio fraction of a band step (up to 0.45 of it); ``global_w`` takes
    the band's widest ramp on every panel.
    """

    def __init__(self, mu, n_phi, cells_across, *, growth=1.3, smooth=False, stagger=False, pad=None,
                 global_w=False, arc_segments=1, full_steps=False):
        from dhfield.models import maugis_dugdale

        self.md = maugis_dugdale.pull_off_nondimensional(1.0, mu)
        a, c = float(self.md.a_star), float(self.md.c_star)
        m = c / a
        fine = (m - 1.0) / cells_across
        pad = 4.0 * fine if pad is None else pad * (m - 1.0)
        s = graded_nodes((1.0, m), fine, growth, 1.6 * max(m, 1.0), pad)
        jitter = None
        if stagger:
            taper = np.clip(np.minimum(s / (1.0 - pad), (s[-1] - s) / (s[-1] - m - pad)), 0.0, 1.0)
            xi = (np.arange(n_phi) * 0.6180339887498949) % 1.0 - 0.5
            jitter = 0.9 * fine * xi[:, None] * taper[None, :]
        self.mesh = RingMesh(a, a, s, n_phi, jitter, arc_segments)
        t0 = time.perf_counter()
        self.K = self.mesh.operator()
        self.assembly = time.perf_counter() - t0
        self.z = 0.5 * (self.mesh.cx ** 2 + self.mesh.cy ** 2)
        self.sigma0, self.h0 = float(mu), 1.0 / float(mu)
        factor = 1.5 * (1.5 if smooth else 1.0)                   # the smoothstep's steepest slope is 1.5/w
        self.w = np.minimum(factor * self.sigma0 * self.mesh.ring_compliance(self.K), 2.0 * self.h0)
        r = np.hypot(self.mesh.cx, self.mesh.cy)
        if global_w:
            self.w = np.full_like(self.w, float(np.max(self.w[(r > a) & (r < c)])))
        self.band = (a * (1.0 - pad), a * (m + pad))
        self.smooth, self.full_steps = smooth, full_steps
        self.zone = (r < c).astype(float) * self.sigma0

    @staticmethod
    def md_at(mu):
        from dhfield.models import maugis_dugdale

        return maugis_dugdale.pull_off_nondimensional(1.0, mu)

    def w_star(self, q):
        return 4.0 * float(q @ self.mesh.area) / (2.0 * math.pi)   # Eq. (34), R = dgamma = 1, sphere

    def contact_rim(self, delta, q):
        """Largest centroid radius in contact [c_r]."""
        h = self.z - delta + self.K @ q
        return float(np.max(np.hypot(self.mesh.cx, self.mesh.cy)[h <= 0.0]))

    def solve(self, delta, q=None):
        if q is None:
            q, _ = contact_start(self.K, self.z, delta, self.zone)
        return adhesive_state(self.K, self.z, delta, q, self.sigma0, self.h0, self.w, self.smooth,
                              full_steps=self.full_steps)


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
        mesh = RingMesh(1.0, 1.0, graded_nodes((1.0, 1.05), 0.05 / across, 1.3, 2.0, 0.2 / across), n_phi)
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

    print("\n3. mu = 10 at Maugis-Dugdale's pull-off approach, one state from the analytic start "
          f"(MD's contact rim a = {float(SphereCase.md_at(10.0).a_star):.5f})")
    print(f"{'variant':<44} {'panels':>6} {'w/h0':>5} {'newton':>6} {'conv':>5} {'W*':>10} {'vs MD':>9} "
          f"{'rim':>8} {'in band':>7} {'time':>6}")
    variants = [
        ("linear ramp, aligned, 32 rays, 8 across", dict(n_phi=32, cells_across=8)),
        ("linear ramp, aligned, 32 rays, 16 across", dict(n_phi=32, cells_across=16)),
        ("C1 ramp, aligned, 32 rays, 16 across", dict(n_phi=32, cells_across=16, smooth=True)),
        ("C1 ramp, staggered, 32 rays, 16 across", dict(n_phi=32, cells_across=16, smooth=True, stagger=True)),
        ("  + full steps, band +1 zone, one ramp", dict(n_phi=32, cells_across=16, smooth=True, stagger=True,
                                                        full_steps=True, pad=1.0, global_w=True, growth=1.15)),
        ("  + 16 rays", dict(n_phi=16, cells_across=16, smooth=True, stagger=True, full_steps=True, pad=1.0,
                             global_w=True, growth=1.15)),
        ("  + 32 rays, arcs of 4 chords", dict(n_phi=32, cells_across=16, smooth=True, stagger=True, full_steps=True,
                                               pad=1.0, global_w=True, growth=1.15, arc_segments=4)),
    ]
    for name, kw in variants:
        t0 = time.perf_counter()
        case = SphereCase(10.0, **kw)
        d = float(case.md.delta_star)
        q, it, ok = case.solve(d)
        rim = case.contact_rim(d, q)
        print(f"{name:<44} {case.mesh.n:6d} {float(np.min(case.w)) / case.h0:5.2f} {it:6d} {str(ok):>5} "
              f"{case.w_star(q):10.6f} {case.w_star(q) / float(case.md.W_star) - 1:+9.2e} {rim:8.5f} "
              f"{str(case.band[0] <= rim <= case.band[1]):>7} {time.perf_counter() - t0:5.1f}s")
    print(f"\n(total {time.perf_counter() - t_all:.0f} s)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
