"""What a sweep computes at its grid points: pure numpy, no dask, no xarray.

Each quantity is a public function of plain numbers or arrays:

* :func:`pull_off_block` -- the analytic pull-off of one comparison model over a
  block of (beta0, mu) points, with each point's validity warning (one vectorised
  call of :func:`dhfield.analysis.compare.pull_off`).
* :func:`bem_field_case` -- the forward BEM check of one DH state
  (:func:`dhfield.analysis.fields.model_case`, :func:`dhfield.analysis.field_metrics.annulus_identity`).
* :func:`adhesive_case` -- the adhesive BEM ground truth at pull-off
  (:func:`dhfield.analysis.bem_start.adhesive_pull_off`), on an explicit n x n grid or on
  the automatic grid and its refinements (:func:`automatic_grid`).
* :func:`expected_seconds` -- a cost model of one case, used by the engine only
  to hand out the costliest tasks first.

The BEM cases run inside dask workers: the half-space operator they use is
built there on first use and cached per process by
:func:`dhfield.bem.get_operator`; it is never pickled.
"""
from __future__ import annotations

import numpy as np

from ..core.records import LoadCurve, PullOff
from .config import MAX_GRID_LEVEL

__all__ = ["PULL_OFF_FIELDS", "CURVE_FIELDS", "load_curve_case", "BEM_FIELD_FIELDS", "ADHESIVE_FIELDS",
           "ADHESIVE_BEM_FIELDS", "ADHESIVE_GRID_FIELDS", "ADHESIVE_TEXT_FIELDS", "ADHESIVE_MODEL",
           "pull_off_block", "block_values", "bem_field_case", "adhesive_case", "automatic_grid",
           "adhesive_solver", "expected_seconds"]

#: Output fields of the analytic pull-off, in the order of the stacked block (names of
#: :data:`dhfield.io.compare.COMPARISON_VARIABLES`, metadata from :mod:`dhfield.core.schema`).
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
#: Numbers of each adhesive case beside its outputs: the grid solved (cells along x and y,
#: domain half-widths [c_r]), the stated error of W* (inf when none), the flags (1/0), the
#: states solved, and the wall and CPU time of the case [s] (on a shared machine: load varies).
ADHESIVE_GRID_FIELDS = ("nx", "ny", "half_width_x", "half_width_y", "W_star_error", "converged", "resolved",
                        "n_steps", "wall_seconds", "cpu_seconds")
#: Text of each adhesive case: the route that gave the pull-off (the solver's ``search``), the
#: solver's caveats (``note``), and its provenance (the git commit of the code that solved it and
#: the UTC time it finished; the command line is added by the engine).
ADHESIVE_TEXT_FIELDS = ("search", "note", "commit", "finished", "solver_options")
#: Name of the adhesive ground truth on the ``model`` dimension of a sweep.
ADHESIVE_MODEL = "bem-adhesive"


def pull_off_block(model: str, *, beta0, mu, control: str = "load") -> PullOff:
    """Analytic pull-off of one model on a block of points: the record of :func:`dhfield.analysis.compare.pull_off`.

    One vectorised call of :func:`dhfield.analysis.compare.pull_off` on the whole block.

    Parameters
    ----------
    model : str
        One of :data:`dhfield.analysis.compare.MODEL_NAMES`.
    beta0, mu : array_like
        Hertz ellipticity [-] and Tabor parameter (Eq. 35) [-], broadcast together
        (keyword-only, as ``control``).
    control : {"load", "displacement"}
        Loading mode of the pull-off.

    Returns
    -------
    dhfield.core.records.PullOff
        Every array field of the shape ``broadcast(beta0, mu).shape`` (the sweep stores
        :data:`PULL_OFF_FIELDS` and ``warning``, each record's validity warning,
        :mod:`dhfield.analysis.validity`; empty inside the validated range).

    Raises
    ------
    ValueError
        As :func:`dhfield.analysis.compare.pull_off`: naming ``beta0`` or ``mu`` if out of range, or if the
        block has no points.
    """
    from ..analysis.compare import pull_off

    beta0, mu = np.broadcast_arrays(np.asarray(beta0, float), np.asarray(mu, float))
    shape = mu.shape
    # The two-axis closure behind dh-elliptic's departure warning is a model of its own
    # ("dh-elliptic-two-axis"): sweep it, and map the departure, rather than solve it twice.
    rec = pull_off(model, beta0=beta0.ravel(), mu=mu.ravel(), control=control, check_closure=False, warn=False)
    return rec.replace(**{k: np.broadcast_to(np.asarray(rec[k]), (mu.size,)).reshape(shape)
                          for k in rec if k not in ("model", "control", "geometry")})


def block_values(rec: PullOff) -> np.ndarray:
    """Stack the :data:`PULL_OFF_FIELDS` of a block's record on a last axis.

    Parameters
    ----------
    rec : dhfield.core.records.PullOff
        A block's record (:func:`pull_off_block`).

    Returns
    -------
    ndarray
        Shape ``rec.W_star.shape + (len(PULL_OFF_FIELDS),)``, float (NaN where the model has none).
    """
    return np.stack([np.asarray(rec[k], dtype=float) for k in PULL_OFF_FIELDS], axis=-1)


def load_curve_case(model: str, *, beta0: float, mu: float, a_star) -> LoadCurve:
    """Compute the load curve of one model at the contact sizes ``a_star``.

    Parameters
    ----------
    model : str
        One of :data:`dhfield.analysis.compare.MODEL_NAMES` (:func:`dhfield.analysis.compare.load_curve`).
    beta0 : float
        Hertz ellipticity [-].
    mu : float
        Tabor parameter, Eq. (35) [-].
    a_star : array_like
        Contact semi-major axes a* = a/c_r [-].

    Returns
    -------
    dhfield.core.records.LoadCurve
        The model's curve (:func:`dhfield.analysis.compare.load_curve`); the sweep stores its
        :data:`CURVE_FIELDS`, arrays over ``a_star`` (NaN where the model has none).
    """
    from ..analysis.compare import load_curve

    return load_curve(model, mu=float(mu), beta0=float(beta0), a_star=np.asarray(a_star, dtype=float))


def bem_field_case(beta0: float, mu: float, a_star: float, n: int, *, half_width=None,
                   sampling="average") -> dict:
    """Check the DH state at contact size ``a_star`` with the forward BEM (one case).

    The DH pressure of :func:`dhfield.models.dh_elliptic.solve_adhesive_axis` is put on an
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
    from ..analysis.field_metrics import annulus_identity
    from ..analysis.fields import model_case

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
        :func:`dhfield.analysis.bem_start.adhesive_pull_off`.

    Raises
    ------
    ValueError
        For another name.
    """
    if name != "default":
        raise ValueError(f"adhesive solver must be one of ('default',); got {name!r}")
    from ..analysis.bem_start import adhesive_pull_off

    return adhesive_pull_off


def automatic_grid(beta0: float, mu: float, grid_level: int = 1, *, law: str = "dugdale",
                   control: str = "load", max_seconds: float | None = None) -> dict:
    """The grid of an adhesive case at a grid level of the automatic plan.

    Level 1 is the grid :func:`dhfield.analysis.bem_start.adhesive_pull_off` plans when no ``n``
    is given (:func:`dhfield.analysis.bem_start.plan_grid`, on the domain of the route it takes);
    level k >= 2 is k times its cells per axis, solved by the same route: the Newton route where
    it is the default (:func:`dhfield.analysis.bem_start.takes_newton_route`), else the predicted
    route where level 1 takes it (mu >= 7.5, :func:`dhfield.analysis.bem_start.takes_predicted_route`),
    so that the levels differ by their cells alone.

    Parameters
    ----------
    beta0 : float
        Hertz ellipticity in (0, 1] [-].
    mu : float
        Tabor parameter, Eq. (35), > 0 [-].
    grid_level : int, default 1
        1 (the automatic grid) to :data:`dhfield.sweep.config.MAX_GRID_LEVEL` [-].
    law : str, default "dugdale"
        Cohesive law, one of :func:`cohesive_laws`.
    control : {"load", "displacement"}
        Loading mode (the route of level 1 depends on it).
    max_seconds : float, optional
        Estimated time allowed [s], > 0; default
        :data:`dhfield.analysis.bem_start.DEFAULT_MAX_SECONDS`.

    Returns
    -------
    dict
        ``nx``, ``ny`` (cells along x and y [-]), ``automatic`` (True for level 1: the
        solver plans it itself), ``predicted`` (every level on the predicted route),
        ``seconds`` and ``memory_bytes`` (the library's estimates for that grid [s],
        [bytes]), ``memory_limit`` (the memory one computation may claim, or None),
        ``max_seconds`` (the time allowed [s]: ``max_seconds``, or the library's default) and
        ``analytic_W_star`` (the analytic value to use where the case cannot be solved [-]).

    Raises
    ------
    ValueError
        If ``grid_level`` is not an integer in [1, MAX_GRID_LEVEL], or ``max_seconds`` is not
        a finite number > 0.
    """
    from ..analysis.bem_start import DEFAULT_MAX_SECONDS, plan_grid, pull_off_cost, takes_predicted_route

    if isinstance(grid_level, bool) or not isinstance(grid_level, (int, np.integer)) \
            or not 1 <= grid_level <= MAX_GRID_LEVEL:
        raise ValueError(f"grid_level must be an integer in [1, {MAX_GRID_LEVEL}] (1: the automatic grid); "
                         f"got {grid_level!r}")
    k = int(grid_level)
    predicted = takes_predicted_route(beta0=beta0, mu=mu, law=law, control=control)
    allowed = DEFAULT_MAX_SECONDS if max_seconds is None else max_seconds
    plan = plan_grid(beta0=beta0, mu=mu, law=law, predicted=predicted, max_seconds=allowed)
    nx, ny = k * int(plan.n_needed), k * int(plan.ny_needed)
    memory_bytes, seconds = pull_off_cost(nx, ny)
    return {"nx": nx, "ny": ny, "automatic": k == 1, "predicted": bool(plan.predicted),
            "seconds": seconds, "memory_bytes": memory_bytes, "memory_limit": plan.memory_limit,
            "max_seconds": float(plan.max_seconds), "analytic_W_star": float(plan.analytic_W_star)}


def _refuse_unaffordable(beta0, mu, grid_level, grid) -> None:
    """Raise before solving when an explicit refined grid exceeds the memory or time the library allows."""
    why = []
    if grid["memory_limit"] is not None and grid["memory_bytes"] > grid["memory_limit"]:
        why.append(f"~{grid['memory_bytes'] / 2**30:.3g} GiB, more than the {grid['memory_limit'] / 2**30:.3g} GiB "
                   "available")
    if grid["seconds"] > grid["max_seconds"]:
        why.append(f"~{grid['seconds'] / 60:.0f} min estimated, more than the {grid['max_seconds'] / 60:.0f} min "
                   "allowed ([bem] max_seconds, --max-seconds)")
    if why:
        raise RuntimeError(f"beta0={beta0:g}, mu={mu:g}, grid_level {grid_level}: {grid['nx']} x {grid['ny']} cells "
                           f"need {' and '.join(why)}; use the analytic W* = {grid['analytic_W_star']:.4f} "
                           "(md-elliptic) instead")


def _git_commit() -> str:
    """Commit of the code solving a case (with uncommitted changes under dhfield/ flagged)."""
    from ..io import git_commit

    return git_commit(paths=["dhfield"])


def adhesive_case(beta0: float, mu: float, n: int | None = None, law: str = "dugdale", control: str = "load", *,
                  grid_level: int | None = None, solver: str = "default", max_seconds: float | None = None) -> dict:
    """Compute the adhesive BEM ground truth at pull-off of one (beta0, mu, n or grid level, law) case.

    The whole load path runs in this one call (each step warm-starts from the
    last).

    Parameters
    ----------
    beta0 : float
        Hertz ellipticity [-].
    mu : float
        Tabor parameter, Eq. (35) [-].
    n : int, optional
        Cells per axis of an explicit n x n grid [-]; give ``n`` or ``grid_level``.
    law : str
        Cohesive law, one of :func:`cohesive_laws`.
    control : {"load", "displacement"}
        Loading mode of the pull-off.
    grid_level : int, optional
        1: the automatic grid and route (the solver plans them, as ``dhfield solve``
        without ``--n``); k >= 2: the explicit grid of :func:`automatic_grid` (k times the
        cells per axis), refused before solving (RuntimeError, one line with the analytic
        W* to use instead) when it exceeds the memory available or ``max_seconds``.
    solver : {"default"}
        The solver (:func:`adhesive_solver`).
    max_seconds : float, optional
        Estimated time allowed [s], > 0: the refusal of a level k >= 2 above, and, given,
        the solver's ``options=AdhesiveOptions(max_seconds=...)`` (level 1 and the automatic
        grid: its own refusal, :func:`dhfield.analysis.bem_start.plan_grid`).  Default (None):
        :data:`dhfield.analysis.bem_start.DEFAULT_MAX_SECONDS`, the solver called without options.
        An estimate checked before solving, not a wall-clock limit.

    Returns
    -------
    dict
        :data:`ADHESIVE_FIELDS`, :data:`ADHESIVE_BEM_FIELDS` and
        :data:`ADHESIVE_GRID_FIELDS` (NaN where the solver gives none; ``converged``
        and ``resolved`` as bools), :data:`ADHESIVE_TEXT_FIELDS` (str) and ``message``
        (str: why the answer is not one, the solver's note when it is not; empty for an answer).

    Raises
    ------
    ValueError
        If neither or both of ``n`` and ``grid_level`` are given, or ``max_seconds`` is not a
        finite number > 0.
    """
    import time

    if (n is None) == (grid_level is None):
        raise ValueError("give n (an explicit n x n grid) or grid_level (the automatic grid), not both or neither")
    kwargs = dict(beta0=float(beta0), mu=float(mu), law=law, control=control, threads=1)
    settings = {}         # the solver's options, only those given (None: the solver called without options)
    if max_seconds is not None:
        from ..core.validation import check_positive

        max_seconds = float(check_positive("max_seconds", max_seconds, "estimated time allowed per case, s"))
        settings["max_seconds"] = max_seconds
    if settings:
        from ..analysis.bem_start import AdhesiveOptions

        kwargs["options"] = AdhesiveOptions(**settings)
    if grid_level is None:
        kwargs["n"] = int(n)
        asked = (int(n), int(n))
    else:
        grid = automatic_grid(float(beta0), float(mu), grid_level, law=law, control=control, max_seconds=max_seconds)
        asked = (grid["nx"], grid["ny"])
        if not grid["automatic"]:
            _refuse_unaffordable(beta0, mu, grid_level, grid)
            kwargs.update(n=grid["nx"], ny=grid["ny"])
            from ..analysis.bem_start import PREDICTED_SEARCH, takes_newton_route

            if takes_newton_route(law=law, control=control, options=kwargs.get("options")):
                kwargs["search"] = "newton"      # level 1's route (the default), on k times its planned cells
            elif grid["predicted"]:        # the route and domain of level 1, refined
                kwargs["search"] = PREDICTED_SEARCH
    t0, c0 = time.perf_counter(), time.process_time()
    res = adhesive_solver(solver)(**kwargs)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0

    def get(*names):
        for nm in names:
            if getattr(res, nm, None) is not None:
                return float(getattr(res, nm))
        return float("nan")

    out = {"W_star": get("W_star"), "a_star": get("a_star"), "c_star": get("c_star"),
           "ellipticity": get("ellipticity", "beta_ab"), "delta_star": get("delta_star"),
           "iterations": get("iterations")}
    out.update(b_star=get("b_star"), d_star=get("d_star"), beta_ab=get("ellipticity", "beta_ab"),
               beta_cd=get("adhesive_ellipticity", "beta_cd"))
    nx, ny = _solved_grid(res, asked)
    out.update(nx=float(nx), ny=float(ny), half_width_x=get("half_width_x"), half_width_y=get("half_width_y"),
               W_star_error=get("W_star_error"), n_steps=get("n_steps"), wall_seconds=wall, cpu_seconds=cpu)
    out["converged"] = bool(getattr(res, "converged", True))
    out["resolved"] = bool(getattr(res, "resolved", True))
    note = str(getattr(res, "note", "") or "")
    message = str(getattr(res, "message", "") or "")
    if not (out["converged"] and out["resolved"]):   # the solver's reasons (its note) say why it is not an answer
        message = message or note
    if not out["converged"] and not message:
        failures = getattr(res, "failures", ()) or ()
        residual = getattr(res, "residual", float("nan"))
        message = f"{len(failures)} state(s) of the load path did not converge; largest residual {residual:.3g}"
    out["message"] = message
    out.update(search=str(getattr(res, "search", "") or ""), note=note, commit=_git_commit(),
               solver_options=str(getattr(res, "solver_options", "") or ""),
               finished=time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()))
    return out


def _solved_grid(res, asked) -> tuple:
    """(nx, ny) the solver used: its own fields, else its pull-off state's grid, else the grid asked for."""
    nx, ny = getattr(res, "nx", None), getattr(res, "ny", None)
    if nx is not None and ny is not None:
        return int(nx), int(ny)
    try:
        return tuple(int(v) for v in res.path.pull_off_state.grid.shape)
    except (AttributeError, TypeError, ValueError):
        return asked


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
    An adhesive case on a ``grid_level`` takes the library's estimate for its planned
    grid (:func:`automatic_grid`, which plans it: ~0.3 s).
    Forward BEM and adhesive cases scale with the FFT work n^2 log n; an
    adhesive pull-off also with its CG iterations, which grow like mu^1.1 with
    the Tabor parameter (a narrower cohesive zone on the same grid), and by
    ~20 % for beta0 < 1.  Constants: ``_SECONDS_*`` in this module, with their
    provenance.
    """
    if quantity == "bem_field":
        return _SECONDS_BEM_FIELD_256 * _grid_scale(params["n"])
    if quantity == "adhesive":
        if params.get("grid_level") is not None:   # the library's estimate of the planned grid
            return automatic_grid(float(params["beta0"]), float(params["mu"]), params["grid_level"],
                                  law=params.get("law", "dugdale"), control=params.get("control", "load"),
                                  max_seconds=params.get("max_seconds"))["seconds"]
        ellipse = 1.2 if float(params["beta0"]) < 1.0 else 1.0
        mu_work = float(params["mu"]) ** _ADHESIVE_MU_EXPONENT + _ADHESIVE_MU_OFFSET
        return _SECONDS_ADHESIVE_256 * _grid_scale(params["n"]) * mu_work * ellipse
    if quantity == "load_curve":
        return _SECONDS_CURVE_POINT * len(params["a_star"])
    raise ValueError(f"quantity must be 'bem_field', 'adhesive' or 'load_curve'; got {quantity!r}")
