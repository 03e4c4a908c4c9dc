"""netCDF output of an adhesive BEM solution: its fields, its path and its pull-off.

In the style of :mod:`dhfield.io.field`, one :class:`xarray.Dataset` per solution:

* coordinates ``x``, ``y`` (cell centres of the full grid);
* on (y, x) -- rows y, columns x, so ``ds.gap.plot()`` draws x horizontally
  (older files have (x, y); :func:`read_solution` turns them): the total
  ``pressure`` (compressive positive, the adhesive traction negative), the
  ``gap`` h = z - delta + omega, the ``cohesive_fraction`` of each cell in
  the cohesive zone (sub-cell, in [0, 1]) and the categorical
  ``region`` (contact / cohesive_zone / outside, CF flags: a cell is in the
  zone when more than half of it is);
* scalars of the state: ``approach``, ``load``, the second-moment semi-axes
  ``a``, ``b``, ``c``, ``d``, ``beta_ab``, ``beta_cd``, and the solver record
  ``converged``, ``iterations``, ``outer_iterations``, ``residual``;
* for a path (:class:`dhfield.bem.UnloadingPath`), on the dimension ``step``
  (solve order): approach, load, semi-axes, contact area, phase (CF flags),
  converged (CF flags), iterations, residual per step, and the pull-off;
* for a nondimensional BEM pull-off (the :class:`dhfield.core.records.PullOff` of
  :func:`dhfield.analysis.bem_start.adhesive_pull_off`), the paper's quantities W*, a*,
  b*, c*, d*, delta* (Eqs. 32-34) per step and at pull-off, with ``units = "1"``
  and the scale in ``long_name``, and its ellipticities at pull-off as
  ``beta_ab_pull_off``, ``beta_cd_pull_off`` (the record's ``ellipticity`` and
  ``adhesive_ellipticity``, named as the state's ``beta_ab``, ``beta_cd``);
* with the physical inputs of the contact (``params``, a
  :class:`dhfield.analysis.dimensional.ContactParameters`): the same pull-off in SI
  (``force_pull_off`` [N], ``semi_major_pull_off`` ... [m], ``approach_pull_off``
  [m]), the ``force_path`` [N] per step, the SI inputs (``work_of_adhesion``,
  ``max_adhesive_stress``, ``reduced_modulus``, ``r_major``, ``r_minor``,
  ``effective_radius``) and the scales of the paper's units as attributes
  (``length_unit_m``, ``approach_unit_m``, ``stress_unit_Pa``, ``load_unit_N``);
* the global attributes of :func:`dhfield.io.provenance_attrs` with every input
  parameter (``param_*``, including the traction law).

Metadata of the quantities come from the one table :mod:`dhfield.core.schema`
(via :mod:`dhfield.io.cf`); the few that it does not list (the raw solver
``load``, ``cohesive_fraction``, ``residual``, ``phase``, ``step``) are defined
here in :data:`LOCAL_VARIABLES`.  Writes go through :func:`dhfield.io.write_netcdf`
(atomic).
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import xarray as xr

from ..core.schema import order_dims as schema_order
from . import cf, check_writable, provenance_attrs, read_netcdf, write_netcdf

__all__ = ["state_dataset", "path_dataset", "pull_off_dataset", "write_solution", "read_solution",
           "pull_off_si", "stress_unit", "REGIONS", "PHASES", "LOCAL_VARIABLES", "SI_PULL_OFF_KEYS",
           "SI_INPUT_KEYS"]

#: Categories of the ``region`` flag variable, code = position.
REGIONS = ("contact", "cohesive_zone", "outside")
#: Categories of the per-step ``phase`` flag variable (a phase the path names that is not
#: listed here is appended to the flag meanings of that file, never dropped).
PHASES = ("loading", "unloading", "refine", "jump")
#: name -> (long_name, kind) of the variables not in :mod:`dhfield.core.schema`; kind
#: is "length", "length2", "stress", "force" or "1".
LOCAL_VARIABLES = {
    "load": ("total normal load, sum of pressure x cell area, positive compressive", "force"),
    "cohesive_fraction": ("fraction of the cell in the cohesive zone (0 < h < h0), sub-cell", "1"),
    "residual": ("solver residual: complementarity error and last change of the zone fraction", "1"),
    "outer_iterations": ("outer (cohesive-zone) iterations", "1"),
    "contact_area": ("contact area", "length2"),
    "a": ("contact semi-major axis from second moments of the contact mask", "length"),
    "b": ("contact semi-minor axis from second moments of the contact mask", "length"),
    "c": ("adhesive semi-major axis from second moments of contact + cohesive zone", "length"),
    "d": ("adhesive semi-minor axis from second moments of contact + cohesive zone", "length"),
    "step": ("solved state index, in solve order", "1"),
}
#: SI outputs of a BEM pull-off (:func:`pull_off_si`), schema names, in order.
SI_PULL_OFF_KEYS = ("force", "semi_major", "semi_minor", "adhesive_semi_major", "adhesive_semi_minor", "approach")
#: SI inputs of the contact reported beside them, schema names, in order.
SI_INPUT_KEYS = ("work_of_adhesion", "max_adhesive_stress", "reduced_modulus", "r_major", "r_minor",
                 "effective_radius")
_SI = {"length": "m", "length2": "m2", "stress": "Pa", "force": "N", "1": "1"}
_NONDIM_SCALE = {"length": "c_r", "length2": "c_r^2", "stress": "E* c_r/R", "force": "R dgamma", "1": None}


def _local(name, dims, values, nondimensional, qualifier=None):
    long_name, kind = LOCAL_VARIABLES[name]
    if nondimensional and _NONDIM_SCALE[kind]:
        attrs = {"long_name": f"{long_name}, in {_NONDIM_SCALE[kind]}", "units": "1"}
    else:
        attrs = {"long_name": long_name, "units": _SI[kind]}
    if qualifier:
        attrs["long_name"] += f", {qualifier}"
    return (dims, np.asarray(values, dtype=float), attrs)


def _flag(name, dims, codes, meanings, long_name):
    return (dims, np.asarray(codes, dtype=np.int8), {
        "long_name": long_name, "flag_values": np.arange(len(meanings), dtype=np.int8),
        "flag_meanings": " ".join(meanings)})


def _law_parameters(law) -> dict:
    if law is None:
        return {"law": "none"}
    return {"law": law.name, "law_max_stress": float(law.max_stress), "law_range": float(law.range)}


def region_codes(state):
    """Return the region code of every cell of a state (outside, cohesive zone, contact; see REGIONS)."""
    region = np.full(state.grid.shape, REGIONS.index("outside"), dtype=np.int8)
    region[np.asarray(state.cohesive) > 0.5] = REGIONS.index("cohesive_zone")
    region[np.asarray(state.contact, dtype=bool)] = REGIONS.index("contact")
    return region


def state_dataset(state, *, nondimensional: bool = False, title: str | None = None, **parameters) -> xr.Dataset:
    """Build the Dataset of one :class:`dhfield.bem.ContactState` (fields and scalars).

    Parameters
    ----------
    state : dhfield.bem.ContactState
        Solved contact state: its pressure, gap, cohesive fraction and region
        on the grid ``(y, x)``, and its scalars (approach, load, semi-axes,
        solver diagnostics).
    nondimensional : bool
        True when the state is in the paper's units (R = E* = dgamma = 1): units
        become "1" and the scales are named in ``long_name``; else SI.
    title : str, optional
        Global ``title``.
    **parameters
        Input parameters stored as ``param_*`` attributes.

    Returns
    -------
    xarray.Dataset
        The state's fields on ``(y, x)`` and its scalars, CF attributes and
        provenance attributes included.
    """
    g = state.grid
    nd = nondimensional
    dims = ("y", "x")   # rows y, columns x (the grid's arrays are (x, y): transposed below)
    a, b = state.contact_semi_axes()
    c, d = state.cohesive_semi_axes()
    data = {
        "pressure": cf.variable("pressure", dims, np.asarray(state.pressure).T, nondimensional=nd,
                                qualifier="total (contact minus adhesive traction)"),
        "gap": cf.variable("gap", dims, np.asarray(state.gap).T, nondimensional=nd),
        "cohesive_fraction": _local("cohesive_fraction", dims, np.asarray(state.cohesive).T, nd),
        "region": _flag("region", dims, region_codes(state).T, REGIONS,
                        "region of the surface (cohesive zone: more than half of the cell)"),
        "approach": cf.variable("approach", (), state.approach, nondimensional=nd),
        "load": _local("load", (), state.load, nd),
        "beta_ab": cf.variable("beta_ab", (), state.beta_ab),
        "beta_cd": cf.variable("beta_cd", (), state.beta_cd),
        "converged": _flag("converged", (), int(bool(state.converged)), ("false", "true"), "solver converged"),
        "outer_iterations": _local("outer_iterations", (), state.outer_iterations, nd),
        "residual": _local("residual", (), state.residual, nd),
    }
    data["iterations"] = ((), np.int64(state.iterations), {"long_name": "inner conjugate-gradient iterations",
                                                           "units": "1"})
    for name, val in (("a", a), ("b", b), ("c", c), ("d", d)):
        data[name] = _local(name, (), val, nd)
    coords = {"x": cf.coordinate("x", g.x, nondimensional=nd), "y": cf.coordinate("y", g.y, nondimensional=nd)}
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update(provenance_attrs(
        title or "dhfield: self-consistent adhesive BEM contact state (DC-FFT, free boundary)",
        **_law_parameters(state.law), cell_size_x=g.dx, cell_size_y=g.dy, nx=g.nx, ny=g.ny,
        nondimensional=bool(nd), **parameters))
    return cf.finalize(ds)


def path_dataset(path, *, nondimensional: bool = False, sin_skew: float | None = None) -> xr.Dataset:
    """Build the per-step arrays of a :class:`dhfield.bem.UnloadingPath` on the dimension ``step``.

    With ``sin_skew`` (and ``nondimensional``), the load is also given as
    W* = W sin(theta_skew)/(2 pi) (Eq. 34, R = dgamma = 1) and the approach as delta*.

    Parameters
    ----------
    path : dhfield.bem.UnloadingPath
        The loading-unloading path (approach, load, contact area, semi-axes,
        phase and solver diagnostics per step, and its pull-off).
    nondimensional : bool
        True when the path is in the paper's units (R = E* = dgamma = 1); else SI.
    sin_skew : float, optional
        The sine of the skew angle, sin(theta_skew) [-] (Eq. 34); with ``nondimensional``
        it adds ``W_star_path``. None (default) leaves it out.

    Returns
    -------
    xarray.Dataset
        The ``*_path`` variables on ``step``, ``pull_off_load`` and
        ``pull_off_approach``; attributes ``control``, ``n_failures``,
        ``failures`` and ``elapsed_seconds``.
    """
    nd = nondimensional
    n = int(np.size(path.approach))
    dims = ("step",)
    meanings = list(PHASES) + sorted({str(p) for p in path.phase} - set(PHASES))
    phase = [meanings.index(str(p)) for p in path.phase]
    data = {
        "approach_path": cf.variable("approach", dims, path.approach, nondimensional=nd, qualifier="per step"),
        "load_path": _local("load", dims, path.load, nd, "per step"),
        "contact_area_path": _local("contact_area", dims, path.contact_area, nd, "per step"),
        "phase": _flag("phase", dims, phase, meanings, "phase of the path"),
        "converged_path": _flag("converged", dims, np.asarray(path.converged, dtype=int), ("false", "true"),
                                "solver converged, per step"),
        "iterations_path": (dims, np.asarray(path.iterations, dtype=np.int64),
                            {"long_name": "inner conjugate-gradient iterations, per step", "units": "1"}),
        "outer_iterations_path": _local("outer_iterations", dims, path.outer_iterations, nd, "per step"),
        "residual_path": _local("residual", dims, path.residual, nd, "per step"),
    }
    for name in ("a", "b", "c", "d"):
        data[f"{name}_path"] = _local(name, dims, getattr(path, name), nd, "per step")
    if nd and sin_skew is not None:
        w_star = np.asarray(path.load, float) * sin_skew / (2.0 * math.pi)  # Eq. (34)
        data["W_star_path"] = cf.variable("W_star", dims, w_star, nondimensional=True, qualifier="per step")
    data["pull_off_load"] = _local("load", (), path.pull_off_load, nd, f"at pull-off ({path.control} control)")
    data["pull_off_approach"] = cf.variable("approach", (), path.pull_off_approach, nondimensional=nd,
                                            qualifier=f"at pull-off ({path.control} control)")
    ds = xr.Dataset(data, coords={"step": ("step", np.arange(n, dtype=np.int32),
                                           {"long_name": LOCAL_VARIABLES["step"][0], "units": "1"})})
    ds.attrs["control"] = path.control
    ds.attrs["n_failures"] = len(path.failures)
    ds.attrs["failures"] = "; ".join(
        f"step at approach {f.get('approach', float('nan')):.6g} ({f.get('phase', '?')}): residual "
        f"{f.get('residual', float('nan')):.3g} after {f.get('iterations', '?')} iterations"
        for f in path.failures) or "none"
    ds.attrs["elapsed_seconds"] = float(path.elapsed)
    return ds


def pull_off_dataset(result, *, fields: bool = True) -> xr.Dataset:
    """Build the Dataset of a nondimensional BEM pull-off record (:class:`dhfield.core.records.PullOff`).

    The pull-off scalars (W*, a*, b*, c*, d*, delta*, Eqs. 32-34, and the
    ellipticities b/a, d/c as ``beta_ab_pull_off``, ``beta_cd_pull_off``), the
    whole path, and (``fields=True``) the fields of the pull-off state, all in
    the paper's units.

    Parameters
    ----------
    result : dhfield.core.records.PullOff
        The BEM pull-off (:func:`dhfield.analysis.bem_start.adhesive_pull_off`), in the
        paper's units (R = E* = dgamma = 1), with its path.
    fields : bool, default True
        Include the fields of the pull-off state on ``(y, x)``; False keeps
        only the scalars and the path.

    Returns
    -------
    xarray.Dataset
        The ``*_pull_off`` scalars, the path's ``*_path`` variables on
        ``step``, the flags ``resolved`` and ``converged_pull_off`` and,
        with ``fields``, the pull-off state's fields; the attribute ``solver_options``
        (JSON) where the record has it.
    """
    sin_skew = float(result.sin_skew)
    params = dict(beta0=result.beta0, mu=result.mu, n=result.n, control=result.control,
                  half_width_x=result.half_width_x, half_width_y=result.half_width_y, sin_skew=sin_skew)
    if fields:
        ds = state_dataset(result.path.pull_off_state, nondimensional=True,
                           title="dhfield: self-consistent adhesive BEM pull-off of the elliptical contact "
                                 "(DC-FFT, free boundary)", **params)
    else:
        ds = xr.Dataset()
        ds.attrs.update(provenance_attrs("dhfield: self-consistent adhesive BEM pull-off of the elliptical "
                                         "contact (DC-FFT, free boundary)", law=result.law, **params))
    path_ds = path_dataset(result.path, nondimensional=True, sin_skew=sin_skew)
    ds = ds.merge(path_ds, combine_attrs="override")
    ds.attrs.update(path_ds.attrs)
    q = "BEM at pull-off"
    for key in ("W_star", "a_star", "b_star", "c_star", "d_star", "delta_star"):
        ds[f"{key}_pull_off"] = cf.variable(key, (), getattr(result, key), nondimensional=True, qualifier=q)
    for key, field in (("beta_ab", "ellipticity"), ("beta_cd", "adhesive_ellipticity")):
        ds[f"{key}_pull_off"] = cf.variable(key, (), getattr(result, field), qualifier=q)
    resolved = bool(getattr(result, "resolved", True))
    ds["resolved"] = _flag("resolved", (), int(resolved), ("false", "true"),
                           "grid resolves the cohesive zone (false: the pull-off is not an answer; refine n)")
    ds["converged_pull_off"] = _flag("converged", (), int(bool(result.converged)), ("false", "true"),
                                     "every state of the path down to the pull-off converged")
    ds.attrs.update({"converged": int(bool(result.converged)), "resolved": int(resolved),
                     "n_steps": int(result.n_steps),
                     "iterations": int(result.iterations), "residual": float(result.residual),
                     "control": result.control, "elapsed_seconds": float(result.elapsed)})
    if getattr(result, "search", ""):
        ds.attrs["search"] = result.search      # the route that gave the pull-off
    if getattr(result, "solver_options", None):
        ds.attrs["solver_options"] = str(result.solver_options)     # JSON of the states' Newton options
    return cf.finalize(ds)


def stress_unit(params) -> float:
    """The paper's unit of stress E* c_r/R of a contact (sigma0 = mu times it, Eq. 35).

    Parameters
    ----------
    params : dhfield.analysis.dimensional.ContactParameters
        The contact (scalar parameters).

    Returns
    -------
    float
        E* c_r/R [Pa].
    """
    return float(params.reduced_modulus * params.length_unit / params.effective_radius)


def pull_off_si(result, params) -> dict:
    """The pull-off of a nondimensional BEM result in SI units, with the SI inputs.

    Parameters
    ----------
    result : dhfield.core.records.PullOff
        A BEM pull-off solved at ``params.beta0`` and ``params.mu``.
    params : dhfield.analysis.dimensional.ContactParameters
        The contact (scalar parameters).

    Returns
    -------
    dict
        :data:`SI_PULL_OFF_KEYS` then :data:`SI_INPUT_KEYS`: ``force`` [N] (negative:
        tensile), the semi-axes and the ``approach`` [m], the inputs [Pa, J m^-2, m].

    Notes
    -----
    Inverts Eqs. (32)-(34) with the scales of
    :func:`dhfield.analysis.dimensional.contact_parameters`:

    .. math:: W = W^* \\frac{2\\pi R \\Delta\\gamma}{\\sin\\theta_{skew}}, \\quad
              a = a^* c_r, \\quad \\delta = \\delta^* c_r^2/R

    where the BEM's sin(theta_skew) (that of beta0) is the one of ``params``.
    """
    if not (math.isclose(float(params.beta0), result.beta0, rel_tol=1e-9)
            and math.isclose(float(params.mu), result.mu, rel_tol=1e-9)):
        raise ValueError(f"params must describe the solved case (beta0 = {result.beta0:g}, mu = {result.mu:g}); "
                         f"got beta0 = {float(params.beta0):g}, mu = {float(params.mu):g}")
    lu = float(params.length_unit)
    out = {
        "force": result.W_star * float(params.load_unit),  # Eq. (34)
        "semi_major": result.a_star * lu, "semi_minor": result.b_star * lu,  # Eq. (32)
        "adhesive_semi_major": result.c_star * lu, "adhesive_semi_minor": result.d_star * lu,
        "approach": result.delta_star * float(params.approach_unit),  # Eq. (33)
    }
    out.update({k: float(getattr(params, k)) for k in SI_INPUT_KEYS})
    return out


def _add_si(ds, result, params):
    """Add the SI pull-off, the SI force path, the SI inputs and the scales to ``ds``."""
    q = "BEM at pull-off"
    si = pull_off_si(result, params)
    for key in SI_PULL_OFF_KEYS:
        ds[f"{key}_pull_off"] = cf.variable(key, (), si[key], qualifier=q)
    for key in SI_INPUT_KEYS:
        ds[key] = cf.variable(key, (), si[key])
    # the path's load is in R dgamma (E* c_r/R x c_r^2 with c_r^3 = R^2 dgamma/E*): W = load R dgamma
    force_unit = float(params.effective_radius * params.work_of_adhesion)
    ds["force_path"] = cf.variable("force", ("step",), np.asarray(result.path.load, float) * force_unit,
                                   qualifier="per step")
    ds.attrs.update({"length_unit_m": float(params.length_unit), "approach_unit_m": float(params.approach_unit),
                     "stress_unit_Pa": stress_unit(params), "load_unit_N": float(params.load_unit)})
    return ds


def write_solution(result, path, *, fields: bool = True, params=None) -> Path:
    """Write a BEM pull-off (:class:`dhfield.core.records.PullOff`) or a ContactState to netCDF atomically.

    Parameters
    ----------
    result : dhfield.core.records.PullOff or dhfield.bem.ContactState
        What to write (:func:`pull_off_dataset` or :func:`state_dataset`).
    path : path-like
        The netCDF file; checked before the Dataset is built, written atomically.
    fields : bool
        A pull-off: also the fields of the pull-off state.
    params : dhfield.analysis.dimensional.ContactParameters, optional
        The contact of the solved case: a pull-off then also carries its SI values
        (:func:`pull_off_si`).

    Returns
    -------
    pathlib.Path
        The file written.
    """
    check_writable(path)
    if getattr(result, "path", None) is not None and hasattr(result, "W_star"):
        ds = pull_off_dataset(result, fields=fields)
        if params is not None:
            ds = cf.finalize(_add_si(ds, result, params))
    else:
        ds = state_dataset(result)
    return write_netcdf(ds, path)


def read_solution(path) -> xr.Dataset:
    """Read a file written by :func:`write_solution`.

    Parameters
    ----------
    path : str or pathlib.Path
        The netCDF file.

    Returns
    -------
    xarray.Dataset
        The solution, its fields ordered ``(y, x)`` (files before 2026-11
        stored them ``(x, y)``).

    Raises
    ------
    ValueError
        If the file is not a dhfield BEM solution (no ``gap``, no
        ``W_star_pull_off``); the message names the file.
    """
    ds = read_netcdf(path)
    if "gap" not in ds and "W_star_pull_off" not in ds:
        raise ValueError(f"input file is not a dhfield BEM solution (no gap, no W_star_pull_off): {str(path)!r}")
    return ds.transpose(*schema_order(ds.dims))   # files before 2026-11 stored the fields (x, y)
