"""The shape of the library, measured (issue 16, "Must show").

Prints, for the dhfield package under ``--root`` (default: this checkout):

* the largest number of parameters of any function in ``dhfield/`` (target <= 10), and the
  functions above the target;
* the number of pull-off result types of the analytic models (target 1): every public function
  outside ``dhfield/bem`` whose name starts with ``pull_off`` is called at beta0 = 0.9, mu = 1
  (SI functions with a PDMS-like contact, a machine stiffness K* = 1) with its parameters filled by
  name; a result type is the returned class with, for a mapping, its set of keys (scalar/array
  results, e.g. a force, are not records and are not counted); a tuple is named by the types it
  holds; then with the BEM's (``adhesive_start.adhesive_pull_off`` at N = 32 and
  ``bem_compliance.bem_pull_off_under_spring`` at K* = 1 on an N = 32 branch), every model's;
* the number of minimum-search implementations outside ``dhfield/bem`` (target 1): functions that
  decide which sample is the minimum: ``np.argmin``/``nanargmin`` on samples, or a discrete
  local-minimum test on neighbouring samples (a comparison of slices such as
  ``v[1:-1] <= v[:-2]`` or ``f[1:] >= f[:-1]``, or ``f[i - 1] < f[i]``); of those, the local-minimum rules (the neighbour
  comparisons, in all of ``dhfield/``: one rule and one tie rule is the target).  Listed apart,
  not counted as searches: the *refinements*, functions that polish a bracket the search gave,
  with scipy's ``find_minimum``/``minimize_scalar``/``fminbound``/``golden``/``brent`` or
  ``find_root`` on a derivative (a callable whose name starts with ``d`` or ``slope``).  Before
  issue 16's one rule (commit cb04ac6) a refinement was counted as a search;
* the number of ``dhfield.core.validation`` calls on one ``dhfield pulloff --beta0 0.9 --mu 1 --json``
  (outermost calls only, counted per parameter name; target: each input once), and the same count,
  each in a fresh process, on ``dhfield curve --beta0 0.9 --mu 1 --json`` and ``dhfield compare
  --beta0 0.9 --mu 1`` and ``dhfield pulloff`` with SI inputs (``check_grid_point`` checks beta0, mu and
  control together);
* whether ``dhfield/bem/`` imports an analytic model module;
* the number of load-curve result types (target 1): every function outside ``dhfield/bem`` whose
  name starts with ``load_curve``, called as the pull-off functions are (:data:`_CURVE_PROBE`);
* the library's line count.

Usage::

    python -m verification.shape                 # this checkout
    python -m verification.shape --root /tmp/an-base
"""
from __future__ import annotations

import argparse
import ast
import json
import os
import subprocess
import sys
from pathlib import Path

#: Modules of the analytic models (the BEM must not import them).
ANALYTIC_MODULES = {"model", "compare", "closure", "dh_circular", "jkr", "dmt", "maugis_dugdale", "jkr_elliptic",
                    "dimensional", "transition", "validity", "analytic", "gvg", "jkr_elliptic_gvg"}
SEARCH_CALLS = {"argmin", "nanargmin"}
REFINE_CALLS = {"find_minimum", "minimize_scalar", "fminbound", "golden", "brent"}


def _functions(root: Path):
    for path in sorted((root / "dhfield").rglob("*.py")):
        tree = ast.parse(path.read_text(), str(path))
        for node in ast.walk(tree):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                yield path.relative_to(root), node


def _n_params(fn) -> int:
    a = fn.args
    n = len(a.posonlyargs) + len(a.args) + len(a.kwonlyargs) + (a.vararg is not None) + (a.kwarg is not None)
    if a.args and a.args[0].arg in ("self", "cls"):
        n -= 1
    return n


def _call_name(call):
    f = call.func
    return f.attr if isinstance(f, ast.Attribute) else f.id if isinstance(f, ast.Name) else None


def _has_neighbour_rule(fn) -> bool:
    """A discrete local-minimum test: a sample compared with its neighbours (v[1:-1] <= v[:-2],
    f[1:] >= f[:-1], f[i] <= f[i - 1])."""
    for node in ast.walk(fn):
        if isinstance(node, ast.Compare) and isinstance(node.ops[0], (ast.LtE, ast.Lt, ast.GtE, ast.Gt)):
            sides = [node.left, *node.comparators]
            if all(isinstance(q, ast.Subscript) for q in sides):
                src = ast.unparse(node)
                if (("1:-1" in src and ":-2" in src) or ("1:]" in src and ":-1]" in src)
                        or ("i - 1]" in src or "i + 1]" in src)):
                    return True
    return False


def _is_min_search(fn) -> bool:
    """Decides the minimum's sample: a neighbour rule or an argmin over samples."""
    if _has_neighbour_rule(fn):
        return True
    return any(isinstance(node, ast.Call) and _call_name(node) in SEARCH_CALLS for node in ast.walk(fn))


def _is_refinement(fn) -> bool:
    """Polishes a bracket: a scalar minimiser, or a root of a derivative (d*, slope*)."""
    for node in ast.walk(fn):
        if isinstance(node, ast.Call):
            name = _call_name(node)
            if name in REFINE_CALLS:
                return True
            if name == "find_root" and node.args and isinstance(node.args[0], ast.Name) \
                    and node.args[0].id.startswith(("d", "slope")):
                return True
    return False


def _top_level(fn_nodes):
    """Drop functions nested in a function already listed (a closure of the search is the search)."""
    out = []
    for path, fn in fn_nodes:
        if not any(p == path and f is not fn and f.lineno <= fn.lineno <= f.end_lineno for p, f in fn_nodes):
            out.append((path, fn))
    return out


def static(root: Path) -> dict:
    params = [(str(p), fn.name, _n_params(fn), fn.lineno) for p, fn in _functions(root)]
    params.sort(key=lambda t: -t[2])
    searches = _top_level([(p, fn) for p, fn in _functions(root)
                           if not str(p).startswith("dhfield/bem") and _is_min_search(fn)])
    rules = _top_level([(p, fn) for p, fn in _functions(root) if _has_neighbour_rule(fn)])
    refinements = _top_level([(p, fn) for p, fn in _functions(root)
                              if not str(p).startswith("dhfield/bem") and _is_refinement(fn)])
    bem_imports = []
    for path in sorted((root / "dhfield" / "bem").rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            mods = []
            if isinstance(node, ast.ImportFrom):
                if node.level >= 2 and node.module:
                    mods = [node.module.split(".")[0]]
                elif node.level >= 2:
                    mods = [a.name for a in node.names]
                elif node.module and node.module.startswith("dhfield."):
                    mods = [node.module.split(".")[1]]
            elif isinstance(node, ast.Import):
                mods = [a.name.split(".")[1] for a in node.names if a.name.startswith("dhfield.")]
            bem_imports += [f"{path.relative_to(root)}:{node.lineno} {m}" for m in mods if m in ANALYTIC_MODULES]
    lines = nonblank = 0
    for path in (root / "dhfield").rglob("*.py"):
        text = path.read_text().splitlines()
        lines += len(text)
        nonblank += sum(1 for t in text if t.strip())
    return {"max_params": params[0][2], "over_10": [f"{p}:{ln} {n} ({k})" for p, n, k, ln in params if k > 10],
            "min_searches": [f"{p}:{fn.lineno} {fn.name}" for p, fn in searches],
            "min_rules": [f"{p}:{fn.lineno} {fn.name}" for p, fn in rules],
            "refinements": [f"{p}:{fn.lineno} {fn.name}" for p, fn in refinements],
            "bem_imports_analytic": bem_imports, "lines": lines, "nonblank_lines": nonblank}


#: Probe code shared by the pull-off and load-curve probes: the result type of an answer, and a call of every
#: function outside ``dhfield/bem`` and ``dhfield/cli`` whose name starts with a prefix, its parameters filled by
#: name from ``values``.
_CALLER = r'''
def result_type(r):
    # the result type of an answer (None: a scalar or array, not a record)
    t = type(r)
    if t.__module__ == "numpy" or t in (float, int):
        return None
    key = f"{t.__module__}.{t.__qualname__}"
    if isinstance(r, dict):
        key += "{" + ",".join(sorted(r)) + "}"
    elif isinstance(r, tuple) and not hasattr(r, "_fields"):
        key += "(" + ", ".join(f"{type(x).__module__}.{type(x).__qualname__}" for x in r) + ")"
    return key


def probe(prefix, values):
    # ({result type: [functions]}, [functions not called]) of every function named prefix*
    import dhfield
    types, skipped = {}, []
    names = sorted(m.name for m in pkgutil.walk_packages(dhfield.__path__, "dhfield.")
                   if not m.name.startswith(("dhfield.bem", "dhfield.cli")))
    for modname in names:
        try:
            mod = importlib.import_module(modname)
        except Exception:  # noqa: BLE001
            continue
        for fname, f in sorted(vars(mod).items()):
            if not (fname.startswith(prefix) and inspect.isfunction(f) and f.__module__ == modname):
                continue
            kw, ok = {}, True
            for p in inspect.signature(f).parameters.values():
                if p.name in values:
                    kw[p.name] = values[p.name]
                elif p.default is inspect.Parameter.empty and p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD):
                    ok = False
            if not ok:
                skipped.append(f"{modname}.{fname}")
                continue
            try:
                with contextlib.redirect_stderr(io.StringIO()):
                    r = f(**kw)
            except Exception as exc:  # noqa: BLE001
                skipped.append(f"{modname}.{fname} ({type(exc).__name__}: {exc})"[:160])
                continue
            key = result_type(r)
            if key is not None:
                types.setdefault(key, []).append(f"{modname}.{fname}")
    return types, skipped
'''

_PROBE = r'''
import functools, importlib, inspect, io, contextlib, json, pkgutil, sys
import dhfield.core.validation as V

counts, depth = {}, [0]
def wrap(name, f):
    @functools.wraps(f)
    def g(*a, **k):
        if depth[0] == 0:
            pname = "control" if name == "check_control" else "beta0, mu" if name == "check_grid_point" else (
                a[0] if a and isinstance(a[0], str) else "?")
            counts[f"{name}({pname})"] = counts.get(f"{name}({pname})", 0) + 1
        depth[0] += 1
        try:
            return f(*a, **k)
        finally:
            depth[0] -= 1
    return g
for n, f in list(vars(V).items()):
    if callable(f) and n.startswith("check") and getattr(f, "__module__", "") == V.__name__:
        setattr(V, n, wrap(n, f))

''' + _CALLER + r'''
import dhfield
from dhfield.cli import main
with contextlib.redirect_stdout(io.StringIO()):
    rc = main(["pulloff", "--beta0", "0.9", "--mu", "1", "--json"])
validation = dict(counts)

from dhfield.analysis.dimensional import contact_parameters
params = contact_parameters(1e6, 0.5, 1e6, 0.5, 0.01, 1.2, 0.05, 2e5)
values = {"mu": 1.0, "beta0": 0.9, "lam": 1.1272, "control": "load", "model": "dh-elliptic",
          "effective_radius": 1e-2, "reduced_modulus": 1.33e6, "work_of_adhesion": 0.05,
          "max_adhesive_stress": 2e5, "params": params, "parameters": params, "machine_stiffness": 1.0}
types, skipped = probe("pull_off", values)
# the BEM's pull-offs (the smallest grid that runs in seconds): load control, and under a spring K* = 1
from dhfield.analysis.bem_start import adhesive_pull_off
from dhfield.analysis.bem_spring import bem_pull_off_under_spring, bem_unloading_branch
bem_types = {}
for fname, call in (("dhfield.analysis.bem_start.adhesive_pull_off",
                     lambda: adhesive_pull_off(beta0=0.9, mu=1.0, n=32, progress=False)),
                    ("dhfield.analysis.bem_spring.bem_pull_off_under_spring",
                     lambda: bem_pull_off_under_spring(bem_unloading_branch(beta0=0.9, mu=1.0, n=32), 1.0))):
    try:
        with contextlib.redirect_stderr(io.StringIO()):
            key = result_type(call())
    except Exception as exc:  # noqa: BLE001
        skipped.append(f"{fname} ({type(exc).__name__}: {exc})"[:160])
        continue
    if key is not None:
        bem_types.setdefault(key, []).append(fname)
print(json.dumps({"rc": rc, "validation": validation, "types": types, "bem_types": bem_types, "skipped": skipped}))
'''


#: Further CLI calls whose _validation calls are counted, each in a fresh process (no cached state).
COUNTED_CALLS = (["curve", "--beta0", "0.9", "--mu", "1", "--json"], ["compare", "--beta0", "0.9", "--mu", "1"],
                 # SI inputs (dhfield.analysis.dimensional): each SI input once, then the grid point they give
                 ["pulloff", "--youngs-modulus", "1e6", "--poisson-ratio", "0.5", "--cylinder-radius", "0.01",
                  "--skew-angle-deg", "60", "--work-of-adhesion", "0.05", "--adhesive-stress", "2e5", "--json"])

_COUNT = _PROBE.split("validation = dict(counts)")[0].replace(
    'main(["pulloff", "--beta0", "0.9", "--mu", "1", "--json"])', "main(json.loads(sys.argv[1]))") + \
    'print(json.dumps({"rc": rc, "validation": dict(counts)}))\n'


def _run_probe(root: Path, code: str, *args) -> dict:
    """The JSON last line printed by probe ``code`` run in a fresh process on the checkout at ``root``."""
    env = {**os.environ, "PYTHONPATH": str(root)}
    out = subprocess.run([sys.executable, "-c", code, *args], env=env, cwd=root, capture_output=True, text=True,
                         check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def counted(root: Path, argv) -> dict:
    """``{"rc", "validation"}`` of one CLI call ``argv`` in a fresh process."""
    return _run_probe(root, _COUNT, json.dumps(argv))


def dynamic(root: Path) -> dict:
    return _run_probe(root, _PROBE)


#: The load-curve probe (issue 16, "one load-curve type"): every function outside ``dhfield/bem`` and
#: ``dhfield/cli`` whose name starts with ``load_curve`` is called as the pull-off probe calls the pull-off
#: functions, its parameters filled by name (beta0 = 0.9, mu = 1; SI functions with the same PDMS-like
#: contact, contact sizes of about one c_r); a result type is the returned class (with its keys for a dict,
#: its element types for a plain tuple).
_CURVE_PROBE = r'''
import contextlib, importlib, inspect, io, json, pkgutil
import numpy as np
''' + _CALLER + r'''
from dhfield.analysis.dimensional import contact_parameters

params = contact_parameters(1e6, 0.5, 1e6, 0.5, 0.01, 1.2, 0.05, 2e5)
size = np.array([1e-4, 3e-4])  # [m], c_r ~ 1.6e-4 m
values = {"mu": 1.0, "beta0": 0.9, "lam": 1.1272, "model": "dh-elliptic", "a_star": np.array([0.5, 1.0]),
          "a_maugis": np.array([0.5, 1.0]), "w_star": np.array([0.0, 1.0]), "contact_radius": size,
          "semi_major": size, "effective_radius": 1e-2, "reduced_modulus": 1.33e6, "work_of_adhesion": 0.05,
          "max_adhesive_stress": 2e5, "params": params}
types, skipped = probe("load_curve", values)
print(json.dumps({"types": types, "skipped": skipped}))
'''


def curve_types(root: Path) -> dict:
    """The load-curve result types (:data:`_CURVE_PROBE`) of the checkout at ``root``."""
    return _run_probe(root, _CURVE_PROBE)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--root", default=str(Path(__file__).resolve().parents[1]))
    args = ap.parse_args(argv)
    root = Path(args.root).resolve()
    s, d = static(root), dynamic(root)
    print(f"shape of {root}")
    print(f"largest number of parameters of a function: {s['max_params']} (target <= 10); "
          f"{len(s['over_10'])} above 10")
    for x in s["over_10"]:
        print(f"    {x}")
    print(f"pull-off result types (analytic, outside dhfield/bem): {len(d['types'])} (target 1)")
    for k, v in d["types"].items():
        print(f"    {k}: {', '.join(v)}")
    if d["skipped"]:
        print(f"    (not called: {'; '.join(d['skipped'])})")
    every = {k: d["types"].get(k, []) + d["bem_types"].get(k, []) for k in {**d["types"], **d["bem_types"]}}
    print(f"pull-off result types (every model, the BEM included): {len(every)} (target 1)")
    for k, v in d["bem_types"].items():
        print(f"    {k}: {', '.join(v)}")
    print(f"minimum-search implementations (outside dhfield/bem): {len(s['min_searches'])} (target 1)")
    for x in s["min_searches"]:
        print(f"    {x}")
    print(f"local-minimum rules (a sample compared with its neighbours, all of dhfield/): {len(s['min_rules'])} "
          f"(target 1)")
    for x in s["min_rules"]:
        print(f"    {x}")
    print(f"refinements of a bracketed minimum (outside dhfield/bem; not searches): {len(s['refinements'])}")
    for x in s["refinements"]:
        print(f"    {x}")
    total = sum(d["validation"].values())
    print(f"_validation calls on one `dhfield pulloff --beta0 0.9 --mu 1 --json`: {total} "
          f"(exit {d['rc']}; target: each input once)")
    for k, v in sorted(d["validation"].items()):
        print(f"    {v:3d}  {k}")
    for argv in COUNTED_CALLS:
        c = counted(root, argv)
        print(f"_validation calls on one `dhfield {' '.join(argv)}`: {sum(c['validation'].values())} "
              f"(exit {c['rc']}; target: each input once)")
        for k, v in sorted(c["validation"].items()):
            print(f"    {v:3d}  {k}")
    print(f"dhfield/bem imports an analytic model: {'yes' if s['bem_imports_analytic'] else 'no'}")
    for x in s["bem_imports_analytic"]:
        print(f"    {x}")
    c = curve_types(root)  # the load-curve result types (issue 16: one load-curve type)
    print(f"load-curve result types (functions load_curve*, outside dhfield/bem): {len(c['types'])} (target 1)")
    for k, v in c["types"].items():
        print(f"    {k}: {', '.join(v)}")
    if c["skipped"]:
        print(f"    (not called: {'; '.join(c['skipped'])})")
    print(f"library lines (dhfield/**/*.py): {s['lines']} ({s['nonblank_lines']} non-blank)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
