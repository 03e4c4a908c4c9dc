"""Newcomer test: the README runs as written.

* Every ```python block runs on its own: in a fresh namespace, in a temporary
  directory.  A ```text block that follows it and starts with ``# output`` is its
  expected standard output, compared line by line.
* Every ``dhfield ...`` line of a ```sh block (also as ``.venv/bin/dhfield``) runs
  through :func:`dhfield.cli.main` in a temporary directory and must exit 0.  A line
  whose comment contains ``slow`` is only parsed, by
  :func:`dhfield.cli.build_parser` (the flags and values must be valid).  A ```text
  block after a ```sh block must appear in what its last command printed.
* Every other command line must be one the test knows how to check without running
  it (``make <target>`` has that target, ``python -m <module>`` imports, a script
  path exists, ``pip install -e '.[extra]'`` names an extra of pyproject.toml);
  anything else fails the test, so that nothing in the README goes unchecked.

The same holds for the ``.. code-block:: python`` / ``sh`` / ``text`` blocks of the documentation
pages in :data:`DOC_PAGES`, where the README's longer examples moved (``::`` literal blocks are
not run).
"""
from __future__ import annotations

import contextlib
import importlib.util
import io
import re
import shlex
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
README = ROOT / "README.md"
#: Documentation pages whose code blocks run too (the README's longer examples moved there).
DOC_PAGES = ("docs/howto/python_api.rst", "docs/howto/cli_tour.rst", "docs/howto/fit.rst",
             "docs/howto/pull_off.rst", "docs/verification.rst")
_FENCE = re.compile(r"^```(\w*)\s*\n(.*?)^```\s*$", re.MULTILINE | re.DOTALL)
_RST_BLOCK = re.compile(r"^\.\. code-block:: *(\w+)[ \t]*\n((?:[ \t]*\n|[ \t]+\S.*\n)*)", re.MULTILINE)


def _rst_blocks(text):
    """(language, body) of every ``.. code-block::`` of an RST page: options dropped, dedented."""
    out = []
    for m in _RST_BLOCK.finditer(text):
        lines = textwrap.dedent(m.group(2)).splitlines()
        while lines and (not lines[0].strip() or lines[0].startswith(":")):
            lines.pop(0)
        out.append((m.group(1), "\n".join(lines).rstrip() + "\n"))
    return out


def _blocks(path=README):
    """(language, body, index) of every code block of a page (the README by default), in order."""
    text = path.read_text(encoding="utf-8")
    pairs = ([(m.group(1), m.group(2)) for m in _FENCE.finditer(text)] if path.suffix == ".md"
             else _rst_blocks(text))
    return [(lang, body, k) for k, (lang, body) in enumerate(pairs)]


def _command_lines(body):
    """(command, comment) of a shell block: continuation lines joined, comments split off."""
    out, pending = [], ""
    for raw in body.splitlines():
        line = pending + raw.strip()
        if line.endswith("\\"):
            pending = line[:-1] + " "
            continue
        pending = ""
        if not line or line.startswith("#"):
            continue
        cmd, _, comment = line.partition(" #")
        out.append((cmd.strip(), comment.strip()))
    return out


PAGES = {"README.md": README, **{page: ROOT / page for page in DOC_PAGES}}
BLOCKS = {name: _blocks(path) for name, path in PAGES.items()}
PYTHON = [(name, k, body) for name, blocks in BLOCKS.items() for lang, body, k in blocks if lang == "python"]
SHELL = [(name, k, cmd, comment) for name, blocks in BLOCKS.items() for lang, body, k in blocks
         if lang in ("sh", "bash", "console", "shell") for cmd, comment in _command_lines(body)]


def _expected_after(page, index):
    """The text block right after block ``index`` of ``page`` (None if the next block is not text)."""
    nxt = [b for b in BLOCKS[page] if b[2] == index + 1]
    return nxt[0][1] if nxt and nxt[0][0] == "text" else None


def test_readme_has_the_worked_example_and_code():
    assert PYTHON and SHELL
    text = README.read_text(encoding="utf-8")
    assert "PDMS" in text and "--skew-angle-deg 60" in text and "--model dh-elliptic" in text
    # issue 40: the worked example's first command is the recommended model, the default (no --model)
    first = next(line for line in text.splitlines() if line.startswith("dhfield pulloff "))
    assert "--model" not in first


def test_every_doc_page_has_code_blocks():
    """The pages the README's examples moved to are parsed (a renamed page or directive would
    otherwise leave its examples silently untested)."""
    for page in DOC_PAGES:
        assert any(p == page for p, _k, _b in PYTHON) or any(p == page for p, *_ in SHELL), page


@pytest.mark.parametrize("page,index,body", PYTHON, ids=[f"{p}-python-block-{k}" for p, k, _ in PYTHON])
def test_python_block_runs_on_its_own(page, index, body, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        exec(compile(body, f"{page} block {index}", "exec"), {"__name__": "__readme__"})  # noqa: S102
    expected = _expected_after(page, index)
    if expected is not None and expected.startswith("# output"):
        want = expected.splitlines()[1:]
        got = buf.getvalue().splitlines()
        assert got == want, f"{page} output block is stale:\n" + "\n".join(got)


def _check_other(cmd):
    """Check a non-dhfield command line without running it; return a reason string if unknown."""
    words = shlex.split(cmd)
    if words[0] == "make":
        targets = re.findall(r"^([\w.-]+):", (ROOT / "Makefile").read_text(), re.MULTILINE)
        assert all(w in targets for w in words[1:]), f"README: no Makefile target for {cmd!r}"
        return None
    if words[0] in (".", "source"):
        venv = re.search(r"^VENV\s*:?=\s*(\S+)", (ROOT / "Makefile").read_text(), re.MULTILINE).group(1)
        assert words[1] == f"{venv}/bin/activate", f"README activates {words[1]}, the Makefile builds {venv}"
        return None
    py = words[0].endswith("python") or words[0].endswith("python3")
    if py and len(words) >= 3 and words[1] == "-m" and words[2] not in ("venv", "pip"):
        assert importlib.util.find_spec(words[2]) is not None, f"README: no module {words[2]} ({cmd!r})"
        return None
    if py and len(words) >= 2 and words[1].endswith(".py"):
        assert (ROOT / words[1]).is_file(), f"README: no script {words[1]} ({cmd!r})"
        return None
    if py and words[1:3] == ["-m", "venv"]:
        return None
    if words[0].endswith("pip") and words[1:3] == ["install", "-e"]:
        extra = re.fullmatch(r"\.\[(\w+)\]", words[3])
        assert extra and f"\n{extra.group(1)} = " in (ROOT / "pyproject.toml").read_text(), cmd
        return None
    return f"README command the test does not know how to check: {cmd!r}"


@pytest.mark.parametrize("page,index,cmd,comment", SHELL, ids=[f"{p}-sh-{k}-{c[:40]}" for p, k, c, _ in SHELL])
def test_shell_line_works(page, index, cmd, comment, tmp_path, monkeypatch, capsys):
    from dhfield import cli

    words = shlex.split(cmd)
    if words[0] not in ("dhfield", ".venv/bin/dhfield"):
        problem = _check_other(cmd)
        assert problem is None, problem
        return
    argv = words[1:]
    monkeypatch.chdir(tmp_path)
    if "slow" in comment:
        cli.build_parser().parse_args(argv)  # flags, choices and types valid; not run
        return
    status = cli.main(argv)
    out = capsys.readouterr()
    assert status == 0, f"`{cmd}` exited {status}:\n{out.err[-2000:]}"
    expected = _expected_after(page, index)
    lines = [c for p, k, c, _c in SHELL if p == page and k == index]
    if expected is not None and not expected.startswith("# output") and cmd == lines[-1]:
        for line in expected.strip().splitlines():
            assert line.strip() in out.out + out.err, f"{page} says `{cmd}` prints {line!r}; it printed:\n{out.err}"


def test_readme_links_to_pages_that_exist():
    """Every relative link of the README (to the documentation's sources) names an existing file."""
    links = re.findall(r"\]\(([^)#\s]+)\)", README.read_text(encoding="utf-8"))
    local = [link for link in links if "://" not in link]
    assert local, "the README links to no documentation page"
    missing = [link for link in local if not (ROOT / link).is_file()]
    assert not missing, f"README links to missing files: {missing}"
