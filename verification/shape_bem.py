"""The shape of dhfield/bem, measured: parameters per function, what it imports, its size.

Prints the functions of ``dhfield/bem`` with the most parameters (self/cls not
counted; ``*args``/``**kwargs`` count one each; target <= 10), the dhfield
modules outside ``bem`` that its files import (statically) and that importing
``dhfield.bem`` loads (in a fresh interpreter), flagging any analytic model
(target: none), and the line count of the package::

    PYTHONPATH=$PWD .venv/bin/python -m verification.shape_bem [--repo DIR]
"""
from __future__ import annotations

import argparse
import ast
import subprocess
import sys
from pathlib import Path

#: dhfield modules ``bem`` may import: numerical helpers and geometry, no model of the contact.
ALLOWED = {"_validation", "pull_off_search", "geometry"}
#: Parameter count a function of dhfield/bem should not exceed.
MAX_PARAMETERS = 10


def parameter_counts(package: Path):
    """(count, 'file:line name') of every function of ``package``, most parameters first."""
    rows = []
    for path in sorted(package.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                a = node.args
                names = [x.arg for x in a.posonlyargs + a.args]
                k = len(names) + len(a.kwonlyargs) + (a.vararg is not None) + (a.kwarg is not None)
                k -= bool(names and names[0] in ("self", "cls"))
                rows.append((k, f"{path.relative_to(package.parent.parent)}:{node.lineno} {node.name}"))
    return sorted(rows, reverse=True)


def static_imports(package: Path):
    """dhfield modules outside ``package`` that its files import: {module: [file, or file (lazy)]}.

    An import inside a function body is marked lazy: it runs on first use, not on import.
    """
    found = {}
    for path in sorted(package.rglob("*.py")):
        tree = ast.parse(path.read_text())
        top = {id(n) for n in tree.body}
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and node.level >= 2:
                mods = [node.module.split(".")[0]] if node.module else [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom) and (node.module or "").startswith("dhfield.") \
                    and not node.module.startswith("dhfield.bem"):
                mods = [node.module.split(".")[1]]
            else:
                continue
            for m in mods:
                found.setdefault(m, []).append(path.name + ("" if id(node) in top else " (lazy)"))
    return found


def code_lines(path: Path) -> int:
    """Lines of ``path`` that are code: not blank, not comments, not docstrings."""
    text = path.read_text()
    doc = set()
    for node in ast.walk(ast.parse(text)):
        body = getattr(node, "body", None)
        if isinstance(body, list) and body and isinstance(body[0], ast.Expr) \
                and isinstance(body[0].value, ast.Constant) and isinstance(body[0].value.value, str):
            doc.update(range(body[0].lineno, body[0].end_lineno + 1))
    return sum(1 for i, line in enumerate(text.splitlines(), 1)
               if i not in doc and line.strip() and not line.strip().startswith("#"))


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repo", default=".", help="checkout to measure (default: the current directory)")
    args = p.parse_args(argv)
    repo = Path(args.repo).resolve()
    package = repo / "dhfield" / "bem"
    rows = parameter_counts(package)
    print(f"largest parameter counts in dhfield/bem (target <= {MAX_PARAMETERS}):")
    for k, where in rows[:5]:
        print(f"  {k:3d}  {where}")
    imports = static_imports(package)
    print("dhfield modules imported by dhfield/bem (static):")
    for m, files in sorted(imports.items()):
        facade = all(f == "__init__.py (lazy)" for f in files)
        flag = "" if m in ALLOWED else ("   <-- the facade forwards its names on first use" if facade
                                        else "   <-- used by the engine: not a numerical helper")
        print(f"  {m:20s} {', '.join(sorted(set(files)))}{flag}")
    code = ("import sys, dhfield.bem; print(' '.join(sorted(m.split('.')[1] for m in sys.modules "
            "if m.startswith('dhfield.') and not m.startswith('dhfield.bem'))))")
    loaded = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=repo,
                            env={"PYTHONPATH": str(repo)}, check=True).stdout.split()
    print(f"dhfield modules loaded by 'import dhfield.bem': {' '.join(loaded) or '(none)'}")
    bad = sorted(set(loaded) - ALLOWED)
    print(f"analytic models loaded by 'import dhfield.bem': {', '.join(bad) if bad else 'none'}")
    files = list(package.rglob("*.py"))
    lines = sum(len(f.read_text().splitlines()) for f in files)
    print(f"lines of dhfield/bem: {lines} ({sum(code_lines(f) for f in files)} of code: no blank, comment "
          "or docstring lines)")


if __name__ == "__main__":
    main()
