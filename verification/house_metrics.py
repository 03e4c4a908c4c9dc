"""The house in figures: flat modules, folders, docstring weight and lab notes in docstrings.

Prints, for the package ``dhfield``:

- the modules that sit flat in ``dhfield/`` (besides ``__init__``) and the modules per folder;
- docstring lines against code lines (comments and blank lines in neither);
- the docstring lines that carry a lab note: the words "measured" or "session", or a commit
  hash (7 to 40 hexadecimal characters with at least one digit and one letter, as a word).

Usage::

    python -m verification.house_metrics            # the table
    python -m verification.house_metrics --list     # and every lab-note line, file:line
"""
from __future__ import annotations

import argparse
import ast
import io
import re
import sys
import tokenize
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PKG = ROOT / "dhfield"
LAB_WORD = re.compile(r"\b(measured|session)\b", re.IGNORECASE)
HASH = re.compile(r"\b(?=[0-9a-f]*[0-9])(?=[0-9a-f]*[a-f])[0-9a-f]{7,40}\b")


def docstring_lines(path: Path) -> list[tuple[int, str]]:
    """(line number, text) of every line of every docstring in ``path``."""
    source = path.read_text(encoding="utf-8")
    tree = ast.parse(source)
    lines = source.splitlines()
    out = []
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            body = node.body
            if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant) \
                    and isinstance(body[0].value.value, str):
                expr = body[0]
                out.extend((n, lines[n - 1]) for n in range(expr.lineno, expr.end_lineno + 1))
    return out


def code_lines(path: Path, doc: set[int]) -> int:
    """Lines holding a code token, docstrings excluded."""
    seen = set()
    toks = tokenize.generate_tokens(io.StringIO(path.read_text(encoding="utf-8")).readline)
    skip = {tokenize.COMMENT, tokenize.NL, tokenize.NEWLINE, tokenize.INDENT, tokenize.DEDENT,
            tokenize.ENDMARKER}
    for tok in toks:
        if tok.type not in skip:
            seen.update(range(tok.start[0], tok.end[0] + 1))
    return len(seen - doc)


def lab_note(text: str) -> bool:
    """True when a docstring line carries a lab note (see the module docstring)."""
    return bool(LAB_WORD.search(text) or HASH.search(text))


def measure(pkg: Path = PKG) -> dict:
    """Counts over every module of ``pkg``; see the module docstring."""
    files = sorted(pkg.rglob("*.py"))
    flat = [p.name for p in files if p.parent == pkg and p.name != "__init__.py"]
    folders = {}
    doc_total = code_total = 0
    notes = []
    for path in files:
        rel = path.relative_to(pkg)
        if len(rel.parts) > 1:
            folders[rel.parts[0]] = folders.get(rel.parts[0], 0) + 1
        doc = docstring_lines(path)
        doc_total += len(doc)
        code_total += code_lines(path, {n for n, _ in doc})
        notes.extend((f"{path.relative_to(pkg.parent)}:{n}", t.strip()) for n, t in doc if lab_note(t))
    return {"modules": len(files), "flat": flat, "folders": folders, "docstring_lines": doc_total,
            "code_lines": code_total, "lab_notes": notes}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--list", action="store_true", help="print every lab-note line")
    args = parser.parse_args(argv)
    m = measure()
    print(f"modules: {m['modules']}; flat in dhfield/ (besides __init__): {len(m['flat'])}")
    if m["flat"]:
        print("  " + " ".join(m["flat"]))
    print("folders: " + ", ".join(f"{k}/ {v}" for k, v in sorted(m["folders"].items())))
    print(f"docstring lines: {m['docstring_lines']}; code lines: {m['code_lines']}")
    print(f"docstring lines with a lab note ('measured', 'session' or a commit hash): {len(m['lab_notes'])}")
    if args.list:
        for where, text in m["lab_notes"]:
            print(f"  {where}: {text}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
