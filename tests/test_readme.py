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
"""
from __future__ import annotations

import contextlib
import importlib.util
import io
import re
import shlex
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
README = ROOT / "README.md"
_FENCE = re.compile(r"^```(\w*)\s*\n(.*?)^```\s*$", re.MULTILINE | re.DOTALL)


def _blocks():
    """(language, body, index) of every fenced block of the README, in order."""
    return [(m.group(1), m.group(2), k) for k, m in enumerate(_FENCE.finditer(README.read_text(encoding="utf-8")))]


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


BLOCKS = _blocks()
PYTHON = [(k, body) for lang, body, k in BLOCKS if lang == "python"]
SHELL = [(k, cmd, comment) for lang, body, k in BLOCKS if lang in ("sh", "bash", "console", "shell")
         for cmd, comment in _command_lines(body)]


def _expected_after(index):
    """The ```text block right after block ``index`` (None if the next block is not text)."""
    nxt = [b for b in BLOCKS if b[2] == index + 1]
    return nxt[0][1] if nxt and nxt[0][0] == "text" else None


def test_readme_has_the_worked_example_and_code():
    assert PYTHON and SHELL
    text = README.read_text(encoding="utf-8")
    assert "PDMS" in text and "--skew-angle-deg 60" in text and "--model dh-elliptic-two-axis" in text


@pytest.mark.parametrize("index,body", PYTHON, ids=[f"python-block-{k}" for k, _ in PYTHON])
def test_python_block_runs_on_its_own(index, body, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        exec(compile(body, f"README.md block {index}", "exec"), {"__name__": "__readme__"})  # noqa: S102
    expected = _expected_after(index)
    if expected is not None and expected.startswith("# output"):
        want = expected.splitlines()[1:]
        got = buf.getvalue().splitlines()
        assert got == want, "README output block is stale:\n" + "\n".join(got)


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


@pytest.mark.parametrize("index,cmd,comment", SHELL, ids=[f"sh-{k}-{c[:40]}" for k, c, _ in SHELL])
def test_shell_line_works(index, cmd, comment, tmp_path, monkeypatch, capsys):
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
    expected = _expected_after(index)
    lines = [c for k, c, _c in SHELL if k == index]
    if expected is not None and not expected.startswith("# output") and cmd == lines[-1]:
        for line in expected.strip().splitlines():
            assert line.strip() in out.out + out.err, f"README says `{cmd}` prints {line!r}; it printed:\n{out.err}"
