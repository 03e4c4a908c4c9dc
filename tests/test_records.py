"""dhfield.core.records: the one pull-off record and the one load-curve record (issue 16)."""
import numpy as np
import pytest

from dhfield.core.records import LoadCurve, PullOff, load_curve_record, pull_off_record
from dhfield.core.schema import LOAD_CURVE_HEADER_KEYS, LOAD_CURVE_KEYS, PULL_OFF_KEYS


def test_pull_off_record_fields_defaults_and_mapping():
    """A circle without adhesive zone (JKR-like state): b = a, no zone, ellipticity 1; the record reads
    as attributes and as a read-only mapping in the schema's order."""
    st = {"W_star": -0.75, "a_star": 1.5, "delta_star": -0.77}
    rec = pull_off_record("jkr", 1.0, [1.0, 2.0], st, control="load", sin_skew=1.0, geometry="circle")
    assert type(rec) is PullOff and tuple(rec) == PULL_OFF_KEYS and len(rec) == len(PULL_OFF_KEYS)
    assert rec.W_star.shape == (2,) and np.all(rec.b_star == rec.a_star)
    assert np.all(np.isnan(rec.c_star)) and np.all(np.isnan(rec.d_star)) and np.all(np.isnan(rec.v))
    assert np.all(rec.ellipticity == 1.0) and np.all(np.isnan(rec.adhesive_ellipticity))
    assert not rec.at_zero_contact.any() and list(rec.warning) == ["", ""]
    assert {**rec}["mu"].tolist() == [1.0, 2.0] and rec["model"] == "jkr"
    with pytest.raises(KeyError):
        rec["force"]
    with pytest.raises(AttributeError):
        rec.W_star = 0.0  # frozen
    assert rec.replace(warning="w").warning == "w"


def test_pull_off_record_zero_contact_and_ellipse():
    """At a* = 0 the contact ratio defaults to 1 and at_zero_contact to True; d* defaults to c* b*/a*."""
    zero = pull_off_record("md", 1.0, 0.5, {"W_star": -1.0, "a_star": 0.0, "c_star": 2.0, "delta_star": 0.0},
                           control="load", sin_skew=1.0, geometry="circle")
    assert zero.at_zero_contact and zero.ellipticity == 1.0 and zero.d_star == 2.0 and np.ndim(zero.W_star) == 0
    ell = pull_off_record("x", 0.5, 1.0, {"W_star": -0.5, "a_star": 2.0, "b_star": 1.0, "c_star": 4.0,
                                          "delta_star": 0.1}, control="displacement", sin_skew=0.8,
                          geometry="ellipse")
    assert ell.d_star == 2.0 and ell.ellipticity == 0.5 and ell.adhesive_ellipticity == 0.5


def test_load_curve_record():
    c = load_curve_record("jkr", 1.0, 2.0, {"a_star": [1.0, 2.0], "W_star": [0.1, 0.2], "delta_star": [0, 1]},
                          sin_skew=1.0, geometry="circle")
    assert type(c) is LoadCurve and tuple(c) == LOAD_CURVE_HEADER_KEYS + LOAD_CURVE_KEYS
    assert c.b_star.tolist() == [1.0, 2.0] and np.all(np.isnan(c.c_star)) and c.mu == 2.0


def test_pull_off_si_record_is_the_nondimensional_one_in_si_units():
    """The one SI record (issue 16): the schema's SI keys in order; every nondimensional field carried
    unchanged; W = W* 2 pi R dgamma / sin(theta_skew), a = a* c_r, delta = delta* c_r^2/R (Eqs. 32-34,
    here with R = 8, E* = 1, dgamma = 1: c_r = 4, c_r^2/R = 2, exact in binary)."""
    from dhfield.core.units import pull_off_si, si_inputs
    from dhfield.core.records import PullOff
    from dhfield.core.schema import PULL_OFF_SI_KEYS

    st = {"W_star": -0.75, "a_star": 1.5, "c_star": 2.0, "delta_star": -0.5}
    rec = pull_off_record("md", 1.0, [1.0, 2.0], st, control="load", sin_skew=0.5, geometry="circle")
    si = pull_off_si(rec, si_inputs(np.float64(8.0), np.float64(1.0), np.float64(1.0), 3.0, radius_ratio=4.0))
    assert type(si) is PullOff and tuple(si) == PULL_OFF_SI_KEYS and si.groups == ("si",)
    assert si.force.tolist() == [-0.75 * 2 * np.pi * 8.0 / 0.5] * 2
    assert si.semi_major.tolist() == [6.0, 6.0] and si.adhesive_semi_major.tolist() == [8.0, 8.0]
    assert si.approach.tolist() == [-1.0, -1.0]
    assert si.r_major.tolist() == [16.0, 16.0] and si.r_minor.tolist() == [4.0, 4.0]  # R'R'' = R^2, R'/R'' = 4
    assert si.max_adhesive_stress.tolist() == [3.0, 3.0]
    for k in PULL_OFF_KEYS:
        x, y = np.asarray(si[k]), np.asarray(rec[k])
        assert np.array_equal(x, y, equal_nan=x.dtype.kind == "f"), k


def test_bem_pull_off_is_the_one_record_with_its_solver_group():
    """The adhesive BEM answers with the same PullOff as every model, its solver group filled (keys
    PULL_OFF_KEYS then PULL_OFF_SOLVER_KEYS, in order) and its path as a non-key attribute."""
    import json

    from dhfield.analysis.bem_start import adhesive_pull_off, refine_pull_off
    from dhfield.bem.branch import UnloadingPath
    from dhfield.bem.pull_off import pull_off_summary
    from dhfield.core.geometry import sin_skew_angle
    from dhfield.core.schema import PULL_OFF_SOLVER_KEYS

    rec = adhesive_pull_off(beta0=0.9, mu=1.0, n=32, progress=False)
    assert type(rec) is PullOff and tuple(rec) == PULL_OFF_KEYS + PULL_OFF_SOLVER_KEYS and rec.groups == ("solver",)
    assert (rec.model, rec.geometry, rec.control, rec.n, rec.law) == ("bem", "ellipse", "load", 32, "dugdale")
    assert rec.sin_skew == float(sin_skew_angle(0.9)) and np.isnan(rec.v)   # Eq. (34); no DH factor
    assert rec.ellipticity == rec.b_star / rec.a_star and rec.adhesive_ellipticity == rec.d_star / rec.c_star
    assert rec.at_zero_contact == (not rec.a_star > 0)
    assert rec.warning == ("" if rec.resolved else rec.note)
    assert isinstance(rec.path, UnloadingPath) and "path" not in rec and isinstance(rec.failures, tuple)
    summary = pull_off_summary(rec)
    assert tuple(summary) == tuple(rec) and isinstance(summary["failures"], list)
    json.dumps(summary)         # JSON-ready: scalars, strings and a list of dicts
    # the options of every state are recorded: a path route's (n given), from its tolerance and cap
    from dhfield.bem.solver import DEFAULT_MAX_ITER, DEFAULT_TOL, state_options

    assert rec.search != "newton"
    assert json.loads(rec.solver_options) == state_options(DEFAULT_TOL, DEFAULT_MAX_ITER).as_dict()
    analytic = pull_off_record("md", 0.9, 1.0, {"W_star": -0.8, "a_star": 1.0, "delta_star": 0.0},
                               control="load", sin_skew=1.0, geometry="ellipse")
    with pytest.raises(ValueError, match="coarse must be a BEM pull-off"):
        refine_pull_off(analytic, 64)


def test_load_curve_si_record_and_groups():
    """An SI curve holds the SI array group (the schema's SI keys, in order) and no nondimensional
    one; a mixture of the two groups is refused; ``ellipticity`` is a key only where set."""
    from dhfield.core.schema import LOAD_CURVE_ALL_KEYS, LOAD_CURVE_SI_KEYS

    c = load_curve_record("jkr", 1.0, float("nan"), {"semi_major": [1.0, 2.0], "force": [0.1, 0.2],
                                                      "approach": [0, 1]}, sin_skew=1.0, geometry="circle")
    assert type(c) is LoadCurve and tuple(c) == LOAD_CURVE_HEADER_KEYS + LOAD_CURVE_SI_KEYS and not c.nondimensional
    assert c.semi_minor.tolist() == [1.0, 2.0] and np.all(np.isnan(c.adhesive_semi_major)) and c.a_star is None
    with pytest.raises(KeyError):
        c["W_star"]
    e = load_curve_record("x", 0.9, 1.0, {"a_star": [1.0], "W_star": [0.1], "delta_star": [0.0]}, sin_skew=0.9,
                          geometry="ellipse", ellipticity=0.8)
    assert tuple(e) == LOAD_CURVE_HEADER_KEYS + LOAD_CURVE_KEYS + ("ellipticity",) and e.ellipticity == 0.8
    assert tuple(f for f in LOAD_CURVE_ALL_KEYS if f in e or f in c) == LOAD_CURVE_ALL_KEYS
    with pytest.raises(ValueError, match="not a mixture"):
        c.replace(W_star=np.zeros(2))


def _si_curves():
    """Every model's SI load_curve at two contact sizes (R = 1 um, E* = 1 GPa, dgamma = 0.05 J/m^2)."""
    from dhfield.models import dh_circular, dmt, jkr, jkr_elliptic, jkr_elliptic_energy, maugis_dugdale
    from dhfield.analysis import dimensional

    r, e, w, s0 = 1e-6, 1e9, 0.05, 3e8
    a = np.array([5e-9, 2e-8])
    p = dimensional.contact_parameters(1e9, 0.5, 1e9, 0.5, 1e-6, 1.2, 0.05, 3e8)
    return {"jkr": jkr.load_curve(a, r, e, w), "dmt": dmt.load_curve(a, r, e, w),
            "md": maugis_dugdale.load_curve(a, r, e, w, s0), "dh-circular": dh_circular.load_curve(a, r, e, w, s0),
            "jkr-elliptic": jkr_elliptic.load_curve(a, r, e, w, beta0=0.8),
            "jkr-elliptic-energy": jkr_elliptic_energy.load_curve(a, r, e, w, beta0=0.8),
            "load_curve_si": dimensional.load_curve_si(p, n=3, model="md")}


def test_every_model_load_curve_is_the_one_type():
    """The one load-curve type (issue 16): the registry's and the paper's model's curves in the paper's
    units (header + LOAD_CURVE_KEYS; the paper's model adds its ellipticity), every SI load_curve with
    the SI keys, in the schema's order."""
    from dhfield.analysis import compare
    from dhfield.models import dh_elliptic as model
    from dhfield.core.schema import LOAD_CURVE_SI_KEYS

    for name in compare.CURVE_MODEL_NAMES:
        c = compare.load_curve(name, mu=1.0, beta0=0.9, n=3)
        assert type(c) is LoadCurve and tuple(c) == LOAD_CURVE_HEADER_KEYS + LOAD_CURVE_KEYS and c.model == name
    m = model.load_curve(mu=1.0, beta0=0.9, n=3, ellipticity=0.85)
    assert type(m) is LoadCurve and tuple(m) == LOAD_CURVE_HEADER_KEYS + LOAD_CURVE_KEYS + ("ellipticity",)
    assert m.ellipticity == 0.85 and m.model == "dh-elliptic" and np.allclose(m.b_star, 0.85 * m.a_star, rtol=0)
    for name, c in _si_curves().items():
        keys = LOAD_CURVE_HEADER_KEYS + LOAD_CURVE_SI_KEYS + (("ellipticity",) if name.startswith("jkr-elliptic")
                                                               else ())
        assert type(c) is LoadCurve and tuple(c) == keys, name
        assert np.shape(c.force) == np.shape(c.semi_major) == np.shape(c.approach) == np.shape(c.v), name


def test_si_curves_match_their_nondimensional_cores():
    """Each SI curve is its core's nondimensional state in SI units: a = a* c_r, W = W* 2 pi R dgamma /
    sin(theta_skew), the zone c = c* c_r where the model has one (Eqs. 32-34); the header's mu is the
    Tabor parameter of Eq. (35) for MD and DH circular and NaN for the models without one."""
    from dhfield.models import dh_circular, maugis_dugdale

    r, e, w, s0 = 1e-6, 1e9, 0.05, 3e8
    cr, mu = np.cbrt(r * r * w / e), s0 * np.cbrt(r / (e * e * w))
    curves = _si_curves()
    for name, module in (("md", maugis_dugdale), ("dh-circular", dh_circular)):
        c = curves[name]
        st = module.load_curve_nondimensional(c.semi_major / cr, mu)
        np.testing.assert_allclose(c.adhesive_semi_major, st["c_star"] * cr, rtol=1e-12)  # round-off of c_r
        np.testing.assert_allclose(c.force, st["W_star"] * 2 * np.pi * r * w, rtol=1e-12)
        assert c.mu == pytest.approx(mu, rel=1e-15) and c.geometry == "circle" and c.beta0 == 1.0
    assert np.all(np.isnan(curves["jkr"].adhesive_semi_major)) and np.isnan(curves["jkr"].mu)
    assert np.all(np.isfinite(curves["dh-circular"].v)) and np.all(np.isnan(curves["md"].v))
    je = curves["jkr-elliptic"]
    assert je.geometry == "ellipse" and je.beta0 == 0.8
    np.testing.assert_allclose(je.ellipticity, je.semi_minor / je.semi_major, rtol=1e-12)  # b/a, rounded once


def test_worst_residual_is_the_largest_unconverged_residual_else_the_records():
    """One expression for the CLI and the lattice retry: the largest residual among the failures."""
    base = pull_off_record("md", 0.9, 1.0, {"W_star": -0.8, "a_star": 1.0, "delta_star": 0.0},
                           control="load", sin_skew=1.0, geometry="ellipse")
    assert base.worst_residual is None                                   # no solver group
    failed = base.replace(converged=False, residual=1e-5,
                          failures=({"residual": 3e-3, "approach": -0.7}, {"residual": 7e-3, "approach": -0.8}))
    assert failed.worst_residual == 7e-3
    assert failed.replace(failures=()).worst_residual == 1e-5
