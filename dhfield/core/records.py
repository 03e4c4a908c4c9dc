"""The one pull-off record and the one load-curve record of every model.

Every model answers with the same types, whose fields are named by :mod:`dhfield.core.schema`:

* :class:`PullOff`: the keys of :data:`dhfield.core.schema.PULL_OFF_KEYS`, in that order
  (the model, control and geometry; beta0, mu and sin(theta_skew); W*, the semi-axes,
  v, delta* and the ellipticities at pull-off; ``at_zero_contact`` and ``warning``),
  and, where they apply, three optional groups, each ``None`` (and not a key) elsewhere:

  - *SI*: the force, semi-axes and approach in SI units and the SI inputs, so that the
    record's keys are :data:`dhfield.core.schema.PULL_OFF_SI_KEYS` (built by
    :func:`pull_off_record_si`; the conversion, Eqs. 32-34 inverted, is
    :func:`dhfield.core.units.pull_off_si`): every model's SI ``pull_off`` and
    :func:`dhfield.analysis.dimensional.pull_off_force` return it;
  - *trust*: the estimated relative error of W* against the stored BEM ground truth and
    whether the point lies in the box of the stored cases (:mod:`dhfield.analysis.model_error`;
    :data:`dhfield.core.schema.PULL_OFF_TRUST_KEYS`): every pull-off of :mod:`dhfield.analysis.compare`,
    nondimensional or SI;
  - *spring*: the jump out under a machine spring of stiffness K*
    (:func:`dhfield.analysis.spring.pull_off_under_spring`, vectorised over K*, and the BEM's
    :func:`dhfield.analysis.bem_spring.bem_pull_off_under_spring`;
    :data:`dhfield.core.schema.PULL_OFF_SPRING_KEYS`);
  - *solver*: a numerical pull-off's stated error, convergence, route and cost (the
    adhesive BEM, :func:`dhfield.analysis.bem_start.adhesive_pull_off`;
    :data:`dhfield.core.schema.PULL_OFF_SOLVER_KEYS`);

* :class:`LoadCurve`: :data:`dhfield.core.schema.LOAD_CURVE_HEADER_KEYS` (scalars) then
  :data:`dhfield.core.schema.LOAD_CURVE_KEYS` (arrays over the contact size, the paper's units)
  or, for a curve from physical inputs, :data:`dhfield.core.schema.LOAD_CURVE_SI_KEYS` (SI),
  then ``ellipticity`` where the model records it (the paper's model): every model's
  ``load_curve``, nondimensional or SI, returns it (built by :func:`load_curve_record`).

Both are read as attributes (``p.W_star``) or as a mapping (``p["W_star"]``, ``dict(p)``,
``{**p}``), so a record goes straight into JSON, netCDF and tables.  NaN stands for a
quantity the model does not have (the adhesive zone of JKR, the DH factor ``v`` outside
the equal-beta DH models).  Units: the paper's nondimensional ones, Eqs. (32)-(35), and SI
in the SI group.
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, fields, replace

import numpy as np

from .schema import (LOAD_CURVE_ALL_KEYS, LOAD_CURVE_KEYS, LOAD_CURVE_SI_KEYS, PULL_OFF_ALL_KEYS,
                     PULL_OFF_SI_KEYS, PULL_OFF_TRUST_KEYS)

__all__ = ["PullOff", "LoadCurve", "broadcast_field", "pull_off_record", "pull_off_record_si", "load_curve_record"]

_NAN = float("nan")


class _Record(Mapping):
    """Attribute and read-only mapping access over the dataclass fields, in their order."""

    __slots__ = ()

    def __getitem__(self, key):
        if key in self._KEYS:
            return getattr(self, key)
        raise KeyError(key)

    def __iter__(self):
        return iter(self._KEYS)

    def __len__(self):
        return len(self._KEYS)

    def replace(self, **changes):
        """A copy with some fields changed."""
        return replace(self, **changes)

    def as_dict(self) -> dict:
        """The fields as a plain dict (arrays kept)."""
        return {k: getattr(self, k) for k in self._KEYS}


@dataclass(frozen=True, eq=False, kw_only=True)
class PullOff(_Record):
    """The pull-off point of a model: dhfield's one pull-off record (keys: :data:`dhfield.core.schema.PULL_OFF_ALL_KEYS`).

    Every model answers with this type: the analytic models in the paper's units, their SI
    ``pull_off`` functions with the SI group filled, :func:`dhfield.analysis.spring.pull_off_under_spring`
    with the spring group, the adhesive BEM (:func:`dhfield.analysis.bem_start.adhesive_pull_off`) with
    the solver group.  A group that does not apply is ``None`` and is not a key: iterating a record
    gives :data:`dhfield.core.schema.PULL_OFF_KEYS` for a nondimensional pull-off and
    :data:`dhfield.core.schema.PULL_OFF_SI_KEYS` for one from physical inputs, then the spring or
    solver keys where present.  Construct with keywords.

    Parameters
    ----------
    model : str
        A name of :data:`dhfield.analysis.compare.MODEL_NAMES`, or 'bem' for the adhesive BEM.
    control : str
        'load' or 'displacement' ('spring' under a machine spring:
        :func:`dhfield.analysis.spring.spring_pull_off_record` and
        :func:`dhfield.analysis.spring.pull_off_under_spring`).
    geometry : str
        'ellipse', or 'circle' for the circular models (R = sqrt(R'R''), sin_skew = 1).
    beta0, mu : ndarray or float
        Hertz ellipticity of the geometry and Tabor parameter (Eq. 35) [-].
    sin_skew : ndarray or float
        The sin(theta_skew) of the load normalisation, Eq. (34) [-].
    force : ndarray or float, optional
        SI group: pull-off load W [N] (negative: tensile).
    semi_major, semi_minor : ndarray or float, optional
        SI group: contact semi-axes a, b [m].
    adhesive_semi_major, adhesive_semi_minor : ndarray or float, optional
        SI group: adhesive-zone semi-axes c, d [m] (NaN: no zone).
    approach : ndarray or float, optional
        SI group: approach delta [m].
    work_of_adhesion : ndarray or float, optional
        SI group: Delta gamma [J m^-2].
    max_adhesive_stress : ndarray or float, optional
        SI group: the peak adhesive stress sigma0 [Pa] (NaN for the models without one: JKR,
        DMT, elliptical JKR).
    reduced_modulus : ndarray or float, optional
        SI group: E* [Pa].
    r_major, r_minor, effective_radius : ndarray or float, optional
        SI group: R', R'' and R = sqrt(R'R'') [m].
    W_star : ndarray or float
        Pull-off load W sin(theta_skew)/(2 pi R dgamma), Eq. (34) (negative: tensile) [-].
    a_star, b_star, c_star, d_star : ndarray or float
        Contact and adhesive-zone semi-axes in c_r, Eq. (33) [-] (NaN: no zone).  For the
        BEM the second-moment semi-axes of the contact and of contact U cohesive zone.
    v : ndarray or float
        Double-Hertz factor of Eq. (22) [-] (NaN outside the equal-beta DH models).
    delta_star : ndarray or float
        Approach in c_r^2/R [-].
    ellipticity, adhesive_ellipticity : ndarray or float
        Ellipticities b/a and d/c at pull-off [-].
    at_zero_contact : ndarray or bool
        True where the pull-off is reached as the contact vanishes.
    warning : ndarray or str
        Empty inside the model's validated range (:mod:`dhfield.analysis.validity`).
    model_error : ndarray or float, optional
        Trust group: estimated relative error of ``W_star`` against the BEM ground truth,
        a fraction (:func:`dhfield.analysis.model_error.model_error`); NaN where no stored BEM case
        checks the answer [-].
    bem_verified : ndarray or bool, optional
        Trust group: True inside the box of the stored BEM cases (load control).
    machine_stiffness_star : ndarray or float, optional
        Spring group: K* in the paper's units (:func:`dhfield.analysis.spring.stiffness_star`);
        inf: a rigid machine [-].
    separation_delta_star : ndarray or float, optional
        Spring group: approach after the jump, W = 0: the machine position delta* + W*/K* [-].
    max_tension_W_star : ndarray or float, optional
        Spring group: the smallest W* met from high load to the jump (the largest tensile
        force a recording shows) [-].
    on_separated_branch : ndarray or bool, optional
        Spring group: True where the jump starts out of contact (MD only,
        :mod:`dhfield.models.maugis_dugdale_separated`).
    W_star_error : float or ndarray, optional
        Solver group: stated error of ``W_star``; a resolved and converged answer lies within
        it of the grid-converged pull-off; infinite when there is no estimate [-].
    converged : bool, optional
        Solver group: every state of the path down to the pull-off converged.
    resolved : bool or ndarray, optional
        Solver group: False when the answer is not trustworthy, the reasons in ``note``.
    note : str, optional
        Solver group: caveats on the pull-off (empty for a resolved load-control pull-off).
    search : str, optional
        Solver group: the route that gave the pull-off ('located', 'predicted', 'bracket',
        'march', 'continuation', 'refine'; 'branch' under a spring,
        :func:`dhfield.analysis.bem_spring.bem_pull_off_under_spring`).
    n : int, optional
        Solver group: cells along x.
    law : str, optional
        Solver group: the cohesive law.
    n_steps, iterations : int, optional
        Solver group: solved states on the path and their Krylov iterations (GMRES of the
        Newton solve; conjugate gradient without adhesion).
    residual : float, optional
        Solver group: largest residual over the path.
    failures : tuple of dict, optional
        Solver group: unconverged states (approach, residual, iterations, phase).
    half_width_x, half_width_y : float, optional
        Solver group: domain half-widths [c_r].
    elapsed : float, optional
        Solver group: wall time of the path [s].
    solver_options : str, optional
        Solver group: the options the states of the answer's grid were solved with, as JSON (the
        fields of :class:`dhfield.bem.newton.SolverOptions`, and ``edge_margin`` on the Newton
        route; a route's coarser grids, which only start them, may take a looser tolerance).
    path : object, optional
        The BEM's whole path (:class:`dhfield.bem.path.UnloadingPath`); not a key.
    """

    model: str
    control: str
    geometry: str
    beta0: np.ndarray
    mu: np.ndarray
    sin_skew: np.ndarray
    force: np.ndarray = None
    semi_major: np.ndarray = None
    semi_minor: np.ndarray = None
    adhesive_semi_major: np.ndarray = None
    adhesive_semi_minor: np.ndarray = None
    approach: np.ndarray = None
    work_of_adhesion: np.ndarray = None
    max_adhesive_stress: np.ndarray = None
    reduced_modulus: np.ndarray = None
    r_major: np.ndarray = None
    r_minor: np.ndarray = None
    effective_radius: np.ndarray = None
    W_star: np.ndarray
    a_star: np.ndarray
    b_star: np.ndarray
    c_star: np.ndarray
    d_star: np.ndarray
    v: np.ndarray
    delta_star: np.ndarray
    ellipticity: np.ndarray
    adhesive_ellipticity: np.ndarray
    at_zero_contact: np.ndarray
    warning: np.ndarray
    model_error: np.ndarray = None
    bem_verified: np.ndarray = None
    machine_stiffness_star: np.ndarray = None
    separation_delta_star: np.ndarray = None
    max_tension_W_star: np.ndarray = None
    on_separated_branch: np.ndarray = None
    W_star_error: float = None
    converged: bool = None
    resolved: bool = None
    note: str = None
    search: str = None
    n: int = None
    law: str = None
    n_steps: int = None
    iterations: int = None
    residual: float = None
    failures: tuple = None
    half_width_x: float = None
    half_width_y: float = None
    elapsed: float = None
    solver_options: str = None
    path: object = field(default=None, repr=False)

    @property
    def _KEYS(self):
        return tuple(k for k in PULL_OFF_ALL_KEYS if getattr(self, k) is not None)

    @property
    def groups(self) -> tuple:
        """The optional groups this record holds: any of 'si', 'trust', 'spring', 'solver'."""
        return tuple(g for g, k in (("si", "force"), ("trust", "model_error"), ("spring", "machine_stiffness_star"),
                                    ("solver", "converged"))
                     if getattr(self, k) is not None)

    @property
    def worst_residual(self) -> float:
        """Solver group: the largest residual of the unconverged states, else ``residual`` [-] (None without it)."""
        if self.failures:
            return max(f.get("residual", float("nan")) for f in self.failures)
        return self.residual


#: The two array groups of a load curve, less ``v`` (in both).
_CURVE_ND = tuple(k for k in LOAD_CURVE_KEYS if k != "v")
_CURVE_SI = tuple(k for k in LOAD_CURVE_SI_KEYS if k != "v")


@dataclass(frozen=True, eq=False, kw_only=True)
class LoadCurve(_Record):
    """A load curve of a model: the one load-curve record of dhfield (keys: :data:`dhfield.core.schema.LOAD_CURVE_ALL_KEYS`).

    Every model's load curve is this type: the registry's (:func:`dhfield.analysis.compare.load_curve`,
    :func:`dhfield.analysis.compare.load_curve_at_load`) and the paper's model's
    (:func:`dhfield.models.dh_elliptic.load_curve`) in the paper's units; the SI ``load_curve`` of every
    comparison model (JKR, DMT, MD, DH circular, the elliptical JKR models) and
    :func:`dhfield.analysis.dimensional.load_curve_si` with the SI group.  A curve holds one of two
    array groups, the other ``None`` and not a key: iterating a nondimensional curve gives
    :data:`dhfield.core.schema.LOAD_CURVE_HEADER_KEYS` + :data:`dhfield.core.schema.LOAD_CURVE_KEYS`,
    an SI one :data:`dhfield.core.schema.LOAD_CURVE_HEADER_KEYS` +
    :data:`dhfield.core.schema.LOAD_CURVE_SI_KEYS` (``v``, dimensionless, is in both), then
    ``ellipticity`` where the model records it.  Construct with keywords.

    Parameters
    ----------
    model, geometry : str
        As in :class:`PullOff`.
    beta0, mu, sin_skew : float or ndarray
        As in :class:`PullOff` (NaN ``mu`` for the models without one: JKR, DMT, the
        elliptical JKR models).  Floats, except for an SI curve of array-valued material
        inputs [-].
    a_star, b_star, c_star, d_star : ndarray, optional
        Nondimensional group: contact and adhesive-zone semi-axes in c_r, Eq. (33) [-]
        (NaN: no zone).
    semi_major, semi_minor : ndarray, optional
        SI group: contact semi-axes a, b [m] (both the contact radius for a circle).
    adhesive_semi_major, adhesive_semi_minor : ndarray, optional
        SI group: adhesive-zone semi-axes c, d [m] (NaN: no zone).
    v : ndarray
        Double-Hertz factor of Eq. (22) [-] (NaN outside the DH models that report it);
        in both groups.
    W_star : ndarray, optional
        Nondimensional group: load W sin(theta_skew)/(2 pi R dgamma), Eq. (34) [-].
    delta_star : ndarray, optional
        Nondimensional group: approach delta/(c_r^2/R) [-].
    force : ndarray, optional
        SI group: load W [N] (positive compressive).
    approach : ndarray, optional
        SI group: approach delta [m].
    ellipticity : float or ndarray, optional
        The contact's ellipticity b/a where the model sets it: the ellipticity of both
        ellipses of the paper's model (:func:`dhfield.models.dh_elliptic.load_curve`: beta0, or its free
        ``ellipticity``; a float), b/a along the curve of the SI elliptical JKR curves (an
        array); ``None`` elsewhere (b*/a* or semi_minor/semi_major gives it) [-].
    """

    model: str
    geometry: str
    beta0: float
    mu: float
    sin_skew: float
    a_star: np.ndarray = None
    b_star: np.ndarray = None
    c_star: np.ndarray = None
    d_star: np.ndarray = None
    semi_major: np.ndarray = None
    semi_minor: np.ndarray = None
    adhesive_semi_major: np.ndarray = None
    adhesive_semi_minor: np.ndarray = None
    v: np.ndarray
    W_star: np.ndarray = None
    delta_star: np.ndarray = None
    force: np.ndarray = None
    approach: np.ndarray = None
    ellipticity: float = None

    def __post_init__(self):
        nd, si = ([getattr(self, k) is not None for k in group] for group in (_CURVE_ND, _CURVE_SI))
        if not ((all(nd) and not any(si)) or (all(si) and not any(nd))):
            raise ValueError(f"a load curve holds either every key of {LOAD_CURVE_KEYS} (the paper's units) or "
                             f"every key of {LOAD_CURVE_SI_KEYS} (SI), not a mixture")

    @property
    def _KEYS(self):
        return tuple(k for k in LOAD_CURVE_ALL_KEYS if getattr(self, k) is not None)

    @property
    def nondimensional(self) -> bool:
        """True for a curve in the paper's units, False for an SI one."""
        return self.force is None


assert tuple(f.name for f in fields(PullOff)) == PULL_OFF_ALL_KEYS + ("path",)
assert tuple(f.name for f in fields(LoadCurve)) == LOAD_CURVE_ALL_KEYS


def broadcast_field(x, shape, dtype=float):
    """Broadcast a record field to the record's shape, as an owned array (a scalar for shape ``()``).

    Parameters
    ----------
    x : array_like
        The value.
    shape : tuple of int
        The record's shape.
    dtype : data-type, default float
        The field's type (``bool`` for flags, ``object`` for text).

    Returns
    -------
    ndarray or scalar
        A copy of ``x`` broadcast to ``shape``; a numpy scalar where ``shape`` is ``()``.
    """
    out = np.broadcast_to(np.asarray(x, dtype=dtype), shape).copy()
    return out[()] if out.ndim == 0 else out


def _ratio(num, den):
    return np.divide(num, den, out=np.ones_like(num), where=den > 0)


def pull_off_record(model, beta0, mu, state, *, control, sin_skew, geometry, warning=""):
    """Build the :class:`PullOff` of a model from its state at pull-off.

    Parameters
    ----------
    model : str
        The model's name.
    beta0, mu : array_like
        The inputs [-]; the record has their broadcast shape.
    state : mapping
        ``W_star``, ``a_star``, ``delta_star`` and, where the model has them, ``b_star``
        (default a*: a circle), ``c_star`` (default NaN), ``d_star`` (default c* b*/a*),
        ``v`` (default NaN), ``ellipticity`` (default b*/a*, 1 at a* = 0) and
        ``at_zero_contact`` (default a* = 0).
    control : {'load', 'displacement'}
        Loading mode of the pull-off.
    sin_skew : array_like
        The sin(theta_skew) of Eq. (34) (1 for the circle) [-].
    geometry : {'ellipse', 'circle'}
        The contact's shape.
    warning : str or array of str
        The model's own warning ("" for none).

    Returns
    -------
    PullOff
        Scalars where every input is a scalar.
    """
    beta0, mu = np.asarray(beta0, float), np.asarray(mu, float)
    shape = np.broadcast_shapes(beta0.shape, mu.shape)
    a = np.asarray(state["a_star"], float)
    b = np.asarray(state.get("b_star", a), float)
    c = np.asarray(state.get("c_star", _NAN), float)
    d = np.asarray(state.get("d_star", c * _ratio(b, a)), float)
    with np.errstate(invalid="ignore", divide="ignore"):
        ell = np.asarray(state.get("ellipticity", _ratio(b, a)), float)
        adh = np.where(np.isfinite(c) & (c > 0), d / np.where(c > 0, c, 1.0), _NAN)
    zero = state.get("at_zero_contact", a == 0)
    def full(x, dtype=float):
        return broadcast_field(x, shape, dtype)

    return PullOff(model=model, control=control, geometry=geometry, beta0=full(beta0), mu=full(mu),
                   sin_skew=full(sin_skew), W_star=full(state["W_star"]), a_star=full(a), b_star=full(b),
                   c_star=full(c), d_star=full(d), v=full(state.get("v", _NAN)), delta_star=full(state["delta_star"]),
                   ellipticity=full(ell), adhesive_ellipticity=full(adh), at_zero_contact=full(zero, bool),
                   warning=full(warning, object))


def pull_off_record_si(rec, si):
    """Build the SI :class:`PullOff` (its SI group filled) of a pull-off record and its SI values.

    Parameters
    ----------
    rec : PullOff or mapping
        The nondimensional record (the keys of :data:`dhfield.core.schema.PULL_OFF_KEYS`).
    si : mapping
        The keys of :data:`dhfield.core.schema.PULL_OFF_SI_KEYS` that the nondimensional
        record has not (force, semi-axes, approach in SI units, the SI inputs),
        broadcast to the record's shape.

    Returns
    -------
    PullOff
        With the SI group (keys :data:`dhfield.core.schema.PULL_OFF_SI_KEYS`), and the trust group
        where ``rec`` has it; scalars where the record is scalar.
    """
    shape = np.shape(rec["W_star"])
    si = {k: _scalar(np.broadcast_to(np.asarray(v, dtype=float), shape)) for k, v in si.items()}
    trust = {k: rec[k] for k in PULL_OFF_TRUST_KEYS if k in rec}
    return PullOff(**{k: (si[k] if k in si else rec[k]) for k in PULL_OFF_SI_KEYS}, **trust)


def _scalar(x):
    return x[()] if x.ndim == 0 else x


def load_curve_record(model, beta0, mu, arrays, *, sin_skew, geometry, ellipticity=None):
    """Build the :class:`LoadCurve` of a model from its arrays over the contact size.

    Parameters
    ----------
    model : str
        The model's name.
    beta0, mu : float or ndarray
        The inputs [-] (arrays only for an SI curve of array-valued material inputs).
    arrays : mapping
        Nondimensional: ``a_star``, ``W_star``, ``delta_star`` and, where the model has them,
        ``b_star`` (default a*), ``c_star``, ``d_star``, ``v`` (default NaN).  SI (recognised by
        ``force``): ``semi_major``, ``force``, ``approach`` and, where the model has them,
        ``semi_minor`` (default the semi-major axis), ``adhesive_semi_major``,
        ``adhesive_semi_minor``, ``v`` (default NaN).
    sin_skew : float or ndarray
        The sin(theta_skew) of Eq. (34) (1 for the circle) [-].
    geometry : {'ellipse', 'circle'}
        The contact's shape.
    ellipticity : float or array_like, optional
        The contact's b/a where the model sets it (:class:`LoadCurve`) [-].

    Returns
    -------
    LoadCurve
        The curve, nondimensional or SI; arrays of the contact sizes' shape (numpy scalars
        for a scalar contact size).
    """
    keys = LOAD_CURVE_SI_KEYS if "force" in arrays else LOAD_CURVE_KEYS
    major, minor, zone_major, zone_minor = keys[:4]
    a = np.asarray(arrays[major], float)
    nan = np.full(a.shape, _NAN)
    get = {major: a, minor: arrays.get(minor, a), zone_major: arrays.get(zone_major, nan),
           zone_minor: arrays.get(zone_minor, nan), "v": arrays.get("v", nan), keys[5]: arrays[keys[5]],
           keys[6]: arrays[keys[6]]}
    return LoadCurve(model=model, geometry=geometry, beta0=_header(beta0), mu=_header(mu), sin_skew=_header(sin_skew),
                     **{k: _scalar(np.asarray(get[k], float)) for k in keys},
                     ellipticity=None if ellipticity is None else _header(ellipticity))


def _header(x):
    return float(x) if np.ndim(x) == 0 else np.asarray(x, dtype=float)
