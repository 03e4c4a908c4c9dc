"""The layers of ``dhfield`` are its folders: who may import whom.

Each module of ``dhfield`` sits in one folder of :data:`LAYERS` (the package's ``__init__`` is
the facade); the import statements of its source, read with :mod:`ast` (module level and inside
functions alike, so a lazy import counts), may reach only the folders before it, as the package
map in ``dhfield/__init__.py`` states.  No module sits flat in ``dhfield/``.
"""
from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PKG = ROOT / "dhfield"

#: The layers, bottom up: each is a folder of dhfield.
LAYERS = ("core", "models", "bem", "analysis", "io", "sweep", "cli")
#: What each layer may import from dhfield (besides itself).
MAY_IMPORT = {
    "core": set(),
    "models": {"core"},
    "bem": {"core"},
    "analysis": {"core", "models", "bem"},
    "io": {"core", "models", "bem", "analysis"},
    "sweep": {"core", "models", "bem", "analysis", "io"},
    "cli": {"core", "models", "bem", "analysis", "io", "sweep"},
}
CORE = ("core", "models", "bem", "analysis")
#: Third-party packages only the edges (io, sweep, cli) may import.
EDGE_ONLY_PACKAGES = {"xarray", "matplotlib", "pandas", "netCDF4", "dask", "distributed"}
#: The one lazy import the bem facade makes (inside a function): the start chosen from the
#: analytic models, forwarded as ``dhfield.bem.adhesive_pull_off``.
BEM_FACADE_LAZY = {"analysis.bem_start"}


def _modules():
    """{dotted name relative to dhfield ('' for the package itself): path}."""
    out = {}
    for path in sorted(PKG.rglob("*.py")):
        parts = list(path.relative_to(PKG).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = path
    return out


MODULES = _modules()


def _layer(name):
    """The folders a module (dotted, relative to dhfield) sits in: one, or none if it is flat."""
    top = name.split(".")[0]
    return [top] if top in LAYERS and "." in name or name in LAYERS else []


def _imports(name, path):
    """(target, top_level) pairs: dhfield modules by relative name, others as 'ext:<package>'."""
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    package = name.split(".") if path.name == "__init__.py" else name.split(".")[:-1]
    package = [p for p in package if p]
    top = {id(n) for n in tree.body}
    out = []

    def resolve(base, names):
        """Relative names: a submodule if it is one, else the module that holds the name."""
        for alias in names:
            full = ".".join([*base, alias]) if base else alias
            yield full if full in MODULES else ".".join(base)

    for node in ast.walk(tree):
        at_top = id(node) in top
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name == "dhfield" or alias.name.startswith("dhfield."):
                    out.append((alias.name[len("dhfield."):] if "." in alias.name else "", at_top))
                else:
                    out.append(("ext:" + alias.name.split(".")[0], at_top))
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[: len(package) - (node.level - 1)] if node.level > 1 else list(package)
                if node.module:
                    base = [*base, *node.module.split(".")]
                for target in resolve(base, [a.name for a in node.names]):
                    out.append((target, at_top))
            elif node.module and (node.module == "dhfield" or node.module.startswith("dhfield.")):
                base = node.module.split(".")[1:]
                for target in resolve(base, [a.name for a in node.names]):
                    out.append((target, at_top))
            elif node.module:
                out.append(("ext:" + node.module.split(".")[0], at_top))
    return out


def _edges():
    """(importer, imported, top_level) over every dhfield module, imported a dhfield module."""
    return [(name, target, top) for name, path in MODULES.items() for target, top in _imports(name, path)
            if not target.startswith("ext:") and target in MODULES and target != name]


def test_every_module_is_in_exactly_one_layer():
    """No flat module: every module of dhfield but the facade sits in a layer's folder."""
    wrong = [name for name in MODULES if name and len(_layer(name)) != 1]
    assert not wrong, f"modules outside the layers' folders (move them into one of {LAYERS}): {wrong}"
    assert {name.split(".")[0] for name in MODULES if name} == set(LAYERS)


def test_the_map_names_every_layer():
    """The map in dhfield/__init__.py's docstring names every layer's folder."""
    doc = ast.get_docstring(ast.parse((PKG / "__init__.py").read_text(encoding="utf-8")))
    missing = [f"{m}/" for m in LAYERS if f"{m}/" not in doc]
    assert not missing, f"the package map in dhfield/__init__.py does not name {missing}"


@pytest.mark.parametrize("layer", list(LAYERS))
def test_layer_imports_only_what_the_map_allows(layer):
    allowed = MAY_IMPORT[layer] | {layer}
    bad = []
    for importer, target, top in _edges():
        if not importer or _layer(importer) != [layer] or not target:
            continue
        if importer == "bem" and not top and target in BEM_FACADE_LAZY:
            continue  # the facade's one lazy forward (documented in the map)
        (target_layer,) = _layer(target)
        if target_layer not in allowed:
            bad.append(f"dhfield.{importer} imports dhfield.{target} ({target_layer})")
    assert not bad, f"{layer} may import {sorted(allowed)} only:\n" + "\n".join(bad)


def test_bem_imports_no_analytic_model():
    """dhfield/bem/ imports no model, nor the registry (only the facade's lazy forward of
    analysis.bem_start, inside a function)."""
    bad = [f"dhfield.{i} imports dhfield.{t}" for i, t, top in _edges()
           if _layer(i) == ["bem"] and _layer(t) and _layer(t)[0] in ("models", "analysis")
           and (top or i != "bem" or t not in BEM_FACADE_LAZY)]
    assert not bad, "\n".join(bad)


def test_numpy_core_imports_no_xarray_or_matplotlib():
    bad = [f"dhfield.{name} imports {t[4:]}" for name, path in MODULES.items()
           if name and _layer(name)[0] in CORE
           for t, _top in _imports(name, path) if t.startswith("ext:") and t[4:] in EDGE_ONLY_PACKAGES]
    assert not bad, "\n".join(bad)


def test_no_core_module_imports_an_edge():
    bad = [f"dhfield.{i} imports dhfield.{t}" for i, t, _top in _edges()
           if i and _layer(i)[0] in CORE and _layer(t)[0] not in CORE]
    assert not bad, "\n".join(bad)


def test_the_checker_sees_imports():
    """The rules are not vacuous: known imports are found (module level, relative, lazy)."""
    edges = {(i, t) for i, t, _top in _edges()}
    assert ("models.dh_elliptic", "models.dh_elliptic_adhesion") in edges and ("cli.solve", "bem") in edges
    assert ("bem", "analysis.bem_start") in edges  # the facade's lazy forward, inside a function
    ext = {t for t, _ in _imports("io", MODULES["io"])}
    assert "ext:xarray" in ext


def test_no_module_sits_flat_in_the_package():
    flat = sorted(p.name for p in PKG.glob("*.py") if p.name != "__init__.py")
    assert not flat, f"flat modules in dhfield/: {flat}"


@pytest.mark.parametrize("old", ["model", "compare", "elliptic_transition", "_validation", "plotting"])
def test_old_flat_import_paths_reach_the_moved_module(old):
    """``import dhfield.<old>`` (before the layers had folders) is the module at its new place,
    with a DeprecationWarning naming that place."""
    import importlib
    import sys

    import dhfield

    new = f"dhfield.{dhfield.MOVED_MODULES[old]}"
    sys.modules.pop(f"dhfield.{old}", None)
    with pytest.warns(DeprecationWarning, match=re.escape(new)):
        module = importlib.import_module(f"dhfield.{old}")
    assert module is importlib.import_module(new)


def test_every_moved_module_exists():
    import dhfield

    missing = [new for new in dhfield.MOVED_MODULES.values()
               if not (PKG / (new.replace(".", "/") + ".py")).is_file()]
    assert not missing and not set(dhfield.MOVED_MODULES) & {p.stem for p in PKG.glob("*.py")}
