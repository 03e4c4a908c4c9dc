"""The JKR limit of the elliptical contact: GVG (2025) against JG (2005), Li & Popov (2020) and the BEM.

Prints, for equal cylinders crossed at 10-90 deg (beta0 from :mod:`dhfield.core.geometry`), the
load-control pull-off F/(pi sqrt(R'R'') dgamma) of

* ``GVG``: the energy-minimising elliptical JKR of Giudici, Vella & Griffiths
  (:mod:`dhfield.models.jkr_elliptic_energy`, model ``jkr-elliptic-energy``);
* ``JG``: Johnson & Greenwood (2005) (:mod:`dhfield.models.jkr_elliptic`, ``jkr-elliptic``);
* ``LP``: the Li & Popov (J. Phys. D 2020) BEM fit for JKR ellipsoids, THIRD-PARTY values:
  as transcribed in kmnam/biofilm-ABMs (``jkr.hpp``, unverified against the paper) and quoted
  in the project notes (adhesive-solver.md) at R'/R'' = 1, 3, 5, 10, 20, 50 only; between
  them interpolated here linearly in ln(R'/R''), beyond 50 not available.  ``LP/sph`` is the
  fit divided by its own sphere value 1.487 (0.9 % below the exact 1.5), times 1.5;

and the relative differences.  Then, for context, the stored BEM ground truth
(``data/adhesive_ground_truth.nc``, Dugdale law, Richardson-extrapolated W*) at its
largest mu, beside GVG corrected by the sphere's Maugis-Dugdale/JKR ratio at that mu.
The slender ground truth (``data/adhesive_ground_truth_slender.nc``, beta0 0.1-0.3) is not
used here: it stores mu = 0.1, 0.3, 1, 5 only, two of them on the JKR side (mu >= 1), too few
for the family of fits below.

Finally, a **numerical JKR limit that does not assume an elliptical contact**: the stored
BEM W*(mu) at each beta0 extrapolated to mu -> infinity (:func:`extrapolate_jkr_limit`,
:func:`bem_jkr_limits`), with an error estimate, beside GVG and JG.  The BEM finds the
contact and adhesive shapes itself; the extrapolation assumes only that the elliptical
contact approaches JKR the way the sphere does (the form of Maugis-Dugdale near JKR).

Extrapolation to mu -> infinity
-------------------------------
Two forms, both from Maugis-Dugdale on the sphere (Maugis 1992; lambda = 1.1272 mu):

* **transition form** (``"g"``): W*(mu) = -s + (W_inf + s) g(mu), with s = sin(theta_skew)
  (W* of DMT, Eq. 34) and g = (W*_MD + 1)/(W*_JKR + 1) the sphere's DMT-to-JKR weight
  (exact for the sphere, where W_inf = -3/4).  Least squares in W_inf over a set of mu.
* **asymptotic series** (``"series"``): W*(mu) = W_inf + A/mu^2 (+ B/mu^4).  Near JKR,
  m = c/a -> 1 and Maugis' two equations expand in s_m^2 = m^2 - 1: the first gives
  (2/3) lambda^2 A_bar s_m^2 = 1 + O(s_m^2), so s_m^2 = 3/(2 lambda^2 A_bar); the load
  P_bar = A_bar^3 - lambda A_bar^2 (2 s_m + (2/3) s_m^3 + ...) is JKR's
  A_bar^3 - sqrt(6 A_bar^3) plus a series in s_m^2, i.e. in 1/lambda^2 ~ 1/mu^2.  On the
  sphere W*_MD + 3/4 = -0.0645/mu^2 (1 + O(mu^-2)) (MD at mu = 10-1000).  A and B free.

The estimate uses only the stored mu >= :data:`MU_JKR_SIDE` (the JKR side, lambda >= 1.13):
the central value is the transition form at the largest stored mu (the finest grids and the
smallest correction, g(5) = 0.990); the family is the transition form over every non-empty
subset of the (up to) three largest such mu, the 1/mu^2 series through the two largest and
the 1/mu^2 + 1/mu^4 series through the three largest.  The error is the largest distance
of a family member from the central value plus the BEM's own uncertainty at the largest mu
(the last step of its N ladder, divided by g).  Each member is checked on MD itself sampled
at the study's mu (``tests/test_jkr_limit.py``: -3/4 within 0.05 %).

``python -m verification.jkr_limit``
"""
from __future__ import annotations

from dataclasses import dataclass, field
from itertools import combinations
from pathlib import Path

import numpy as np

from dhfield.models import jkr_elliptic as jg
from dhfield.models import jkr_elliptic_energy as gvg
from dhfield.models import maugis_dugdale
from dhfield.core.geometry import ellipticity_from_skew_angle, radius_ratio, sin_skew_angle, skew_angle

DATASET = Path(__file__).resolve().parent.parent / "data" / "adhesive_ground_truth.nc"
#: Li & Popov (2020) fit, F/(pi sqrt(R'R'') dgamma) at R'/R'': third-party transcription (notes).
LI_POPOV = {1.0: 1.487, 3.0: 1.468, 5.0: 1.458, 10.0: 1.442, 20.0: 1.422, 50.0: 1.387}
LI_POPOV_SPHERE = 1.487


def li_popov(rho):
    """The third-party LP values, interpolated linearly in ln(rho); NaN beyond rho = 50."""
    x = np.log(np.array(sorted(LI_POPOV)))
    y = np.array([LI_POPOV[k] for k in sorted(LI_POPOV)])
    rho = np.asarray(rho, float)
    out = np.interp(np.log(rho), x, y)
    return np.where(rho <= 50.0 + 1e-9, out, np.nan)


def pull_off_ratio_table(angles_deg):
    """Rows (angle, beta0, rho, GVG, JG, LP, LP/sph) of F/(pi R dgamma), load control."""
    th = np.radians(np.asarray(angles_deg, float))
    beta0 = ellipticity_from_skew_angle(th)
    rho = radius_ratio(beta0)
    f_gvg = 1.5 * gvg.pull_off_force_ratio(beta0=beta0)
    f_jg = 1.5 * jg.pull_off_force_ratio(beta0=beta0)
    lp = li_popov(rho)
    return beta0, rho, f_gvg, f_jg, lp, lp / LI_POPOV_SPHERE * 1.5


def _pct(x):
    return "   n/a" if not np.isfinite(x) else f"{100 * x:+6.2f}"


def ground_truth_rows():
    """(beta0, mu, W*_BEM, W*_GVG, W*_GVG x MD/JKR, W*_JG) at the largest stored mu."""
    import xarray as xr

    with xr.open_dataset(DATASET) as ds:
        mu = float(ds["mu"].values.max())
        w = ds["W_star_extrapolated"].sel(mu=mu).values
        b0 = ds["beta0"].values
    md_over_jkr = float(maugis_dugdale.pull_off_nondimensional(beta0=1.0, mu=mu).W_star) / -0.75
    w_gvg = gvg.pull_off_nondimensional(beta0=b0, mu=1.0).W_star
    w_jg = jg.pull_off_nondimensional(beta0=b0, mu=1.0).W_star
    return mu, md_over_jkr, [(b, mu, wb, wg, wg * md_over_jkr, wj)
                             for b, wb, wg, wj in zip(b0, w, w_gvg, w_jg)]


#: The JKR side of the transition: the extrapolation uses stored mu >= this (lambda = 1.1272 mu >= 1.13) [-].
MU_JKR_SIDE = 1.0
#: At most this many of the largest stored mu enter the extrapolation.
N_MU_FIT = 3
#: W* of the JKR sphere, load control (JKR 1971: W = -(3/2) pi R dgamma).
W_STAR_JKR_SPHERE = -0.75


def sphere_transition_weight(mu):
    """The sphere's DMT-to-JKR weight g = (W*_MD + 1)/(W*_JKR + 1), load control [-].

    Parameters
    ----------
    mu : array_like
        Tabor parameter of Eq. (35), R = sqrt(R'R'') [-].

    Returns
    -------
    ndarray
        0 at DMT (mu -> 0), 1 at JKR (mu -> infinity); MD of :mod:`dhfield.models.maugis_dugdale`.
    """
    w = maugis_dugdale.pull_off_nondimensional(beta0=1.0, mu=np.asarray(mu, float)).W_star
    return (np.asarray(w, float) + 1.0) / (W_STAR_JKR_SPHERE + 1.0)


def transition_form_limit(mu, w_star, sin_skew):
    """W_inf of W*(mu) = -s + (W_inf + s) g(mu), least squares over the given mu [-].

    Parameters
    ----------
    mu, w_star : array_like
        Tabor parameters and the W* (Eq. 34) there [-].
    sin_skew : float
        sin(theta_skew) of the geometry: W* of DMT is -sin_skew [-].

    Returns
    -------
    float
        The extrapolated W* at mu -> infinity.
    """
    g = sphere_transition_weight(mu)
    w = np.asarray(w_star, float)
    return float(-sin_skew + np.sum(g * (w + sin_skew)) / np.sum(g * g))


def series_limit(mu, w_star, terms):
    """W_inf of W*(mu) = W_inf + A/mu^2 (+ B/mu^4), through ``terms`` points exactly [-].

    Parameters
    ----------
    mu, w_star : array_like
        ``terms`` Tabor parameters and their W* [-].
    terms : {2, 3}
        Number of terms of the series in 1/mu^2.

    Returns
    -------
    float
        The extrapolated W* at mu -> infinity.
    """
    mu = np.asarray(mu, float)
    a = np.stack([mu ** (-2.0 * k) for k in range(terms)], axis=1)
    return float(np.linalg.solve(a, np.asarray(w_star, float))[0])


@dataclass(frozen=True)
class JKRLimit:
    """A numerical JKR limit W*(mu -> infinity) with its error estimate.

    Parameters
    ----------
    w_inf : float
        Central value: the transition form at the largest mu used [-].
    error : float
        ``fit_spread + bem_error`` [-].
    fit_spread : float
        Largest distance of a family member from ``w_inf`` [-].
    bem_error : float
        The BEM's uncertainty at the largest mu over g there (0 when not given) [-].
    mu_used : tuple of float
        The mu that entered (ascending).
    estimates : dict
        Family member label -> its W_inf [-].
    """

    w_inf: float
    error: float
    fit_spread: float
    bem_error: float
    mu_used: tuple
    estimates: dict = field(default_factory=dict)


def extrapolate_jkr_limit(mu, w_star, sin_skew, w_uncertainty=None) -> JKRLimit:
    """Extrapolate W*(mu) of one geometry to mu -> infinity (module docstring).

    Parameters
    ----------
    mu, w_star : array_like
        Tabor parameters (Eq. 35) and the load-control W* there (Eq. 34) [-]; non-finite
        W* are skipped, and only mu >= :data:`MU_JKR_SIDE` is used (the largest
        :data:`N_MU_FIT` of them).
    sin_skew : float
        sin(theta_skew) of the geometry, in (0, 1] [-].
    w_uncertainty : array_like, optional
        Absolute uncertainty of each W* [-] (same shape as ``mu``).

    Returns
    -------
    JKRLimit
        The central value, its error and the family of estimates.

    Raises
    ------
    ValueError
        If no finite W* exists at mu >= MU_JKR_SIDE, or ``sin_skew`` is outside (0, 1].
    """
    if not 0.0 < float(sin_skew) <= 1.0:
        raise ValueError(f"sin_skew must be in (0, 1]; got {sin_skew!r}")
    mu = np.asarray(mu, float).ravel()
    w = np.asarray(w_star, float).ravel()
    unc = np.zeros_like(w) if w_uncertainty is None else np.asarray(w_uncertainty, float).ravel()
    keep = np.isfinite(w) & (mu >= MU_JKR_SIDE)
    order = np.argsort(mu[keep])[-N_MU_FIT:]
    mu, w, unc = mu[keep][order], w[keep][order], unc[keep][order]
    if mu.size == 0:
        raise ValueError(f"mu must include at least one finite W* at mu >= {MU_JKR_SIDE:g}; got none")
    s = float(sin_skew)
    central = transition_form_limit(mu[-1:], w[-1:], s)
    est = {}
    for k in range(1, mu.size + 1):
        for idx in combinations(range(mu.size), k):
            idx = list(idx)
            est["g, mu = " + "/".join(f"{m:g}" for m in mu[idx])] = transition_form_limit(mu[idx], w[idx], s)
    if mu.size >= 2:
        est["1/mu^2, mu = " + "/".join(f"{m:g}" for m in mu[-2:])] = series_limit(mu[-2:], w[-2:], 2)
    if mu.size >= 3:
        est["1/mu^2+1/mu^4, mu = " + "/".join(f"{m:g}" for m in mu[-3:])] = series_limit(mu[-3:], w[-3:], 3)
    spread = max(abs(v - central) for v in est.values())
    bem = float(abs(unc[-1]) / sphere_transition_weight(mu[-1]))
    return JKRLimit(central, spread + bem, spread, bem, tuple(float(m) for m in mu), est)


def ladder_uncertainty(ds):
    """Relative uncertainty of the stored W* at each mu: the largest last step of the N ladder.

    For every (beta0, mu) with two usable N levels, ``|W*(N) / W*(N/2) - 1|`` of the two finest;
    per mu, the largest over beta0 (several cases have a single usable N, so the step of the
    neighbouring beta0 at the same mu stands in).

    Parameters
    ----------
    ds : xarray.Dataset
        The stored ground truth (``W_star``, ``status`` on beta0, mu, n).

    Returns
    -------
    ndarray, shape (n_mu,)
        Relative uncertainty [-]; NaN where no case at that mu has two usable levels.
    """
    from verification.study_adhesive import STATUSES, USABLE

    w = ds["W_star"].transpose("beta0", "mu", "n").values
    usable = np.isin(ds["status"].transpose("beta0", "mu", "n").values, [STATUSES.index(u) for u in USABLE])
    out = np.full(w.shape[1], np.nan)
    for i in range(w.shape[0]):
        for j in range(w.shape[1]):
            k = np.flatnonzero(usable[i, j] & np.isfinite(w[i, j]))
            if k.size >= 2:
                step = abs(w[i, j, k[-1]] / w[i, j, k[-2]] - 1.0)
                out[j] = step if not np.isfinite(out[j]) else max(out[j], step)
    return out


def bem_jkr_limits(path=DATASET):
    """The numerical JKR limit at every stored beta0, beside GVG and JG (load control).

    Parameters
    ----------
    path : path-like
        The stored ground truth (``data/adhesive_ground_truth.nc``).

    Returns
    -------
    list of dict
        Per beta0: ``beta0``, ``angle_deg``, ``limit`` (:class:`JKRLimit`), ``gvg``, ``jg``
        (W* of Eq. 34), ``gvg_z`` = |GVG - W_inf|/error and ``jg_z`` likewise.
    """
    import xarray as xr

    with xr.open_dataset(path) as ds:
        ds = ds.load()
    mu = ds["mu"].values.astype(float)
    rel = ladder_uncertainty(ds)
    rows = []
    for b in ds["beta0"].values.astype(float):
        w = ds["W_star_extrapolated"].sel(beta0=b).values.astype(float)
        s = float(sin_skew_angle(b))
        lim = extrapolate_jkr_limit(mu, w, s, np.abs(w) * np.nan_to_num(rel, nan=np.inf))
        w_gvg = float(gvg.pull_off_nondimensional(beta0=b, mu=1.0).W_star)
        w_jg = float(jg.pull_off_nondimensional(beta0=b, mu=1.0).W_star)
        rows.append(dict(beta0=b, angle_deg=float(np.degrees(skew_angle(b))), limit=lim, gvg=w_gvg, jg=w_jg,
                         gvg_z=abs(w_gvg - lim.w_inf) / lim.error, jg_z=abs(w_jg - lim.w_inf) / lim.error))
    # the BEM's bias common to every beta0, measured on the sphere (exact limit -3/4)
    sph = [r["limit"].w_inf for r in rows if r["beta0"] == 1.0]
    scale = W_STAR_JKR_SPHERE / sph[0] if sph else float("nan")
    for r in rows:
        r["sphere_scale"] = scale
        r["w_inf_normalised"] = r["limit"].w_inf * scale
    return rows


def print_bem_jkr_limits(rows):
    """Print the table of :func:`bem_jkr_limits`."""
    print("Numerical JKR limit: the stored BEM W*(mu) extrapolated to mu -> infinity (no elliptical-shape "
          "assumption; the sphere's MD approach to JKR)")
    print(f"  mu used: {', '.join(f'{m:g}' for m in rows[0]['limit'].mu_used)} (mu >= {MU_JKR_SIDE:g}); "
          "error = spread of the family of fits + the BEM's N-ladder step at the largest mu over g")
    print(f"{'beta0':>6} {'angle':>6} {'W*_inf':>9} {'+-err':>8} {'err%':>6} {'spread':>8} {'BEM':>8}"
          f" {'GVG':>9} {'GVG/Winf-1%':>11} {'|dGVG|/err':>10} {'JG':>9} {'JG/Winf-1%':>10} {'|dJG|/err':>9}")
    for r in rows:
        lim = r["limit"]
        print(f"{r['beta0']:6.3f} {r['angle_deg']:6.1f} {lim.w_inf:9.5f} {lim.error:8.5f} "
              f"{100 * lim.error / abs(lim.w_inf):6.3f} {lim.fit_spread:8.5f} {lim.bem_error:8.5f}"
              f" {r['gvg']:9.5f} {_pct(r['gvg'] / lim.w_inf - 1):>11} {r['gvg_z']:10.2f}"
              f" {r['jg']:9.5f} {_pct(r['jg'] / lim.w_inf - 1):>10} {r['jg_z']:9.2f}")
    sph = [r for r in rows if r["beta0"] == 1.0]
    if sph:
        lim = sph[0]["limit"]
        print(f"Sphere check: W*_inf = {lim.w_inf:.5f} +- {lim.error:.5f} against JKR -0.75 "
              f"(|d|/err = {abs(lim.w_inf - W_STAR_JKR_SPHERE) / lim.error:.2f})")
    if sph:
        print(f"Divided by the sphere's own extrapolated value (x {rows[0]['sphere_scale']:.5f}: the BEM's bias "
              "common to every beta0, the sphere's exact limit being -3/4):")
        print("  " + "; ".join(f"beta0 {r['beta0']:g}: GVG {_pct(r['gvg'] / r['w_inf_normalised'] - 1)} %, "
                               f"JG {_pct(r['jg'] / r['w_inf_normalised'] - 1)} %" for r in rows))
    print("Family of fits per beta0 (W*_inf):")
    for r in rows:
        print(f"  beta0 = {r['beta0']:g}: " + "; ".join(f"{k}: {v:.5f}" for k, v in r["limit"].estimates.items()))
    print(f"Below beta0 = {min(r['beta0'] for r in rows):g} (crossing angles < "
          f"{min(r['angle_deg'] for r in rows):.0f} deg) only the slender ground truth is stored "
          "(data/adhesive_ground_truth_slender.nc: beta0 0.1, 0.1806, 0.3 at mu = 0.1, 0.3, 1, 5): mu <= 5, "
          f"with only mu = 1, 5 >= MU_JKR_SIDE = {MU_JKR_SIDE:g}, too few for the family of fits; the numerical "
          "limit does not judge GVG there.")


def main():
    angles = np.array([10, 15, 20, 25, 30, 35, 40, 45, 50, 60, 70, 80, 90], float)
    beta0, rho, f_gvg, f_jg, lp, lps = pull_off_ratio_table(angles)
    print("Load-control pull-off F/(pi sqrt(R'R'') dgamma); JKR sphere = 1.5")
    print("LP = Li & Popov 2020 fit, THIRD-PARTY transcription (kmnam/biofilm-ABMs jkr.hpp via the notes),")
    print("     interpolated in ln(R'/R''); LP/sph = LP x 1.5/1.487 (normalised by its own sphere value)")
    print(f"{'angle':>5} {'beta0':>7} {'R1/R2':>8} {'GVG':>7} {'JG':>7} {'LP':>7} {'LP/sph':>7}"
          f" {'JG/GVG-1%':>9} {'LP/GVG-1%':>9} {'LPs/GVG-1%':>10}")
    for i, a in enumerate(angles):
        print(f"{a:5.0f} {beta0[i]:7.4f} {rho[i]:8.2f} {f_gvg[i]:7.4f} {f_jg[i]:7.4f} {lp[i]:7.4f} {lps[i]:7.4f}"
              f" {_pct(f_jg[i] / f_gvg[i] - 1):>9} {_pct(lp[i] / f_gvg[i] - 1):>9} {_pct(lps[i] / f_gvg[i] - 1):>10}")
    try:
        mu, ratio, rows = ground_truth_rows()
    except (OSError, ImportError) as exc:  # no dataset or no xarray: the table above stands alone
        print(f"(ground truth not read: {exc})")
        return 0
    print()
    print(f"Stored BEM ground truth at the largest mu = {mu:g} (W* of Eq. 34, Richardson-extrapolated);")
    print(f"GVG*MD = GVG x (sphere MD/JKR pull-off at mu = {mu:g}) = GVG x {ratio:.5f}")
    print(f"{'beta0':>6} {'angle':>6} {'BEM':>9} {'GVG':>9} {'GVG*MD':>9} {'JG':>9}"
          f" {'GVG/BEM-1%':>10} {'GVG*MD/BEM-1%':>13} {'JG/BEM-1%':>9}")
    for b, _, wb, wg, wgm, wj in rows:
        ang = np.degrees(np.arccos(np.clip((radius_ratio(b) - 1) / (radius_ratio(b) + 1), -1, 1)))
        print(f"{b:6.3f} {ang:6.1f} {wb:9.5f} {wg:9.5f} {wgm:9.5f} {wj:9.5f}"
              f" {_pct(wg / wb - 1):>10} {_pct(wgm / wb - 1):>13} {_pct(wj / wb - 1):>9}")
    print("(F/(pi R dgamma) = 2 W*/sin(theta_skew); sin(theta_skew) of beta0: "
          + ", ".join(f"{b:g}: {float(sin_skew_angle(b)):.4f}" for b, *_ in rows) + ")")
    print()
    print_bem_jkr_limits(bem_jkr_limits())
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
