"""What a sweep computes at its grid points: pure numpy, no dask, no xarray.

Each quantity is a public function of plain numbers or arrays:

* :func:`pull_off_block` -- the analytic pull-off of one comparison model over a
  block of (beta0, mu) points, with each point's validity warning (one vectorised
  call of :func:`dhfield.compare.pull_off`).
* :func:`bem_field_case` -- the forward BEM check of one DH state
  (:func:`dhfield.fields.model_case`, :func:`dhfield.field_metrics.annulus_identity`).
* :func:`adhesive_case` -- the adhesive BEM ground truth at pull-off
  (:func:`dhfield.adhesive_start.adhesive_pull_off`).
* :func:`expected_seconds` -- a cost model of one case, used by the engine only
  to hand out the costliest tasks first.

The BEM cases run inside dask workers: the half-space operator they use is
built there on first use and cached per process by
:func:`dhfield.bem.get_operator`; it is never pickled.
"""
from __future__ import annotations

import numpy as np

from ..records import PullOff

__all__ = ["PULL_OFF_FIELDS", "CURVE_FIELDS", "load_curve_case", "BEM_FIELD_FIELDS", "ADHESIVE_FIELDS", "ADHESIVE_BEM_FIELDS", "ADHESIVE_MODEL",
           "pull_off_block", "block_values", "bem_field_case", "adhesive_case", "cohesive_laws", "adhesive_solver",
           "expected_seconds"]

#: Output fields of the analytic pull-off, in the order of the stacked block (names of
#: :data:`dhfield.io.compare.COMPARISON_VARIABLES`, metadata from :mod:`dhfield.schema`).
PULL_OFF_FIELDS = ("W_star", "a_star", "c_star", "v", "delta_star", "ellipticity", "sin_skew")
#: Output fields of a load curve (arrays over the contact sizes), named ``curve_<field>`` in a sweep.
CURVE_FIELDS = ("W_star", "delta_star", "c_star", "v")
#: Output fields of the forward BEM check of one state.
BEM_FIELD_FIELDS = ("bem_displacement_error", "bem_gap_error", "bem_annulus_error", "bem_c_star", "bem_v")
#: Output fields of the adhesive BEM ground truth at pull-off (nondimensional).
ADHESIVE_FIELDS = ("W_star", "a_star", "c_star", "ellipticity", "delta_star", "iterations")
#: Outputs only the adhesive BEM has (the semi-minor axes and both ellipticities from second
#: moments of the masks), stored per case beside :data:`ADHESIVE_FIELDS`, as `dhfield solve --json`.
ADHESIVE_BEM_FIELDS = ("b_star", "d_star", "beta_ab", "beta_cd")
#: Name of the adhesive ground truth on the ``model`` dimension of a sweep.
ADHESIVE_MODEL = "bem-adhesive"


def cohesive_laws() -> tuple:
    """List the names of the cohesive laws of the adhesive BEM solver.

    Returns
    -------
    tuple of str
        The names.
    """
    try:
        from ..bem.laws import LAWS
    except ImportError:  # pragma: no cover - laws module always ships
        return ("dugdale",)
    return tuple(LAWS)


def pull_off_block(model: str, *, beta0, mu, control: str = "load") -> PullOff:
    """Analytic pull-off of one model on a block of points: the record of :func:`dhfield.compare.pull_off`.

    One vectorised call of :func:`dhfield.compare.pull_off` on the whole block.

    Parameters
    ----------
    model : str
        One of :data:`dhfield.compare.MODEL_NAMES`.
    beta0, mu : array_like
        Hertz ellipticity [-] and Tabor parameter (Eq. 35) [-], broadcast together
        (keyword-only, as ``control``).
    control : {"load", "displacement"}
        Loading mode of the pull-off.

    Returns
    -------
    dhfield.records.PullOff
        Every array field of the shape ``broadcast(beta0, mu).shape`` (the sweep stores
        :data:`PULL_OFF_FIELDS` and ``warning``, each record's validity warning,
        :mod:`dhfield.validity`; empty inside the validated range).
    """
    from ..compare import pull_off

    beta0, mu = np.broadcast_arrays(np.asarray(beta0, float), np.asarray(mu, float))
    shape = mu.shape
    # The two-axis closure behind dh-elliptic's departure warning is a model of its own
    # ("dh-elliptic-two-axis"): sweep it, and map the departure, rather than solve it twice.
    rec = pull_off(model, beta0=beta0.ravel(), mu=mu.ravel(), control=control, check_closure=False)
    return rec.replace(**{k: np.broadcast_to(np.asarray(rec[k]), (mu.size,)).reshape(shape)
                          for k in rec if k not in ("model", "control", "geometry")})


def block_values(rec: PullOff) -> np.ndarray:
    """Stack the :data:`PULL_OFF_FIELDS` of a block's record on a last axis.

    Parameters
    ----------
    rec : dhfield.records.PullOff
        A block's record (:func:`pull_off_block`).

    Returns
    -------
    ndarray
        Shape ``rec.W_star.shape + (len(PULL_OFF_FIELDS),)``, float (NaN where the model has none).
    """
    return np.stack([np.asarray(rec[k], dtype=float) for k in PULL_OFF_FIELDS], axis=-1)


def load_curve_case(model: str, *, beta0: float, mu: float, a_star) -> dict:
    """Compute the load curve of one model at the contact sizes ``a_star``.

    Parameters
    ----------
    model : str
        One of :data:`dhfield.compare.MODEL_NAMES` (:func:`dhfield.compare.load_curve`).
    beta0 : float
        Hertz ellipticity [-].
    mu : float
        Tabor parameter, Eq. (35) [-].
    a_star : array_like
        Contact semi-major axes a* = a/c_r [-].

    Returns
    -------
    dict
        :data:`CURVE_FIELDS` -> arrays over ``a_star`` (NaN where the model has none).
    """
    from ..compare import load_curve

    rec = load_curve(model, mu=float(mu), beta0=float(beta0), a_star=np.asarray(a_star, dtype=float))
    return {k: np.asarray(rec[k], dtype=float) for k in CURVE_FIELDS}


def bem_field_case(beta0: float, mu: float, a_star: float, n: int, *, half_width=None,
                   sampling="average") -> dict:
    """Check the DH state at contact size ``a_star`` with the forward BEM (one case).

    The DH pressure of :func:`dhfield.model.solve_adhesive_axis` is put on an
    ``n`` x ``n`` grid, its displacement computed with the DC-FFT operator and
    compared with Eq. (26); the gap with Eq. (27); the annulus identity
    h = (1 + v) h_Hertz is checked along every ray.

    Parameters
    ----------
    beta0 : float
        Hertz ellipticity [-].
    mu : float
        Tabor parameter, Eq. (35) [-].
    a_star : float
        Contact semi-major axis a* = a/c_r [-].
    n : int
        Cells per axis [-].
    half_width : float, optional
        Half-width of the domain [c_r]; default 1.5 c*.
    sampling : {"average", "centre"}
        Cell means (default) or centre values of the pressure.

    Returns
    -------
    dict
        :data:`BEM_FIELD_FIELDS`: maximum displacement and gap errors over the
        grid relative to max |omega| [-], worst relative annulus-identity error
        [-], and the solved c* and v of the state.
    """
    from ..field_metrics import annulus_identity
    from ..fields import model_case

    case = model_case(int(n), float(beta0), float(mu), float(a_star), half_width=half_width,
                      sampling=sampling, threads=1)
    prm = case.parameters
    return {"bem_displacement_error": case.displacement_errors()["all"]["rel_max"],
            "bem_gap_error": case.gap_errors()["all"]["rel_max"],
            "bem_annulus_error": annulus_identity(case)["worst"],
            "bem_c_star": float(prm["c_star"]), "bem_v": float(prm["scaling"])}


def adhesive_solver(name: str = "default"):
    """Return the adhesive BEM solver of a name.

    Parameters
    ----------
    name : {"default"}
        The solver's name.

    Returns
    -------
    callable
        :func:`dhfield.adhesive_start.adhesive_pull_off`.

    Raises
    ------
    ValueError
        For another name.
    """
    if name != "default":
        raise ValueError(f"adhesive solver must be one of ('default',); got {name!r}")
    from ..adhesive_start import adhesive_pull_off

    return adhesive_pull_off


def adhesive_case(beta0: float, mu: float, n: int, law: str, control: str = "load", *,
                  solver: str = "default") -> dict:
    """Compute the adhesive BEM ground truth at pull-off of one (beta0, mu, n, law) case.

    The whole load path runs in this one call (each step warm-starts from the
    last).

    Parameters
    ----------
    beta0 : float
        Hertz ellipticity [-].
    mu : float
        Tabor parameter, Eq. (35) [-].
    n : int
        Cells per axis [-].
    law : str
        Cohesive law, one of :func:`cohesive_laws`.
    control : {"load", "displacement"}
        Loading mode of the pull-off.
    solver : {"default"}
        The solver (:func:`adhesive_solver`).

    Returns
    -------
    dict
        :data:`ADHESIVE_FIELDS` and :data:`ADHESIVE_BEM_FIELDS` (NaN where the
        solver gives none) plus ``converged`` (bool), ``resolved`` (bool: the grid
        resolves the cohesive zone) and ``message`` (str).
    """
    res = adhesive_solver(solver)(beta0=float(beta0), mu=float(mu), n=int(n), law=law, control=control, threads=1)

    def get(*names):
        for nm in names:
            if getattr(res, nm, None) is not None:
                return float(getattr(res, nm))
        return float("nan")

    out = {"W_star": get("W_star"), "a_star": get("a_star"), "c_star": get("c_star"),
           "ellipticity": get("ellipticity", "beta_ab"), "delta_star": get("delta_star"),
           "iterations": get("iterations")}
    # the BEM's pull-off record names its ellipticities as every model's; the sweep stores them as beta_ab, beta_cd
    record_name = {"beta_ab": "ellipticity", "beta_cd": "adhesive_ellipticity"}
    out.update({k: get(record_name.get(k, k), k) for k in ADHESIVE_BEM_FIELDS})
    out["converged"] = bool(getattr(res, "converged", True))
    out["resolved"] = bool(getattr(res, "resolved", True))
    message = str(getattr(res, "message", "") or "")
    if not out["converged"] and not message:
        failures = getattr(res, "failures", ()) or ()
        residual = getattr(res, "residual", float("nan"))
        message = f"{len(failures)} state(s) of the load path did not converge; largest residual {residual:.3g}"
    out["message"] = message
    return out


#: Cost model of :func:`expected_seconds`, calibrated on one core of the 2-core development
#: machine at N = 256 (2026-11-23).  Forward BEM: ~0.15 s a state (Eq. 26 on the grid, dominated
#: by the ellipsoid integrals, O(N^2)).  Adhesive pull-off (path of commit 44d8f34, 4-6 states):
#: CG iterations over the path 185, 249, 402, 1084 at beta0 = 0.8 and mu = 0.3, 0.5, 1, 2
#: (130, 238, 329, 1032 at beta0 = 1), i.e. ~mu^1.1 and ~20 % more for beta0 < 1, at a few ms
#: an iteration: about 2 (mu^1.1 + 0.06) s.  (The path before it took 4-28 s, 807-6435
#: iterations, with the same ranking.)  Load curve: ~1 ms a point.  Only the ranking matters to
#: the schedule; the scale only weighs one quantity against another in a mixed sweep.
_SECONDS_BEM_FIELD_256 = 0.15
_SECONDS_ADHESIVE_256 = 2.0
_ADHESIVE_MU_EXPONENT = 1.1
_ADHESIVE_MU_OFFSET = 0.06
_SECONDS_CURVE_POINT = 1e-3


def _grid_scale(n) -> float:
    """FFT work of an n x n grid relative to n = 256: n^2 log n (padded 2n x 2n transforms)."""
    n = float(n)
    return (n / 256.0) ** 2 * np.log(2.0 * n) / np.log(512.0)


def expected_seconds(quantity: str, params: dict) -> float:
    """Rough single-core wall time of one case [s]: the engine's cost model.

    The engine sorts its tasks by this estimate so that the costliest start
    first (longest-processing-time order) while dask hands tasks to workers as
    they free up.  A wrong estimate costs load balance, never correctness: every
    case is independent, so results are identical in any order.

    Parameters
    ----------
    quantity : {"bem_field", "adhesive", "load_curve"}
        The kind of case.
    params : dict
        The case's keyword arguments (:func:`bem_field_case`,
        :func:`adhesive_case`, :func:`load_curve_case`).

    Returns
    -------
    float
        The estimate [s].

    Notes
    -----
    Forward BEM and adhesive cases scale with the FFT work n^2 log n; an
    adhesive pull-off also with its CG iterations, which grow like mu^1.1 with
    the Tabor parameter (a narrower cohesive zone on the same grid), and by
    ~20 % for beta0 < 1.  Constants: ``_SECONDS_*`` in this module, with their
    provenance.
    """
    if quantity == "bem_field":
        return _SECONDS_BEM_FIELD_256 * _grid_scale(params["n"])
    if quantity == "adhesive":
        ellipse = 1.2 if float(params["beta0"]) < 1.0 else 1.0
        mu_work = float(params["mu"]) ** _ADHESIVE_MU_EXPONENT + _ADHESIVE_MU_OFFSET
        return _SECONDS_ADHESIVE_256 * _grid_scale(params["n"]) * mu_work * ellipse
    if quantity == "load_curve":
        return _SECONDS_CURVE_POINT * len(params["a_star"])
    raise ValueError(f"quantity must be 'bem_field', 'adhesive' or 'load_curve'; got {quantity!r}")
