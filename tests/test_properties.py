"""Property-based tests (hypothesis) over the whole accepted input domain (issue 9).

Domain: mu in TABOR_RANGE = [1e-6, 1e12], beta0 in ELLIPTICITY_RANGE = [1e-4, 1],
a* in CONTACT_SIZE_RANGE = [1e-6, 1e6] (dhfield.core.validation); the closures have
the narrower CLOSURE_MU_RANGE / CLOSURE_BETA0_RANGE.

Properties
----------
* never a non-finite W*, a*, delta*;
* W*max in [W*_DMT, 0): W*_DMT = -beta0 sin(theta_skew) R'(beta0)/R, the zero-contact
  limit of the DH model as mu -> 0 (= -1 at the circle, Bradley/DMT); the pull-off
  is tensile and never exceeds the DMT force (Eq. 36 at a = 0 with mu S^2 -> 3R');
* load control |W*| >= displacement control |W*| (load control pulls off at the
  minimum of W over the stable branch, which the fixed-grips path also passes);
* |W*max| decreasing in mu (DMT -> JKR: the DMT limit is the largest adhesion of the
  family; checked for the DH models and MD);
* every rejection is a ValueError whose message starts with the parameter's name.

Profiles: "ci" (default; derandomized, few examples) and "long" (HYPOTHESIS_PROFILE=long,
run by ``verification/properties_long.py``).
"""
import os

import numpy as np
import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from dhfield.analysis import compare, dimensional
from dhfield.models import dh_elliptic as model
from dhfield.core.validation import CONTACT_SIZE_RANGE, ELLIPTICITY_RANGE, TABOR_RANGE
from dhfield.core.geometry import radius_ratio, sin_skew_angle

settings.register_profile("ci", max_examples=12, derandomize=True, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("long", max_examples=int(os.environ.get("DHFIELD_LONG_EXAMPLES", "400")), deadline=None,
                          suppress_health_check=[HealthCheck.too_slow])
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))

#: W* bounds are checked to the solve tolerance (1e-14 in log Delta gamma) with margin.
BOUND_RTOL = 1e-9
#: Monotonicity in mu is checked between values a factor >= 1.5 apart, beyond rounding.
MONO_RTOL = 1e-9

log_mu = st.floats(np.log10(TABOR_RANGE[0]), np.log10(TABOR_RANGE[1]))
log_beta = st.floats(np.log10(ELLIPTICITY_RANGE[0]), 0.0)
mus = log_mu.map(lambda x: float(min(10.0**x, TABOR_RANGE[1])))
betas = log_beta.map(lambda x: float(min(10.0**x, 1.0)))


def dmt_limit(beta0):
    """W* of the DH model's zero-contact state as mu -> 0: -beta0 sin(theta_skew) sqrt(R'/R'')."""
    return -beta0 * sin_skew_angle(beta0) * np.sqrt(radius_ratio(beta0))


@given(mu=mus, beta0=betas)
@example(mu=1e8, beta0=1.0)      # issue 9 item 1: was W* = +1.698
@example(mu=1e9, beta0=1.0)      # was 0
@example(mu=1e-6, beta0=0.9)     # item 6 neighbourhood (1e-30 is now rejected)
@example(mu=100.0, beta0=0.001)  # item 2: was the zero-contact limit
@example(mu=10.0, beta0=1e-4)    # pull-off at 6x the JKR-limit contact
def test_dh_pull_off_is_finite_bounded_and_load_beats_displacement(mu, beta0):
    load = model.pull_off(mu=mu, beta0=beta0)
    disp = model.pull_off(mu=mu, beta0=beta0, control="displacement")
    for p in (load, disp):
        for k in ("W_star", "a_star", "c_star", "delta_star"):
            assert np.isfinite(getattr(p, k)), k
    w_dmt = float(dmt_limit(beta0))
    w = float(load.W_star)
    assert w_dmt * (1 + BOUND_RTOL) <= w < 0.0
    assert abs(w) >= abs(float(disp.W_star)) * (1 - BOUND_RTOL)


@given(mu=mus, beta0=betas, factor=st.floats(1.5, 100.0))
@example(mu=2.5, beta0=0.01, factor=2.0)  # issue 9 item 2: W* was not monotone in mu here
def test_dh_pull_off_magnitude_decreases_with_mu(mu, beta0, factor):
    mu2 = min(mu * factor, TABOR_RANGE[1])
    if mu2 <= mu:
        return
    w1, w2 = (abs(float(model.pull_off(mu=m, beta0=beta0).W_star)) for m in (mu, mu2))
    assert w2 <= w1 * (1 + MONO_RTOL)


@given(mu=mus, beta0=betas, lo=st.floats(-6.0, 6.0), span=st.floats(0.0, 3.0))
def test_load_curve_is_finite_and_never_below_the_pull_off(mu, beta0, lo, span):
    a = np.clip(np.geomspace(10.0**lo, 10.0 ** (lo + span), 7), *CONTACT_SIZE_RANGE)
    c = model.load_curve(mu=mu, beta0=beta0, a_star=a)
    for k in ("W_star", "c_star", "v", "delta_star"):
        assert np.all(np.isfinite(getattr(c, k))), k
    assert np.all(c.c_star >= c.a_star)
    # Every state is at or above the global minimum load of the curve family.
    assert np.all(c.W_star >= float(dmt_limit(beta0)) * (1 + BOUND_RTOL))


@pytest.mark.parametrize("name", [n for n in compare.MODEL_NAMES])
@given(mu=mus, beta0=betas)
def test_comparison_models_finite_or_reject_by_name(name, mu, beta0):
    try:
        rec = compare.pull_off(name, mu=mu, beta0=beta0)
    except ValueError as exc:  # a narrower domain (the closures): must name mu or beta0
        assert str(exc).startswith(("mu ", "beta0 ")), str(exc)
        return
    w = float(rec["W_star"])
    if not np.isfinite(w):  # a record may carry NaN with a warning saying why; never inf
        assert not np.isinf(w) and rec.get("warning"), rec
        return
    assert w < 0.0
    # Circular references use sin = 1 and R: their DMT bound is -1; elliptical ones beta0's.
    bound = -1.0 if rec.get("geometry") == "circle" else min(-1.0, float(dmt_limit(beta0)))
    assert w >= bound * (1 + 1e-6)


@given(mu=mus.filter(lambda m: m < 1e11))
def test_md_and_dh_circle_decrease_in_mu(mu):
    for name in ("md", "dh-circular"):
        w1 = abs(float(compare.pull_off(name, mu=mu, beta0=1.0)["W_star"]))
        w2 = abs(float(compare.pull_off(name, mu=mu * 3.0, beta0=1.0)["W_star"]))
        assert w2 <= w1 * (1 + MONO_RTOL), name


bad_values = st.sampled_from([0.0, -1.0, 1e-308, 1e308, float("inf"), float("nan")])


@given(value=bad_values, which=st.sampled_from(["mu", "beta0"]))
def test_every_rejection_names_the_parameter(value, which):
    kw = {"mu": 1.0, "beta0": 0.8}
    kw[which] = value
    with pytest.raises(ValueError, match=rf"^{which} "):
        model.pull_off(**kw)
    with pytest.raises(ValueError, match=rf"^{which} "):
        compare.pull_off("md", **kw)
    with pytest.raises(ValueError, match=rf"^{which} "):
        model.load_curve(mu=kw["mu"], beta0=kw["beta0"], a_star=[1.0])


@given(value=bad_values)
def test_rejected_contact_sizes_name_a_star(value):
    with pytest.raises(ValueError, match=r"^a_star "):
        model.load_curve(mu=1.0, beta0=0.8, a_star=[1.0, value])


_SI = dict(youngs_modulus_1=1e6, poisson_ratio_1=0.5, youngs_modulus_2=1e6, poisson_ratio_2=0.5,
           cylinder_radius=1e-3, skew_angle=1.0, work_of_adhesion=0.05, max_adhesive_stress=1e5)


@given(sigma0=st.floats(-3.0, 18.0).map(lambda x: 10.0**x), angle=st.floats(7e-4, np.pi / 2))
@example(sigma0=1e15, angle=1.0)  # issue 9 item 1: was -2.6e-35 N
def test_si_front_end_finite_or_rejected_by_name(sigma0, angle):
    try:
        p = dimensional.contact_parameters(**{**_SI, "max_adhesive_stress": sigma0, "skew_angle": angle})
    except ValueError as exc:
        assert str(exc).startswith(("max_adhesive_stress ", "skew_angle ")), str(exc)
        return
    rec = dimensional.pull_off_force(p, "dh-elliptic", check_closure=False)
    force = float(rec["force"])
    assert np.isfinite(force) and force < 0.0
    # Bounded by the DMT force of the same contact: W* >= W*_DMT, W = W* 2 pi R dgamma/sin.
    assert float(rec["W_star"]) >= float(dmt_limit(p.beta0)) * (1 + BOUND_RTOL)
    # the default (md-elliptic since issue 20): bounded by the paraboloid's DMT force -2 pi dgamma sqrt(R'R'')
    rec = dimensional.pull_off_force(p, warn=False)
    assert np.isfinite(float(rec["force"])) and float(rec["force"]) < 0.0
    # issue 40: md-elliptic answers everywhere but says so outside the box of the stored BEM ground truth,
    # beta0 0.1-1 and mu 0.1-10 (the file's extent, read back by tests/test_one_default.py)
    inside = 0.1 <= float(p.beta0) <= 1.0 and 0.1 <= float(p.mu) <= 10.0
    assert (rec["warning"] == "") if inside else ("outside the BEM-verified box" in rec["warning"]), rec["warning"]
    assert float(rec["W_star"]) >= -float(sin_skew_angle(p.beta0)) * (1 + BOUND_RTOL)


@given(bad=st.sampled_from([0.0, 1e-12, -0.1, 2.0, float("nan")]))
def test_si_rejects_skew_angle_by_name(bad):
    with pytest.raises(ValueError, match=r"^skew_angle "):
        dimensional.contact_parameters(**{**_SI, "skew_angle": bad})


# --- issue 18: TOML values, scheduler addresses, plot cells, sizes ----------------------------------------
toml_scalars = st.one_of(st.none(), st.booleans(), st.integers(-2**70, 2**70),
                         st.floats(allow_nan=True, allow_infinity=True), st.text(max_size=12),
                         st.lists(st.integers(-3, 3), max_size=3))


@given(workers=toml_scalars, out=toml_scalars, num=toml_scalars)
@example(workers=20, out="", num=1e300)            # issue 18 items 7, 9, 14
@example(workers=1, out="s.nc", num=float("inf"))
def test_sweep_config_values_accepted_in_range_or_rejected_by_key(workers, out, num):
    """Any TOML value of run.workers, run.out and a linspace num: a config within the CLI's bounds,
    or one ValueError naming the key -- never another exception, never an empty output path."""
    from dhfield.sweep import config_from_mapping
    from dhfield.sweep.config import MAX_POINTS, max_workers

    run = {k: v for k, v in (("workers", workers), ("out", out)) if v is not None}
    mapping = {"axes": {"beta0": [0.9], "mu": {"linspace": [0.1, 1.0, num]}}, "run": run}
    try:
        cfg = config_from_mapping(mapping)
    except ValueError as exc:
        assert str(exc).startswith(("run.workers", "run.out", "axes.mu", "axes ")), str(exc)
        return
    assert cfg.workers is None or 1 <= cfg.workers <= max_workers()
    assert cfg.out is None or cfg.out.strip()
    assert 1 <= len(cfg.axes["mu"]) <= MAX_POINTS


@given(address=st.one_of(st.text(max_size=30), st.from_regex(r"[a-z]{2,6}://[a-z0-9.:\[\]]{0,20}", fullmatch=True)))
@example(address="inproc://x")
@example(address="tls://127.0.0.1:8786")
@example(address="tcp://127.0.0.1:99999")
def test_scheduler_address_is_tcp_host_port_or_rejected_by_name(address):
    from dhfield.sweep.config import check_scheduler_address, scheduler_host_port

    try:
        check_scheduler_address(address)
    except ValueError as exc:
        assert str(exc).startswith("scheduler "), str(exc)
        return
    host, port = scheduler_host_port(address)
    assert address.startswith("tcp://") and host and 1 <= port <= 65535


@given(centres=st.lists(st.floats(1e-6, 1e12), min_size=1, max_size=30, unique=True), log=st.booleans())
@example(centres=[0.3, 1.0, 3.0, 10.0], log=True)   # issue 17: mu = 0.3 was hidden
def test_plot_cells_cover_every_point_with_positive_width(centres, log):
    from dhfield.io.sweep_maps import cell_edges

    x = np.sort(np.asarray(centres))
    e = cell_edges(x, log=log)
    assert e.size == x.size + 1 and np.all(np.diff(e) > 0)
    assert np.all((e[:-1] <= x) & (x <= e[1:]))         # each point inside its own cell
    if log:
        assert np.all(e > 0)                              # every cell visible on a log axis


@given(nbytes=st.integers(0, 2**60))
def test_sizes_in_messages_are_never_rounded_to_zero(nbytes):
    from dhfield.io import format_size

    text = format_size(nbytes)
    value, unit = text.split()
    assert unit in ("B", "KiB", "MiB", "GiB", "TiB") and (float(value) > 0 or nbytes == 0)
