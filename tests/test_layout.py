"""The package map of ``dhfield/__init__.py`` (and the README) holds: who may import whom.

Each module of ``dhfield`` belongs to one layer of :data:`LAYERS`; the import statements of its
source, read with :mod:`ast` (module level and inside functions alike, so a lazy import counts),
must follow the rules stated in the map.  A new module must be placed in a layer here and in
the map, or :func:`test_every_module_is_in_exactly_one_layer` fails.
"""
from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PKG = ROOT / "dhfield"

#: The layers of the map, bottom up.  Modules by name relative to ``dhfield``; a trailing
#: ``/`` names a whole subpackage.
LAYERS = {
    "foundations": ("_validation", "_memory", "schema", "records", "elliptic", "geometry",
                    "pull_off_search", "_adhesion", "transition", "dugdale_separation"),
    "analytic": ("hertz", "double_hertz", "adhesion", "model", "_rays", "periphery", "eq30", "closure"),
    "comparison": ("jkr", "dmt", "dh_circular", "maugis_dugdale", "jkr_elliptic", "jkr_elliptic_energy",
                   "elliptic_transition"),
    "front": ("compare", "validity", "model_error", "_truth_table", "dimensional", "compliance", "fit",
              "adhesion_map", "force_vs_angle"),
    "bem": ("bem/",),
    "bridge": ("adhesive_start", "fields", "field_sampling", "field_metrics", "polar", "refinement",
               "bem_compliance", "solve_progress"),
    "io": ("io/",),
    "plotting": ("plotting",),
    "sweep": ("sweep/",),
    "cli": ("cli/",),
}
#: What each layer may import from dhfield (besides itself).
MAY_IMPORT = {
    "foundations": set(),
    "analytic": {"foundations"},
    "comparison": {"foundations"},
    "front": {"foundations", "analytic", "comparison"},
    "bem": {"foundations"},
    "bridge": {"foundations", "analytic", "comparison", "front", "bem"},
    "io": {"foundations", "analytic", "comparison", "front", "bem", "bridge"},
    "plotting": {"io"},
    "sweep": {"foundations", "analytic", "comparison", "front", "bem", "bridge", "io"},
    "cli": {"foundations", "analytic", "comparison", "front", "bem", "bridge", "io", "plotting", "sweep"},
}
CORE = ("foundations", "analytic", "comparison", "front", "bem", "bridge")
#: Third-party packages only the edges (io, plotting, sweep, cli) may import.
EDGE_ONLY_PACKAGES = {"xarray", "matplotlib", "pandas", "netCDF4", "dask", "distributed"}
#: The one lazy import the bem facade makes (inside a function): the start chosen from the
#: analytic models, forwarded as ``dhfield.bem.adhesive_pull_off``.
BEM_FACADE_LAZY = {"adhesive_start"}


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
    hits = [layer for layer, members in LAYERS.items() for m in members
            if (m.endswith("/") and (name == m[:-1] or name.startswith(m[:-1] + "."))) or name == m]
    return hits


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
    wrong = {name: _layer(name) for name in MODULES if name and len(_layer(name)) != 1}
    assert not wrong, f"modules in no layer or in several (update LAYERS and the map in dhfield/__init__.py): {wrong}"


def test_the_map_names_every_layer_member():
    """The map in dhfield/__init__.py's docstring names every module and subpackage of LAYERS."""
    doc = ast.get_docstring(ast.parse((PKG / "__init__.py").read_text(encoding="utf-8")))
    missing = [m for members in LAYERS.values() for m in members
               if not re.search(rf"(?<![\w.]){re.escape(m)}(?![\w/])" if not m.endswith("/") else re.escape(m), doc)]
    assert not missing, f"the package map in dhfield/__init__.py does not name {missing}"


@pytest.mark.parametrize("layer", list(LAYERS))
def test_layer_imports_only_what_the_map_allows(layer):
    allowed = MAY_IMPORT[layer] | {layer}
    bad = []
    for importer, target, top in _edges():
        if not importer or _layer(importer) != [layer] or not target:
            continue
        if layer == "bem" and importer == "bem" and not top and target in BEM_FACADE_LAZY:
            continue  # the facade's one lazy forward (documented in the map)
        (target_layer,) = _layer(target)
        if target_layer not in allowed:
            bad.append(f"dhfield.{importer} imports dhfield.{target} ({target_layer})")
    assert not bad, f"{layer} may import {sorted(allowed)} only:\n" + "\n".join(bad)


def test_bem_imports_no_analytic_model():
    """dhfield/bem/ imports no analytic or comparison model, nor the registry (only the facade's
    lazy forward of adhesive_start, inside a function)."""
    def in_bem(name):  # the package dhfield.bem and its modules (not dhfield.bem_compliance, a bridge)
        return name == "bem" or name.startswith("bem.")

    bad = [f"dhfield.{i} imports dhfield.{t}" for i, t, top in _edges()
           if in_bem(i) and _layer(t)[0] in ("analytic", "comparison", "front")
           or (in_bem(i) and _layer(t)[0] == "bridge" and (top or i != "bem" or t not in BEM_FACADE_LAZY))]
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
    assert ("model", "adhesion") in edges and ("cli.solve", "bem") in edges
    assert ("bem", "adhesive_start") in edges  # the facade's lazy forward, inside a function
    ext = {t for t, _ in _imports("io", MODULES["io"])}
    assert "ext:xarray" in ext
