"""One table of variable metadata for every dhfield record, Dataset and file.

Pure Python (no numpy, no xarray): the writers in :mod:`dhfield.io`, the JSON
records of the command line and the sweeps all take their names, units and
descriptions from here, so that a quantity is called the same thing, in the
same unit, wherever it appears.

Conventions
-----------
* ``units`` are CF/UDUNITS strings; ``"1"`` is dimensionless.
* Loads and forces are positive compressive: a pull-off force is negative.
* Nondimensional quantities use the paper's units (Eqs. 32-35): lengths in
  c_r = (R^2 dgamma/E*)^(1/3), approach in c_r^2/R, stresses in E* c_r/R, load
  as W* = W sin(theta_skew)/(2 pi R dgamma), with R = sqrt(R'R'').
* A quantity that exists both in SI and in the paper's units has one entry with
  its SI unit and a ``scale``; :func:`attrs` with ``nondimensional=True`` gives
  units ``"1"`` and names the scale in ``long_name``.
* Every Dataset orders its dimensions by :data:`DIM_ORDER`; grids of the two
  model parameters are always ``GRID_DIMS = ("beta0", "mu")``.

Records
-------
:data:`PULL_OFF_KEYS` (nondimensional) and :data:`PULL_OFF_SI_KEYS` (physical
inputs) are the keys, in order, of a pull-off record of every model: a value
that does not apply to a model is NaN (JSON ``null``), never missing.  The one
record type, :class:`dhfield.core.records.PullOff`, adds the groups
:data:`PULL_OFF_TRUST_KEYS` (the estimated error against the BEM ground truth: every
pull-off of :mod:`dhfield.analysis.compare`), :data:`PULL_OFF_SPRING_KEYS` (under a machine spring) and
:data:`PULL_OFF_SOLVER_KEYS` (a numerical solution, the adhesive BEM) where they
apply; :data:`PULL_OFF_ALL_KEYS` lists every key in order.
:data:`LOAD_CURVE_KEYS` and :data:`LOAD_CURVE_SI_KEYS` are the array keys of a
load curve, after the scalar header :data:`LOAD_CURVE_HEADER_KEYS`: the one
load-curve type, :class:`dhfield.core.records.LoadCurve`, holds one of the two array
groups (the paper's units or SI) and, where the model records it, the optional
key :data:`LOAD_CURVE_OPTIONAL_KEYS` after them; :data:`LOAD_CURVE_ALL_KEYS`
lists every key in order.
"""
from __future__ import annotations

from dataclasses import dataclass

__all__ = [
    "Variable",
    "VARIABLES",
    "GRID_DIMS",
    "DIM_ORDER",
    "PULL_OFF_KEYS",
    "PULL_OFF_SI_KEYS",
    "PULL_OFF_TRUST_KEYS",
    "PULL_OFF_SPRING_KEYS",
    "PULL_OFF_SOLVER_KEYS",
    "PULL_OFF_ALL_KEYS",
    "LOAD_CURVE_HEADER_KEYS",
    "LOAD_CURVE_KEYS",
    "LOAD_CURVE_SI_KEYS",
    "LOAD_CURVE_OPTIONAL_KEYS",
    "LOAD_CURVE_ALL_KEYS",
    "BEM_ADHESIVE_KEYS",
    "attrs",
    "units",
    "units_of",
    "order_dims",
]


@dataclass(frozen=True)
class Variable:
    """Metadata of one named quantity.

    Parameters
    ----------
    units : str
        CF/UDUNITS unit of the quantity in SI ("1": dimensionless).
    long_name : str
        Short human-readable name (CF ``long_name``).
    standard_name : str or None
        CF standard name, where CF defines one.
    description : str
        Definition, sign convention and equation of the paper.
    scale : str or None
        The paper's unit of the quantity when it is given nondimensionally
        (e.g. "c_r"); None when the quantity is dimensionless anyway.
    """

    units: str
    long_name: str
    standard_name: str | None = None
    description: str = ""
    scale: str | None = None


_CR = "c_r = (R^2 dgamma/E*)^(1/3)"
_APPROACH = "c_r^2/R"
_STRESS = "E* c_r/R"
_DGAMMA = "dgamma"

#: name -> :class:`Variable`.  One entry per quantity, whatever writes it.
VARIABLES: dict[str, Variable] = {
    # ----------------------------------------------------------------- identifiers and flags
    "model": Variable("1", "model name", description="one of dhfield.analysis.compare.MODEL_NAMES"),
    "control": Variable("1", "loading mode", description="'load' (dead load) or 'displacement' (fixed grips)"),
    "geometry": Variable("1", "contact geometry of the model",
                         description="'ellipse' or 'circle' (the circular models use R = sqrt(R'R''), "
                                     "sin(theta_skew) = 1)"),
    "warning": Variable("1", "model-choice warning",
                        description="empty, or why the result should not be trusted (e.g. the paper's "
                                    "closure departs from the two-axis closure by more than 2 %)"),
    "at_zero_contact": Variable("1", "pull-off at vanishing contact",
                                description="True where the pull-off minimum is reached as a* -> 0"),
    "model_error": Variable("1", "estimated relative error of the pull-off W* against the BEM ground truth",
                            description="largest (|W*_model - W*_truth| + W*_truth error)/|W*_truth| over the "
                                        "stored BEM cases bracketing the point (dhfield.analysis.model_error); NaN "
                                        "where no stored case checks the answer"),
    "bem_verified": Variable("1", "inside the box of the stored BEM ground truth",
                             description="beta0 and mu within the stored BEM cases, load control "
                                         "(dhfield.analysis.model_error)"),
    "converged": Variable("1", "solver converged"),
    "n_steps": Variable("1", "number of load or displacement steps"),
    "iterations": Variable("1", "solver iterations"),
    # ----------------------------------------------------------------- model parameters (grid dims)
    "beta0": Variable("1", "initial (Hertz) ellipticity b/a (Eq. 9)",
                      description="Hertz ellipticity of the geometry, in (0, 1] (Eq. 9)"),
    "mu": Variable("1", "Tabor parameter (Eq. 35)", description="mu = sigma0 (R/(E*^2 dgamma))^(1/3) (Eq. 35)"),
    "sin_skew": Variable("1", "sine of the skew angle",
                         description="sin(theta_skew) of the load normalisation of Eq. (34); 1 for the "
                                     "circular models"),
    "skew_angle": Variable("rad", "skew angle of the crossed cylinders",
                           description="crossing angle theta_skew in (0, pi/2]"),
    "skew_angle_deg": Variable("degree", "skew angle of the crossed cylinders",
                               description="crossing angle theta_skew in (0, 90]"),
    "ellipticity": Variable("1", "contact ellipticity b/a", description="at the state reported (Eq. 19)"),
    "adhesive_ellipticity": Variable("1", "adhesive-zone ellipticity d/c",
                                     description="equal to the contact ellipticity in the paper's closure "
                                                 "(Eq. 19); NaN where the model has no adhesive zone"),
    "beta_ab": Variable("1", "contact ellipticity b/a", description="BEM: of the contact ellipse fitted"),
    "beta_cd": Variable("1", "adhesive-zone ellipticity d/c", description="BEM: of the adhesive ellipse fitted"),
    # ----------------------------------------------------------------- nondimensional state (Eqs. 32-36)
    "W_star": Variable("1", "normalised load W sin(theta_skew)/(2 pi R dgamma) (Eq. 34)",
                       description="Eq. (34); positive compressive, negative at pull-off"),
    "a_star": Variable("1", "contact semi-major axis a/c_r (Eq. 32)", description="Eq. (32); radius for a circle"),
    "b_star": Variable("1", "contact semi-minor axis b/c_r (Eq. 32)", description="Eq. (32)"),
    "c_star": Variable("1", "adhesive semi-major axis c/c_r (Eq. 32)",
                       description="outer edge of the adhesive zone (Eq. 32); NaN where the model has none"),
    "d_star": Variable("1", "adhesive semi-minor axis d/c_r (Eq. 32)",
                       description="Eq. (32); NaN where the model has none"),
    "v": Variable("1", "double-Hertz scaling factor v (Eq. 22)", description="Eq. (22); NaN for non-DH models"),
    "delta_star": Variable("1", "normalised approach delta R/c_r^2", description="Eq. (33)"),
    # ----------------------------------------------------------------- SI outputs
    "force": Variable("N", "normal force W (Eq. 34)", description="W (Eq. 34), positive compressive; the pull-off "
                                                       "force is negative (tensile)"),
    "semi_major": Variable("m", "contact semi-major axis a", scale=_CR),
    "semi_minor": Variable("m", "contact semi-minor axis b", scale=_CR),
    "adhesive_semi_major": Variable("m", "adhesive-zone semi-major axis c", scale=_CR,
                                    description="NaN where the model has no adhesive zone"),
    "adhesive_semi_minor": Variable("m", "adhesive-zone semi-minor axis d", scale=_CR,
                                    description="NaN where the model has no adhesive zone"),
    "approach": Variable("m", "approach delta", scale=_APPROACH,
                         description="mutual approach of distant points, positive compressive"),
    "machine_displacement": Variable("m", "machine displacement Delta = delta + W/K", scale=_APPROACH,
                                     description="position of the far end of a machine spring of stiffness K "
                                     "(dhfield.analysis.spring); the jump out is its first minimum on unloading"),
    "machine_stiffness": Variable("N m-1", "machine stiffness K", scale="(2 pi R dgamma/sin(theta_skew))/(c_r^2/R)",
                                  description="stiffness of the machine spring in series with the contact "
                                              "(dhfield.analysis.spring.stiffness_star); the jump out is where "
                                              "dW/d(delta) = -K; 0 is load control, inf a rigid machine"),
    "separation_approach": Variable("m", "approach after the jump out, W = 0", scale=_APPROACH,
                                    description="the machine displacement at the jump out: the force-free "
                                                "state the contact jumps to (dhfield.analysis.spring)"),
    # ----------------------------------------------------------------- SI inputs and derived scales
    "work_of_adhesion": Variable("J m-2", "work of adhesion dgamma", scale=_DGAMMA,
                                 description="Dupre work of adhesion; per ray, the integral of sigma dh "
                                             "(Eq. 31)"),
    "max_adhesive_stress": Variable("Pa", "maximum adhesive stress sigma0", scale=_STRESS,
                                    description="Dugdale/double-Hertz stress at the contact edge (Eqs. 24, 35)"),
    "adhesive_stress": Variable("Pa", "tensile adhesive stress", scale=_STRESS,
                                description="positive tensile (Eq. 23)"),
    "youngs_modulus": Variable("Pa", "Young's modulus E1 of the first body"),
    "youngs_modulus_2": Variable("Pa", "Young's modulus E2 of the second body"),
    "poisson_ratio": Variable("1", "Poisson's ratio nu1 of the first body"),
    "poisson_ratio_2": Variable("1", "Poisson's ratio nu2 of the second body"),
    "reduced_modulus": Variable("Pa", "reduced modulus E* (Eq. 6)", description="1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2 (Eq. 6)"),
    "cylinder_radius": Variable("m", "cylinder radius", description="of both cylinders"),
    "r_major": Variable("m", "principal relative radius R'", description="larger principal radius (Eqs. 3-4)"),
    "r_minor": Variable("m", "principal relative radius R''", description="smaller principal radius (Eqs. 3-4)"),
    "effective_radius": Variable("m", "effective radius R = sqrt(R'R'') (Eq. 5)", description="Eq. (5)"),
    # ----------------------------------------------------------------- periphery (ray) quantities
    "contact_radius": Variable("m", "contact-ellipse radius r_ab on the ray", scale=_CR, description="Eq. (A1)"),
    "adhesive_radius": Variable("m", "adhesive-ellipse radius r_cd on the ray", scale=_CR, description="Eq. (A2)"),
    "zone_width": Variable("m", "adhesive-zone width r_cd - r_ab on the ray", scale=_CR),
    "edge_separation": Variable("m", "gap at the adhesive edge h(r_cd)", scale=_APPROACH, description="Eq. (27)"),
    "contact_edge_gap": Variable("m", "gap at the contact edge h(r_ab)", scale=_APPROACH),
    "work_ratio": Variable("1", "dgamma(pi/2)/dgamma(0) at pull-off", description="paper's model (Eq. 31 on both axes)"),
    "mean_work": Variable("1", "ray-averaged work of adhesion, in dgamma"),
    "work_major": Variable("1", "dgamma(0), in dgamma", description="Eq. (31)"),
    "work_minor": Variable("1", "dgamma(pi/2), in dgamma", description="Eq. (31) on the minor axis"),
    # ----------------------------------------------------------------- field (BEM) quantities
    "pressure": Variable("Pa", "contact pressure", scale=_STRESS, description="compressive positive (Eqs. 7/22)"),
    "displacement": Variable("m", "combined surface displacement", scale=_APPROACH,
                             description="into the bodies (Eqs. 13/26)"),
    "gap": Variable("m", "gap h = z - delta + omega", scale=_APPROACH, description="Eq. (27)"),
    # ----------------------------------------------------------------- coordinates
    "point": Variable("1", "curve point index"),
    "theta": Variable("rad", "polar angle theta_p of the ray", description="0 on the major axis (Eqs. A3-A4)"),
    "theta_p": Variable("rad", "polar angle theta_p from the major axis", description="Eq. (A3)"),
    "r": Variable("m", "radial coordinate r", scale=_CR, description="Eq. (A3)"),
    "x": Variable("m", "x, along the major axis a", scale=_CR),
    "y": Variable("m", "y, along the minor axis b", scale=_CR),
    "closure": Variable("1", "closure of the elliptical DH model",
                        description="paper = Eqs. 17-19, 31; ray_average = mean dgamma = 1; two_axis = "
                                    "dgamma = 1 on both axes"),
    # ----------------------------------------------------------------- diagnostics of the writers (H7)
    "region": Variable("1", "region of the surface", description="contact ellipse, adhesive annulus or outside"),
    "annulus_identity_error": Variable("1", "annulus-identity error on the ray",
                                       description="max over the annulus of |h_BEM - (1+v) h_Hertz| / "
                                                   "max (1+v) h_Hertz"),
    "law_theta": Variable("rad", "ray angle theta_p of the sigma-h curves"),
    "sample": Variable("1", "sample index along the ray, contact edge to adhesive edge"),
    "work_spread": Variable("1", "(max - min)/mean of dgamma(theta_p) at pull-off"),
    "law_spread": Variable("1", "max over theta_p of int |sigma_theta(h) - sigma_0(h)| dh / dgamma(0)"),
    "law_sup_spread": Variable("1", "max over theta_p and h of |sigma_theta(h) - sigma_0(h)| / sigma0"),
    "separation_ratio": Variable("1", "edge separation h(r_cd), minor axis / major axis"),
    "width_ratio": Variable("1", "adhesive-zone width, minor axis / major axis"),
    "eq30": Variable("1", "Eq. (30) at pull-off, in dgamma",
                     description="equals 4 [dgamma(0) - dgamma(pi/2)], not dgamma"),
    # ----------------------------------------------------------------- adhesion map (dhfield.analysis.adhesion_map)
    "force_pi_r_dgamma": Variable("1", "pull-off force W/(pi R dgamma), R = sqrt(R'R'')",
                                  description="2 W*/sin(theta_skew) (Eq. 34); load control, negative tensile: "
                                              "-2 is DMT, -1.5 the JKR sphere"),
    "relative_deviation": Variable("1", "relative deviation of the pull-off force from the reference model",
                                   description="W_model/W_reference - 1; positive: more adhesion than the "
                                               "reference; NaN where the model gave no answer"),
    "model_status": Variable("1", "status of the model's answer",
                             description="answered; answered with a warning (outside the model's validated "
                                         "range); refused (the model raised: no answer); not finite"),
    "validated_region": Variable("1", "inside the extent of the BEM ground truth",
                                 description="where the reference model is validated against the BEM"),
}

#: The two model parameters, in the one order every grid Dataset uses.
GRID_DIMS = ("beta0", "mu")

#: Canonical order of every dimension a dhfield Dataset may carry.  Surface fields are (y, x):
#: rows are y, columns x, so ``ds.gap.plot()`` puts x on the horizontal axis.
DIM_ORDER = ("model", "closure", "skew_angle_deg", "skew_angle", "beta0", "mu", "a_star", "point",
             "theta", "law_theta", "sample", "r", "theta_p", "y", "x")

_HEAD = ("model", "control", "geometry", "beta0", "mu", "sin_skew")
_NONDIM = ("W_star", "a_star", "b_star", "c_star", "d_star", "v", "delta_star", "ellipticity",
           "adhesive_ellipticity")
_SI_OUT = ("force", "semi_major", "semi_minor", "adhesive_semi_major", "adhesive_semi_minor", "approach")
_SI_IN = ("work_of_adhesion", "max_adhesive_stress", "reduced_modulus", "r_major", "r_minor",
          "effective_radius")
_TAIL = ("at_zero_contact", "warning")

#: Keys, in order, of a nondimensional pull-off record (every model).
PULL_OFF_KEYS = _HEAD + _NONDIM + _TAIL
#: Keys, in order, of a pull-off record from physical inputs (every model).
PULL_OFF_SI_KEYS = _HEAD + _SI_OUT + _SI_IN + _NONDIM + _TAIL
#: Keys of a pull-off's trust (:mod:`dhfield.analysis.model_error`): its estimated relative error against the BEM ground
#: truth and whether the point lies in the box of the stored BEM cases; every pull-off of :mod:`dhfield.analysis.compare`.
PULL_OFF_TRUST_KEYS = ("model_error", "bem_verified")
#: Keys of a pull-off under a machine spring (:func:`dhfield.analysis.spring.pull_off_under_spring`), after the SI and
#: nondimensional ones.
PULL_OFF_SPRING_KEYS = ("machine_stiffness_star", "separation_delta_star", "max_tension_W_star", "on_separated_branch")
#: Keys of a numerical pull-off (the adhesive BEM, :func:`dhfield.analysis.bem_start.adhesive_pull_off`): its stated
#: error, convergence, route and cost.
PULL_OFF_SOLVER_KEYS = ("W_star_error", "converged", "resolved", "note", "search", "n", "law", "n_steps",
                        "iterations", "residual", "failures", "half_width_x", "half_width_y", "elapsed",
                        "solver_options")
#: Every key a :class:`dhfield.core.records.PullOff` may carry, in order; a record holds the groups it has
#: (:data:`PULL_OFF_KEYS` always; the SI, trust, spring and solver groups where they apply).
PULL_OFF_ALL_KEYS = (_HEAD + _SI_OUT + _SI_IN + _NONDIM + _TAIL + PULL_OFF_TRUST_KEYS + PULL_OFF_SPRING_KEYS
                     + PULL_OFF_SOLVER_KEYS)
#: Scalar keys that head a load-curve record.
LOAD_CURVE_HEADER_KEYS = ("model", "geometry", "beta0", "mu", "sin_skew")
#: Array keys of a nondimensional load curve, in order.
LOAD_CURVE_KEYS = ("a_star", "b_star", "c_star", "d_star", "v", "W_star", "delta_star")
#: Array keys of a load curve from physical inputs, in order.
LOAD_CURVE_SI_KEYS = ("semi_major", "semi_minor", "adhesive_semi_major", "adhesive_semi_minor", "v", "force",
                      "approach")
#: Optional key of a load curve, after its arrays: ``ellipticity``, the contact's b/a where the model sets it
#: (the paper's model: the ellipticity of both ellipses; the SI elliptical JKR curves: b/a along the curve).
LOAD_CURVE_OPTIONAL_KEYS = ("ellipticity",)
#: Every key a :class:`dhfield.core.records.LoadCurve` may carry, in order.  ``v`` belongs to both array groups,
#: so a nondimensional curve iterates ``LOAD_CURVE_HEADER_KEYS + LOAD_CURVE_KEYS`` and an SI one
#: ``LOAD_CURVE_HEADER_KEYS + LOAD_CURVE_SI_KEYS`` (then the optional key where present).
LOAD_CURVE_ALL_KEYS = (LOAD_CURVE_HEADER_KEYS + LOAD_CURVE_KEYS[:4] + LOAD_CURVE_SI_KEYS[:4] + ("v",)
                       + LOAD_CURVE_KEYS[5:] + LOAD_CURVE_SI_KEYS[5:] + LOAD_CURVE_OPTIONAL_KEYS)
#: Outputs of the adhesive BEM solve at one state.
BEM_ADHESIVE_KEYS = ("a_star", "b_star", "c_star", "d_star", "beta_ab", "beta_cd", "W_star", "delta_star",
                     "converged", "n_steps", "iterations")


def _get(name: str) -> Variable:
    try:
        return VARIABLES[name]
    except KeyError:
        raise ValueError(f"name must be one of the variables of dhfield.core.schema.VARIABLES; got {name!r}") from None


def attrs(name: str, nondimensional: bool = False) -> dict:
    """Build the xarray-ready attributes of a named quantity.

    Parameters
    ----------
    name : str
        A key of :data:`VARIABLES`.
    nondimensional : bool
        True for the quantity in the paper's units: ``units`` becomes "1" and
        the scale is named in ``long_name`` (no effect on dimensionless names).

    Returns
    -------
    dict
        ``long_name``, ``units``, and ``standard_name``/``description`` where set.
    """
    var = _get(name)
    out = {"long_name": var.long_name, "units": var.units}
    if nondimensional and var.scale is not None:
        out = {"long_name": f"{var.long_name}, in {var.scale}", "units": "1"}
    if var.standard_name:
        out["standard_name"] = var.standard_name
    if var.description:
        out["description"] = var.description
    return out


def units(name: str, nondimensional: bool = False) -> str:
    """Return the CF/UDUNITS unit string of a named quantity ("1": dimensionless).

    Parameters
    ----------
    name : str
        A key of :data:`VARIABLES`.
    nondimensional : bool, default False
        True for the quantity in the paper's units ("1" unless dimensionless anyway).

    Returns
    -------
    str
        The unit string.
    """
    return attrs(name, nondimensional)["units"]


def units_of(keys, nondimensional: bool = False) -> dict:
    """Map each of a sequence of names (e.g. a record's keys) to its unit string.

    Parameters
    ----------
    keys : iterable of str
        Names of :data:`VARIABLES`.
    nondimensional : bool, default False
        True for the quantity in the paper's units ("1" unless dimensionless anyway).

    Returns
    -------
    dict
        Name -> unit string.
    """
    return {k: units(k, nondimensional) for k in keys}


def order_dims(dims) -> tuple:
    """Sort ``dims`` into :data:`DIM_ORDER` (unknown names keep their order, last).

    Parameters
    ----------
    dims : iterable of str
        Dimension names.

    Returns
    -------
    tuple of str
        The sorted names.
    """
    dims = tuple(dims)
    known = [d for d in DIM_ORDER if d in dims]
    return tuple(known) + tuple(d for d in dims if d not in DIM_ORDER)
