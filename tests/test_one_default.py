"""One recommended model, stored once (issue 40).

The registry, :data:`dhfield.analysis.compare.RECOMMENDED_MODEL`, is the one place that names the
recommended model.  Every default a user meets must be that model: the command line's ``--model``
(argparse defaults and help), the Python API (``dhfield.pull_off``, ``dhfield.load_curve``,
:mod:`dhfield.analysis.compare`, :mod:`dhfield.analysis.dimensional`, :mod:`dhfield.analysis.fit`, :mod:`dhfield.analysis.spring`,
the sweep), the plots' reference order, and the words "default" next to a model name in the
report's source, the README and the docs.  Also here: the JKR limit named in the report, the
BEM-verified box read back from the stored ground truth, and the warnings raised as Python
warnings of dhfield's own categories.
"""
from __future__ import annotations

import argparse
import inspect
import re
import warnings
from pathlib import Path

import numpy as np
import pytest

import dhfield
from dhfield.analysis import compare, spring as compliance, dimensional, fit, validity
from dhfield.io import sweep_maps as plotting
from dhfield.cli import build_parser, main

ROOT = Path(__file__).resolve().parent.parent
REGISTRY = compare.RECOMMENDED_MODEL
#: Text a user reads: the README, the docs (pages and gallery examples), the report's source,
#: and the package itself (docstrings, help strings).
TEXT_FILES = sorted([ROOT / "README.md", *(ROOT / "docs").rglob("*.rst"), *(ROOT / "docs" / "examples").glob("*.py"),
                     ROOT / "verification" / "report.py", *(ROOT / "verification").glob("sec_*.py"),
                     *(ROOT / "dhfield").rglob("*.py")])
#: Developer pages about past states of the tool (before/after figures), not advice to a user.
HISTORY_FILES = {ROOT / "docs" / "developer" / "figure_gallery.rst", ROOT / "docs" / "changelog.rst"}
_NAME = "(" + "|".join(re.escape(n) for n in sorted(compare.MODEL_NAMES, key=len, reverse=True)) + r")(?![\w-])"
#: The ways a text names a default model: "`X` (the default)", "X (default)", "default: X", "The default `X`",
#: "default model X", "X is the default", ``default="X"``.
DEFAULT_PATTERNS = [
    re.compile(r"`{0,2}" + _NAME + r"`{0,2}\*{0,2}\s*\((?:the\s+)?default\b", re.I),
    re.compile(r"\bdefault(?:\s+model)?(?:\s+is)?\s*[:=]?\s*(?:the\s+)?`{0,2}['\"]?" + _NAME, re.I),
    re.compile(_NAME + r"`{0,2},?\s+(?:is|as)\s+the\s+default\b", re.I),
]


def named_defaults(text):
    """Model names that ``text`` calls the default."""
    return [m.group(1) for p in DEFAULT_PATTERNS for m in p.finditer(" ".join(text.split()))]


def test_registry_names_one_known_model():
    assert REGISTRY in compare.MODEL_NAMES and REGISTRY in compare.CURVE_MODEL_NAMES
    assert compare.DEFAULT_MODEL == REGISTRY == dhfield.RECOMMENDED_MODEL
    assert compare.PAPER_MODEL == "dh-elliptic" != REGISTRY


def test_the_pattern_finds_the_old_wording():
    """The detector catches the sentences issue 40 found (and not a default that is not a model)."""
    assert named_defaults("the paper's `dh-elliptic` (the default) — 0.04 % from") == ["dh-elliptic"]
    assert named_defaults("The default `dh-elliptic` is 3.4–11.7 % weaker") == ["dh-elliptic"]
    assert named_defaults("model (default: md-elliptic, the recommended one; dh-elliptic is the paper's)") \
        == ["md-elliptic"]
    assert named_defaults("p = dhfield.pull_off(mu=1.0, beta0=0.9)   # load control (default)") == []
    assert named_defaults("`dh-elliptic-two-axis` (the default)") == ["dh-elliptic-two-axis"]


def _subparsers(parser):
    action = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return action.choices


def test_cli_defaults_are_the_registry():
    """Every --model of every subcommand defaults to the registry's model and says so in its help."""
    seen = []
    for name, sub in _subparsers(build_parser()).items():
        for action in sub._actions:
            if action.dest == "model":
                seen.append(name)
                assert action.default == REGISTRY, name
                assert set(named_defaults(action.help or "")) <= {REGISTRY}, name
            elif action.dest == "models":
                assert action.default in (None, [REGISTRY], (REGISTRY,)), name
            for hit in named_defaults(action.help or ""):
                assert hit == REGISTRY, (name, action.dest, action.help)
    assert {"pulloff", "curve", "cycle", "fit"} <= set(seen)


def test_plot_reference_order_puts_the_registry_after_the_ground_truth():
    assert plotting.REFERENCE_ORDER[:2] == ("bem-adhesive", REGISTRY)
    import xarray as xr

    ds = xr.Dataset(coords={"model": ["dh-elliptic", "jkr-elliptic", "dh-elliptic-two-axis", REGISTRY]})
    assert plotting.default_reference(ds) == REGISTRY
    ref = next(a for a in _subparsers(build_parser())["plot"]._actions if a.dest == "reference")
    listed = [n for n in re.findall(r"[a-z][a-z-]+", ref.help) if n in plotting.REFERENCE_ORDER]
    assert listed == list(plotting.REFERENCE_ORDER)


@pytest.mark.parametrize("func", [dhfield.pull_off, dhfield.load_curve, compare.pull_off, compare.load_curve,
                                  dimensional.pull_off_force, dimensional.load_curve_si,
                                  fit.fit_work_of_adhesion, fit.fit_curve,
                                  compliance.pull_off_force_under_spring, compliance.loading_cycle_si],
                         ids=lambda f: f"{f.__module__}.{f.__name__}")
def test_python_defaults_are_the_registry(func):
    assert inspect.signature(func).parameters["model"].default == REGISTRY


def test_top_level_pull_off_answers_with_the_registry_and_the_paper_by_name():
    """issue 40: the first call of the tour answered with the paper's model, 33 % weak, without a word."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", validity.DhfieldWarning)
        rec = dhfield.pull_off(beta0=0.4826, mu=5.0)
        paper = dhfield.pull_off("dh-elliptic", beta0=0.4826, mu=5.0)
        curve = dhfield.load_curve(beta0=0.4826, mu=5.0, n=5)
    assert rec.model == REGISTRY == curve.model
    assert float(rec.W_star) == float(compare.MODELS[REGISTRY](np.asarray(0.4826), np.asarray(5.0)).W_star)
    assert paper.model == "dh-elliptic" and "departs from the recommended model" in paper.warning


def test_dimensional_pull_off_force_answers_with_the_registry():
    p = dimensional.contact_parameters(1.8e6, 0.49, 1.8e6, 0.49, 3e-3, np.pi / 2, 0.045, 0.3e6)
    assert dimensional.pull_off_force(p).model == REGISTRY


def test_sweep_default_model_is_the_registry():
    from dhfield.sweep.config import SweepConfig

    assert SweepConfig.__dataclass_fields__["models"].default == (REGISTRY,)


@pytest.mark.parametrize("path", [p for p in TEXT_FILES if p not in HISTORY_FILES],
                         ids=lambda p: str(p.relative_to(ROOT)))
def test_text_names_no_other_default(path):
    """README, docs, the report's source and the package's own text call no other model the default."""
    hits = named_defaults(path.read_text(encoding="utf-8"))
    assert set(hits) <= {REGISTRY}, f"{path.relative_to(ROOT)} calls {sorted(set(hits) - {REGISTRY})} the default"


def test_report_names_the_jkr_limit_right():
    """The JKR limit of an elliptical contact is GVG's energy minimum; JG is 2.5 % weaker at beta0 = 0.5."""
    from verification import sec_models

    text = (ROOT / "verification" / "sec_models.py").read_text(encoding="utf-8")
    assert "limit every elliptical DH closure must reach" not in text
    jkr = sec_models.jkr_limits()
    tab = {(m, b): {n: -0.7 for n in ("dh-elliptic", "dh-elliptic-jkr-beta", "jkr-elliptic", "dh-circular", REGISTRY)}
           for m in sec_models.MU_TABLE for b in sec_models.BETA0}
    tab[(sec_models.MU_FIG8, 1.0)] = {"dh-circular": -0.74, "jkr": -0.75}
    _, guide = sec_models.verdict_lines(tab, jkr)
    limit = next(g for g in guide if "JKR side" in g)
    assert "JKR limit of an elliptical contact is `jkr-elliptic-energy`" in limit
    w_jg, w_gvg = jkr[0.5]
    assert f"{100 * (1 - w_jg / w_gvg):.1f} % weaker than it at β0 = 0.5" in limit
    assert 0.02 < 1 - w_jg / w_gvg < 0.03  # JG's one shape condition: weaker than the energy minimum
    near = next(g for g in guide if "Near-circular" in g)
    assert f"`{REGISTRY}` (the default" in near and "`dh-elliptic`, available by name" in near


def test_bem_verified_box_is_the_stored_ground_truth():
    """The box of the recommended model's warning is the extent of data/adhesive_ground_truth_extended.nc."""
    xr = pytest.importorskip("xarray")
    with xr.open_dataset(ROOT / "data" / "adhesive_ground_truth_extended.nc") as ds:
        ok = np.isfinite(ds["W_star_truth"].values)
        b = ds["beta0"].values[ok.any(axis=1)]
        m = ds["mu"].values[ok.any(axis=0)]
    assert validity.BEM_VERIFIED_BETA0 == (float(b.min()), float(b.max()))
    assert validity.BEM_VERIFIED_MU == (float(m.min()), float(m.max()))
    assert validity.VALIDITY_RANGES[REGISTRY] == (validity.BEM_VERIFIED_BETA0, validity.BEM_VERIFIED_MU)


def test_recommended_model_warns_outside_the_box_as_a_python_warning():
    """issue 40: at 10 deg (beta0 = 0.047) and mu = 19.5 the recommended model printed an empty warning."""
    with pytest.warns(validity.OutsideVerifiedDomainWarning, match="outside the BEM-verified box") as rec_w:
        rec = dhfield.pull_off(beta0=0.047, mu=19.5)
    assert rec.warning and rec.warning == str(rec_w[0].message)
    assert issubclass(validity.OutsideVerifiedDomainWarning, dhfield.DhfieldWarning)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert dhfield.pull_off(beta0=0.5, mu=1.0).warning == ""  # inside: silent
    with pytest.warns(validity.OutsideVerifiedDomainWarning, match="1 of 2 points warn"):
        arr = dhfield.pull_off(beta0=[0.5, 0.047], mu=[1.0, 19.5])
    assert arr.warning[0] == "" and arr.warning[1]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert compare.pull_off(beta0=0.047, mu=19.5, warn=False).warning  # in the record only


def test_cli_prints_the_warning_once_and_never_an_empty_one(capsys):
    assert main(["pulloff", "--beta0", "0.047", "--mu", "19.5", "--json"]) == 0
    err = capsys.readouterr().err
    assert err.count("dhfield: warning:") == 1 and "outside the BEM-verified box" in err
    assert main(["pulloff", "--beta0", "0.5", "--mu", "1", "--json"]) == 0
    assert "warning" not in capsys.readouterr().err
    assert main(["pulloff", "--beta0", "0.5", "--mu", "1"]) == 0  # the text table: no empty warning row
    out = capsys.readouterr()
    assert "warning" not in out.err and not any(line.split()[:1] == ["warning"] for line in out.out.splitlines())
    assert main(["pulloff", "--beta0", "0.047", "--mu", "19.5"]) == 0
    assert any(line.startswith("warning ") and "BEM-verified box" in line for line in capsys.readouterr().out.splitlines())


PDMS_WRONG_UNITS = ["--youngs-modulus", "1.8", "--poisson-ratio", "0.49", "--cylinder-radius", "3",
                    "--skew-angle-deg", "60", "--work-of-adhesion", "45", "--adhesive-stress", "0.3"]


def test_cli_asks_did_you_mean_for_implausible_si_inputs(capsys):
    """issue 40: E = 1.8 Pa, R = 3 m, dgamma = 45 J/m^2 gave -4630 N without a word."""
    assert main(["pulloff", *PDMS_WRONG_UNITS, "--json"]) == 0
    err = capsys.readouterr().err
    line = next(x for x in err.splitlines() if "implausible" in x)
    assert line.startswith("dhfield: warning: ")
    for said in ("youngs_modulus_1 = 1.8 Pa", "did you mean MPa?", "cylinder_radius = 3 m", "did you mean mm?",
                 "work_of_adhesion = 45 J m^-2", "did you mean mJ m^-2?"):
        assert said in line


@pytest.mark.parametrize("kw, said", [
    (dict(youngs_modulus_1=500.0), "youngs_modulus_1 = 500 Pa is below"),
    (dict(youngs_modulus_2=2e12), "youngs_modulus_2 = 2e+12 Pa is above"),
    (dict(cylinder_radius=1.5), "cylinder_radius = 1.5 m is above"),
    (dict(work_of_adhesion=12.0), "work_of_adhesion = 12 J m^-2 is above"),
    (dict(max_adhesive_stress=2e11), "max_adhesive_stress = 2e+11 Pa is above"),
])
def test_implausible_si_inputs_warn_each_limit(kw, said):
    base = dict(youngs_modulus_1=1.8e6, poisson_ratio_1=0.49, youngs_modulus_2=1.8e6, poisson_ratio_2=0.49,
                cylinder_radius=3e-3, skew_angle=np.pi / 3, work_of_adhesion=0.045, max_adhesive_stress=0.3e6)
    args = {**base, **kw}
    with pytest.warns(validity.ImplausibleInputWarning, match="did you mean") as caught:
        try:
            dimensional.contact_parameters(**args)
        except ValueError:  # some of these leave the models' mu range: the warning came first
            pass
    assert said in str(caught[0].message)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        dimensional.contact_parameters(**base)  # a real PDMS contact: silent


def test_implausible_principal_radius_warns_on_the_smaller_radius():
    with pytest.warns(validity.ImplausibleInputWarning, match=r"r_minor\) = 2 m is above"):
        dimensional.contact_parameters_from_principal_radii(1.8e6, 0.49, 1.8e6, 0.49, 5.0, 2.0, 0.045, 0.3e6)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # R' = 66 R_c at 10 deg: a long principal radius is geometry, not a unit slip
        r1, r2 = dimensional.crossed_cylinder_radii(0.02, 0.02, np.radians(10))
        assert r1 > 1.0
        dimensional.contact_parameters_from_principal_radii(1.8e6, 0.49, 1.8e6, 0.49, r1, r2, 0.045, 0.3e6)
