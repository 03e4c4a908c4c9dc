"""Sphinx extension: the pages of the dhfield site that are generated from the code and the data.

At ``config-inited`` (before Sphinx lists the source files) it writes, under ``docs/``:

``api/``
    The API reference: one page per public module (every module of :mod:`dhfield` whose
    dotted name has no component starting with ``_``, except the command-line subcommand
    modules, which the CLI reference covers), listing the module's ``__all__`` through
    a table (one generated page per name, ``api/generated/``).  A name that a
    module re-exports from another public module links to the page of the module that
    defines it.  ``api/index.rst`` (the user's API reference) lists the entry points a user
    calls, :data:`ENTRY_POINTS`, grouped by task; ``api/internals.rst`` (the developer
    reference) lists every other public module, the building blocks, grouped by :data:`GROUPS`,
    one group per folder of the package (``models/``, ``core/``, ``bem/``, ``analysis/``, ...).
    A module not matched by :data:`GROUPS` lands in "Other modules", so a new module is
    documented without editing this file.
``_generated/verdict.rst``, ``_generated/truth_table.rst``, ``_generated/sphere.rst``
    The verdict of the self-consistent adhesive BEM against the closures, computed from
    ``data/adhesive_ground_truth.nc`` and ``data/adhesive_sphere_convergence.json`` by the
    verification report's own functions (:mod:`verification.sec_adhesive`).
``_generated/netcdf_variables.rst``
    The netCDF/CSV variables, from :data:`dhfield.core.schema.VARIABLES`.
``_generated/changelog.rst``
    CHANGELOG.md, converted (headings, bullets, paragraphs).

:func:`public_api` is also used by ``tests/test_docs.py`` and ``verification/doc_counts.py``.
"""
from __future__ import annotations

import importlib
import inspect
import json
import pkgutil
import re
from pathlib import Path

import os

DOCS = Path(__file__).resolve().parents[1]
#: The project root (data/, CHANGELOG.md, CITATION.cff, verification/); DHFIELD_DOCS_ROOT overrides it
#: when the docs tree is a copy (tests/test_docs.py builds one in a temporary directory).
ROOT = Path(os.environ.get("DHFIELD_DOCS_ROOT", DOCS.parent)).resolve()

#: The developer reference, one group per folder of the package, in the order a newcomer reads
#: them: the models first, then the layers they build on and what is built on them (the layer
#: map: the docstring of :mod:`dhfield`).  Each entry is (title, introduction, module names).
#: A module belongs to the first group that names it or a package above it (``dhfield.models``
#: holds every ``dhfield.models.*``).  Within its group a module named there is listed in that
#: order (the folder's overview page first, then the modules a reader should meet first), and
#: the others after them, by name.
GROUPS = (
    ("Models", "``dhfield/models/``: one module per analytic model, named as on the command line "
     "(``--model``). The recommended model ``md-elliptic`` first, the registry of every model by "
     "its name, then the paper's extended double-Hertz model ``dh-elliptic`` with its fields, "
     "adhesion integral (Eq. 31), periphery and closures, and the comparison models.",
     ("dhfield.models", "dhfield.models.md_elliptic", "dhfield.models.registry", "dhfield.models.dh_elliptic",
      "dhfield.models.dh_elliptic_fields", "dhfield.models.dh_elliptic_adhesion",
      "dhfield.models.dh_elliptic_periphery", "dhfield.models.dh_elliptic_rays",
      "dhfield.models.dh_elliptic_closure", "dhfield.models.jkr_elliptic", "dhfield.models.jkr_elliptic_energy",
      "dhfield.models.maugis_dugdale", "dhfield.models.maugis_dugdale_separated", "dhfield.models.jkr",
      "dhfield.models.dmt", "dhfield.models.dh_circular", "dhfield.models.hertz")),
    ("Foundations", "``dhfield/core/``: what every layer builds on: input validation, the paper's "
     "units, the crossed-cylinder geometry (Eqs. 2-6), elliptic integrals, the one pull-off search, "
     "the result records and the variable table.  It imports nothing else of dhfield.",
     ("dhfield.core", "dhfield.core.validation", "dhfield.core.units", "dhfield.core.geometry",
      "dhfield.core.elliptic", "dhfield.core.transition", "dhfield.core.pull_off_search", "dhfield.core.records",
      "dhfield.core.schema")),
    ("The boundary-element method", "``dhfield/bem/``: the ground truth: the DC-FFT half-space "
     "operator, the traction-separation laws, the self-consistent adhesive solver, unloading paths "
     "and the pull-off.  It builds on the foundations and imports no model.",
     ("dhfield.bem", "dhfield.bem.pull_off", "dhfield.bem.state", "dhfield.bem.operator", "dhfield.bem.laws",
      "dhfield.bem.solver")),
    ("Analysis", "``dhfield/analysis/``: what is built on the models and the BEM together: the "
     "comparison of every model, its error against the ground truth, the SI front end, fits, the "
     "BEM started from the models, the machine spring, fields and Eq. (30), the adhesion map.",
     ("dhfield.analysis", "dhfield.analysis.compare", "dhfield.analysis.validity", "dhfield.analysis.model_error",
      "dhfield.analysis.dimensional", "dhfield.analysis.fit", "dhfield.analysis.bem_start",
      "dhfield.analysis.spring", "dhfield.analysis.bem_spring", "dhfield.analysis.fields",
      "dhfield.analysis.field_sampling", "dhfield.analysis.field_metrics", "dhfield.analysis.polar",
      "dhfield.analysis.eq30")),
    ("Input and output", "``dhfield/io/``: netCDF/CSV writers with provenance, atomic writes, and the "
     "figures.", ("dhfield.io",)),
    ("Sweeps", "``dhfield/sweep/``: parameter sweeps on dask that resume.", ("dhfield.sweep",)),
    ("Command line", "``dhfield/cli/``: the ``dhfield`` command's entry point (its options: :doc:`/cli`).",
     ("dhfield.cli",)),
)
OTHER_GROUP = ("Other modules", "Public modules not yet placed in a group.")

#: The user's API reference (``api/index.rst``): (task, introduction, modules), in the order a user
#: meets them.  Every other public module is a building block, listed on ``api/internals.rst``.
ENTRY_POINTS = (
    ("Compute a pull-off force", "The recommended model by default, any model by name; nondimensional "
     "(the paper's units) or SI; every answer with its estimated error against the BEM ground truth.",
     ("dhfield", "dhfield.analysis.compare", "dhfield.analysis.dimensional", "dhfield.analysis.model_error", "dhfield.analysis.validity")),
    ("Fit measurements", "The work of adhesion (and the adhesive stress) from measured pull-off forces or "
     "load curves.", ("dhfield.analysis.fit",)),
    ("Maps, sweeps and figures", "Every model over crossing angle and μ, parameter sweeps that resume, and "
     "the figures drawn from them.",
     ("dhfield.analysis.adhesion_map", "dhfield.analysis.force_vs_angle", "dhfield.sweep", "dhfield.io.sweep_maps")),
    ("The boundary-element ground truth", "The self-consistent adhesive BEM solution that judges the models.",
     ("dhfield.bem",)),
    ("Files", "netCDF/CSV files with provenance, and the one table of their variables.",
     ("dhfield.io", "dhfield.core.schema")),
    ("Command line", "The ``dhfield`` command's entry point (its options: :doc:`/cli`).", ("dhfield.cli",)),
)


def entry_point_modules() -> list[str]:
    """The modules of the user's API reference (:data:`ENTRY_POINTS`) that exist, in order."""
    mods = set(public_modules())
    return [m for _, _, group in ENTRY_POINTS for m in group if m in mods]


# --------------------------------------------------------------------------- the public API
def public_modules() -> list[str]:
    """Dotted names of the public modules of dhfield, sorted (package before its modules)."""
    import dhfield

    names = ["dhfield"]
    for info in pkgutil.walk_packages(dhfield.__path__, "dhfield."):
        parts = info.name.split(".")
        if any(p.startswith("_") for p in parts[1:]):
            continue
        if info.name.startswith("dhfield.cli."):   # subcommands: covered by the CLI reference
            continue
        names.append(info.name)
    return sorted(names, key=lambda n: n.split("."))


def module_names(modname: str) -> list[str]:
    """The public names of a module: ``__all__``, or its own non-underscore definitions."""
    mod = importlib.import_module(modname)
    if hasattr(mod, "__all__"):
        return list(mod.__all__)
    return sorted(n for n, o in vars(mod).items() if not n.startswith("_")
                  and getattr(o, "__module__", None) == modname and (inspect.isfunction(o) or inspect.isclass(o)))


def _assigns(modname: str, name: str) -> bool:
    """Whether the module's source binds ``name`` at top level (an assignment or a definition)."""
    try:
        src = inspect.getsource(importlib.import_module(modname))
    except (OSError, TypeError):
        return False
    return re.search(rf"^(?:{re.escape(name)}\s*(?::[^=\n]*)?=|(?:def|class)\s+{re.escape(name)}\b)", src,
                     re.M) is not None


def public_api() -> dict[str, dict[str, str]]:
    """Every public name: ``{module: {name: canonical "module.name"}}``.

    The canonical home of a function or class is its defining module when that module is public
    and lists it; of anything else (a constant, or an object from a private module), the public
    module that binds it in its source, else the deepest public module listing it.
    """
    mods = public_modules()
    listed = {m: module_names(m) for m in mods}
    objects = {}
    for m in mods:
        mod = importlib.import_module(m)
        for n in listed[m]:
            obj = getattr(mod, n)
            objects[m, n] = obj
    api: dict[str, dict[str, str]] = {}
    for m in mods:
        api[m] = {}
        for n in listed[m]:
            obj = objects[m, n]
            home = None
            if inspect.isfunction(obj) or inspect.isclass(obj):
                defining = getattr(obj, "__module__", "")
                if defining in listed and getattr(obj, "__name__", n) in listed[defining]:
                    home = f"{defining}.{obj.__name__}"
            if home is None:
                cands = [c for c in mods if n in listed[c] and objects[c, n] is obj]
                bound = [c for c in cands if _assigns(c, n)]
                pick = bound[0] if bound else max(cands, key=lambda c: c.count("."))
                home = f"{pick}.{n}"
            api[m][n] = home
    return api


def _match(modname: str, prefixes) -> int | None:
    """Position of ``modname`` in ``prefixes``, else of the first package above it there, else None."""
    if modname in prefixes:
        return prefixes.index(modname)
    for i, p in enumerate(prefixes):
        if p != "dhfield" and modname.startswith(p + "."):
            return i
    return None


def group_of(modname: str) -> int:
    """Index into :data:`GROUPS` (``len(GROUPS)``: the "Other modules" group)."""
    for k, (_, _, prefixes) in enumerate(GROUPS):
        if _match(modname, prefixes) is not None:
            return k
    return len(GROUPS)


def group_order(modname: str) -> tuple:
    """Sort key of a module on the developer reference: its group, then its place in the group."""
    k = group_of(modname)
    named = GROUPS[k][2] if k < len(GROUPS) else ()
    place = named.index(modname) if modname in named else len(named)
    return k, place, modname.split(".")


def _first_line(modname: str) -> str:
    doc = inspect.getdoc(importlib.import_module(modname)) or ""
    return doc.strip().split("\n\n")[0].replace("\n", " ")


def _title(text: str, char: str = "=") -> str:
    return f"{text}\n{char * len(text)}\n"


def write_if_changed(path: Path, text: str) -> None:
    """Write ``text`` unless the file already holds it (keeps Sphinx's incremental build quiet)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    if not path.exists() or path.read_text() != text:
        path.write_text(text)


def _kind(obj) -> str:
    if inspect.isclass(obj):
        return "class"
    if inspect.isfunction(obj) or inspect.isbuiltin(obj) or callable(obj) and hasattr(obj, "__wrapped__"):
        return "function"
    return "data"


def _summary(obj, kind: str) -> str:
    """The first paragraph of a docstring, one line, made safe for a table cell."""
    if kind == "data":
        return ""
    doc = inspect.getdoc(obj) or ""
    para = " ".join(doc.strip().split("\n\n")[0].split())
    return escape_bars(para)


_LITERAL = re.compile(r"(``.*?``|:math:`[^`]*`|`[^`]*`_?)")


def escape_bars(line: str) -> str:
    """Escape ``|`` outside inline literals and math, so that ``|x|`` (an absolute value in a
    plain-text docstring) is not read as a reStructuredText substitution."""
    parts = _LITERAL.split(line)
    return "".join(p if k % 2 else re.sub(r"(?<!\\)\|", r"\\|", p) for k, p in enumerate(parts))


_QUALIFIED_HEADER = re.compile(r"^(\s*)(Attributes|Parameters|Returns|Other Parameters)\s+\((.+)\)\s*$")


def sanitize_docstring(app, what, name, obj, options, lines) -> None:
    """``autodoc-process-docstring`` (before numpydoc): plain-text conventions made valid.

    * ``|x|`` (an absolute value) becomes literal bars; lines of ``.. math::`` blocks, literal
      blocks (after ``::``) and grid tables are left alone;
    * a qualified section header such as ``Attributes (arrays over the broadcast inputs)``,
      which numpydoc would drop with its content as an unknown section, becomes the plain
      header, its qualifier a sentence just before it.
    """
    for k in range(len(lines) - 2, -1, -1):
        m = _QUALIFIED_HEADER.match(lines[k])
        if m and set(lines[k + 1].strip()) == {"-"}:
            indent, header, qualifier = m.groups()
            lines[k:k + 2] = [f"{indent}{header}: {qualifier}.", "", f"{indent}{header}",
                              f"{indent}{'-' * len(header)}"]
    verbatim_indent = None
    for k, line in enumerate(lines):
        stripped = line.strip()
        indent = len(line) - len(line.lstrip())
        if verbatim_indent is not None:
            if stripped and indent <= verbatim_indent:
                verbatim_indent = None
            else:
                continue
        if stripped.startswith(".. math::") or stripped.endswith("::"):
            verbatim_indent = indent
            if stripped.startswith(".. math::") and stripped != ".. math::":
                continue
            lines[k] = escape_bars(line) if not stripped.startswith("..") else line
            continue
        if stripped.startswith(("+-", "+=", "| ")) and stripped.endswith(("+", "|")):
            continue
        lines[k] = escape_bars(line)


def write_api(outdir: Path) -> None:
    """The API reference pages (see the module docstring)."""
    api = public_api()
    gen = outdir / "generated"
    outdir.mkdir(parents=True, exist_ok=True)
    gen.mkdir(parents=True, exist_ok=True)
    groups: dict[int, list[str]] = {}
    for m in sorted(api, key=group_order):
        groups.setdefault(group_of(m), []).append(m)
    keep, keep_gen = {"index.rst"}, set()
    for m, names in api.items():
        mod = importlib.import_module(m)
        own = [n for n, home in names.items() if home == f"{m}.{n}"]
        reexported = [(n, home) for n, home in names.items() if home != f"{m}.{n}"]
        lines = [f".. _api-{m}:\n", _title(m),
                 f".. automodule:: {m}\n   :no-members:\n   :no-index:\n"]
        if own:
            lines += [_title("Contents", "-"), ".. list-table::\n   :widths: 35 65\n   :class: dhfield-summary\n"]
            for n in own:
                obj = getattr(mod, n)
                kind = _kind(obj)
                lines += [f"   * - :py:{'obj'}:`~{m}.{n}`", f"     - {_summary(obj, kind) or kind}"]
                page = [f".. Generated by docs/_ext/dhfield_docs.py from {m}.__all__; do not edit.\n",
                        _title(f"{m}.{n}"), f".. currentmodule:: {m}\n"]
                if kind == "class":
                    page.append(f".. autoclass:: {n}\n   :members:\n   :special-members: __call__\n")
                elif kind == "function":
                    page.append(f".. autofunction:: {n}\n")
                else:
                    page.append(f".. autodata:: {n}\n")
                write_if_changed(gen / f"{m}.{n}.rst", "\n".join(page))
                keep_gen.add(f"{m}.{n}.rst")
            lines += ["", ".. toctree::\n   :hidden:\n"] + [f"   generated/{m}.{n}" for n in own] + [""]
        if reexported:
            lines.append(f"Also importable from ``{m}``, documented where they are defined:\n")
            lines += [f"* ``{n}``: :obj:`{home}`" for n, home in reexported]
            lines.append("")
        fname = f"{m}.rst"
        keep.add(fname)
        write_if_changed(outdir / fname, "\n".join(lines) + "\n")
    entry = entry_point_modules()
    index = [".. _api:\n", _title("API reference"),
             "The functions and classes a user calls, grouped by task, generated from the docstrings: each "
             "module lists its ``__all__``.  Units are SI unless a name says ``_star``/``nondimensional`` (the "
             "paper's units of Eqs. 32-35, :doc:`/theory/model`).  Equations cite the paper as \"Eq. (n)\".  "
             "The building blocks behind them are in the :doc:`developer reference </api/internals>`, one "
             "group per folder of the package: the models (``dhfield.models``, the recommended "
             "``md_elliptic`` first), the foundations (``dhfield.core``), the BEM's parts (``dhfield.bem``) "
             "and the analyses built on both (``dhfield.analysis``).\n"]
    for title, intro, group in ENTRY_POINTS:
        present = [m for m in group if m in entry]
        if not present:
            continue
        index += [_title(title, "-"), intro + "\n", ".. list-table::\n   :widths: 30 70\n"]
        for m in present:
            index.append(f"   * - :doc:`{m}`\n     - {escape_bars(_first_line(m))}")
        index += ["", ".. toctree::\n   :hidden:\n"] + [f"   {m}" for m in present] + [""]
    internals = [".. _api-internals:\n", _title("Developer reference: the building blocks"),
                 "Every other public module of :mod:`dhfield`, grouped by the folder it lives in, one folder "
                 "per layer: ``core`` at the bottom, ``models`` and ``bem`` on it, ``analysis`` on both, "
                 "``io``, ``sweep`` and ``cli`` at the edge (the map, and who may import whom: "
                 ":mod:`dhfield`).  The models come first, the recommended one at their head.  The entry "
                 "points of the :doc:`API reference </api/index>` are listed there, not here.  Public and "
                 "documented, but a user rarely calls them directly.\n"]
    for k in sorted(groups):
        mods = [m for m in groups[k] if m not in entry]
        if not mods:
            continue
        title, intro = (GROUPS[k][:2] if k < len(GROUPS) else OTHER_GROUP)
        internals += [_title(title, "-"), intro + "\n", ".. list-table::\n   :widths: 30 70\n"]
        for m in mods:
            internals.append(f"   * - :doc:`{m}`\n     - {escape_bars(_first_line(m))}")
        internals += ["", ".. toctree::\n   :hidden:\n"] + [f"   {m}" for m in mods] + [""]
    write_if_changed(outdir / "internals.rst", "\n".join(internals) + "\n")
    keep.add("internals.rst")
    write_if_changed(outdir / "index.rst", "\n".join(index) + "\n")
    for stale in outdir.glob("*.rst"):
        if stale.name not in keep:
            stale.unlink()
    for stale in gen.glob("*.rst"):
        if stale.name not in keep_gen:
            stale.unlink()


# --------------------------------------------------------------------------- data-driven pages
def _md_to_rst(text: str) -> str:
    """The Markdown of the verification report's sentences, as reStructuredText inline markup."""
    text = re.sub(r"(?<!`)`([^`]+)`(?!`)", r"``\1``", text)
    return text


def write_verdict(outdir: Path) -> None:
    """The adhesive BEM verdict, its table and the sphere convergence, from the stored data."""
    import numpy as np
    import xarray as xr

    from verification import sec_adhesive as sec

    path = ROOT / "data" / "adhesive_ground_truth.nc"
    with xr.open_dataset(path) as ds:
        ds = ds.load()
    tab = sec.truth_table(ds)
    coverage = sec._coverage(ds)
    lines = sec.guide_lines(tab) + sec.verdict_lines(tab, coverage)
    rst = [f".. Generated from ``data/{path.name}`` by docs/_ext/dhfield_docs.py; do not edit.\n"]
    rst += [f"* {_md_to_rst(s)}" for s in lines]
    write_if_changed(outdir / "verdict.rst", "\n".join(rst) + "\n")
    short = [f".. Generated from ``data/{path.name}`` by docs/_ext/dhfield_docs.py; do not edit.\n",
             ".. admonition:: Which model to use: the verdict of the ground truth\n"]
    short += [f"   {_md_to_rst(s)}\n" for s in sec.guide_lines(tab)]
    short += ["   Details: :doc:`/theory/bem`.  (Computed from the stored data when this page was built.)"]
    write_if_changed(outdir / "verdict_short.rst", "\n".join(short) + "\n")

    models = [m for m in list(sec.CLOSURES) + list(sec.OTHERS) if m in tab["dev"]]
    head = ["β0", "μ", "W*max BEM", "β_ab", "β_cd"] + [f"``{m}``" for m in models]
    rows = []
    for i, b in enumerate(tab["beta0"]):
        for j, mu in enumerate(tab["mu"]):
            w = tab["W_bem"][i, j]
            cells = [f"{b:g}", f"{mu:g}", f"{w:.4f}" if np.isfinite(w) else "–",
                     f"{tab['beta_ab'][i, j]:.3f}", f"{tab['beta_cd'][i, j]:.3f}"]
            cells += [f"{100 * tab['dev'][m][i, j]:+.1f} %" if np.isfinite(tab["dev"][m][i, j]) else "–"
                      for m in models]
            rows.append(cells)
    table = [f".. Generated from ``data/{path.name}`` by docs/_ext/dhfield_docs.py; do not edit.\n",
             ".. list-table:: W*max of the self-consistent adhesive BEM (Dugdale law; Richardson-extrapolated "
             "where three grids converged) and each model's deviation W*model/W*BEM − 1 (negative: weaker "
             "pull-off)",
             "   :header-rows: 1", "   :class: dhfield-wide", ""]
    for r in [head] + rows:
        table.append("   * - " + r[0])
        table += [f"     - {c}" for c in r[1:]]
    write_if_changed(outdir / "truth_table.rst", "\n".join(table) + "\n")

    sphere = ROOT / "data" / "adhesive_sphere_convergence.json"
    doc = json.loads(sphere.read_text())
    srows = [["λ", "μ", "W* (MD)"] + [f"N = {n}" for n in doc["n"]] + ["Richardson", "observed order"]]
    for case in doc["cases"]:
        per_n = {r["n"]: r["err"] for r in case["rows"]}
        order = case["order"]
        srows.append([f"{case['lam']:g}", f"{case['mu']:.4f}", f"{case['W_md']:.6f}"]
                     + [f"{100 * per_n[n]:+.4f} %" if n in per_n else "–" for n in doc["n"]]
                     + [f"{100 * case['richardson_err']:+.4f} %",
                        f"{order:.2f}" if order == order else "–"])
    out = [f".. Generated from ``data/{sphere.name}`` by docs/_ext/dhfield_docs.py; do not edit.\n",
           f".. list-table:: Sphere (β0 = 1, Dugdale law): W*BEM/W*MD − 1 per grid and Richardson-extrapolated "
           f"(solver commit ``{doc['git_commit'][:10]}``; {doc['route']}; observed order –: the error is not "
           f"monotone over N)",
           "   :header-rows: 1", "   :class: dhfield-wide", ""]
    for r in srows:
        out.append("   * - " + r[0])
        out += [f"     - {c}" for c in r[1:]]
    out += ["", f"Command: ``{doc['command']}``"]
    write_if_changed(outdir / "sphere.rst", "\n".join(out) + "\n")


def write_netcdf_variables(outdir: Path) -> None:
    """The variables table, from :data:`dhfield.core.schema.VARIABLES`."""
    from dhfield.core import schema

    out = [".. Generated from dhfield.core.schema.VARIABLES by docs/_ext/dhfield_docs.py; do not edit.\n",
           ".. list-table::", "   :header-rows: 1", "   :widths: 16 10 22 40 12", "   :class: dhfield-vars", "",
           "   * - name", "     - units", "     - long_name", "     - description", "     - paper's unit"]

    def cell(s):
        s = " ".join(str(s).split())
        return s.replace("*", r"\*").replace("`", "'").replace("|", r"\|").replace("_", r"\_") if s else "–"

    for name, var in schema.VARIABLES.items():
        desc = var.description + (f" (CF standard_name ``{var.standard_name}``)" if var.standard_name else "")
        out += [f"   * - ``{name}``", f"     - ``{var.units}``", f"     - {cell(var.long_name)}",
                f"     - {cell(desc)}", f"     - {cell(var.scale or '')}"]
    write_if_changed(outdir / "netcdf_variables.rst", "\n".join(out) + "\n")


def write_changelog(outdir: Path) -> None:
    """CHANGELOG.md as reStructuredText (headings ``#``/``##``/``###``, ``-`` bullets, paragraphs)."""
    md = (ROOT / "CHANGELOG.md").read_text().splitlines()
    chars = {1: "=", 2: "-", 3: "~"}
    out = []
    for line in md:
        m = re.match(r"^(#{1,3})\s+(.*)$", line)
        if m:
            title = _md_inline(m.group(2))
            out += ["", title, chars[len(m.group(1))] * len(title), ""]
        elif re.match(r"^\s*[-*]\s+", line):
            out.append(_md_inline(re.sub(r"^(\s*)[-*]\s+", r"\1* ", line)))
        else:
            out.append(_md_inline(line))
    write_if_changed(outdir / "changelog.rst", "\n".join(out).strip() + "\n")


def _md_inline(text: str) -> str:
    text = re.sub(r"\[([^\]]+)\]\(([^)]+)\)", r"`\1 <\2>`__", text)
    return re.sub(r"(?<!`)`([^`]+)`(?!`)", r"``\1``", text)


def write_citation(outdir: Path) -> None:
    """A BibTeX entry for the software, from CITATION.cff."""
    import yaml

    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text())
    authors = " and ".join(a.get("name") or f"{a['family-names']}, {a['given-names']}" for a in cff["authors"])
    year = str(cff.get("date-released", ""))[:4]
    bib = (f"@software{{dhfield,\n  author  = {{{{{authors}}}}},\n  title   = {{{{{cff['title']}}}}},\n"
           f"  version = {{{cff['version']}}},\n  year    = {{{year}}},\n  license = {{{cff['license']}}},\n"
           f"  note    = {{Implements Zini et al., Tribology Letters 66 (2018) 30, "
           f"doi:{cff['references'][0]['doi']}}}\n}}\n")
    write_if_changed(outdir / "citation.bib", bib)


def generate(app=None) -> None:
    """Write every generated page (run at Sphinx's ``config-inited``)."""
    write_api(DOCS / "api")
    gen = DOCS / "_generated"
    write_verdict(gen)
    write_netcdf_variables(gen)
    write_changelog(gen)
    write_citation(gen)


def setup(app):
    # config-inited: before Sphinx lists the source files, so the generated pages are found on a
    # fresh clone
    app.connect("config-inited", lambda app, config: generate(app))
    app.connect("autodoc-process-docstring", sanitize_docstring, priority=100)   # numpydoc: 500
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
