"""Hostile inputs to the CLI: refused in one line, before computing, with nothing clobbered (issue 9)."""
from __future__ import annotations

import os
import stat

import pytest

from dhfield.analysis import fields
from dhfield.cli import main
from dhfield import io as dio

PULLOFF = ["--beta0", "0.9", "--mu", "1"]
FIELD = ["field", "--beta0", "0.9", "--mu", "1", "--a-star", "1.2", "--n", "16"]


def _one_error_line(capsys, *words, prefix="dhfield: error:"):
    err = capsys.readouterr().err.strip()
    lines = err.splitlines()
    assert len(lines) == 1 and lines[0].startswith(prefix), err
    for w in words:
        assert w in err, err
    return err


@pytest.fixture
def no_compute(monkeypatch):
    """Make any field computation fail the test: the input must be refused before it."""
    def forbidden(*a, **k):
        raise AssertionError("computed before validating the input")

    monkeypatch.setattr(fields, "model_case", forbidden)


@pytest.fixture(autouse=True)
def _private_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("DHFIELD_CACHE", str(tmp_path / "cache"))
    monkeypatch.delenv("DHFIELD_THREADS", raising=False)
    monkeypatch.delenv("DHFIELD_DEBUG", raising=False)


# --- item 4: the rename must not clobber what is not a writable regular file ----------------------
def test_symlink_target_is_refused_and_left_alone(tmp_path, capsys):
    real = tmp_path / "real.nc"
    real.write_bytes(b"keep")
    link = tmp_path / "link.nc"
    link.symlink_to(real)
    assert main(["compare", *PULLOFF, "--out", str(link)]) == 2
    _one_error_line(capsys, "symbolic link", "real.nc")
    assert link.is_symlink() and real.read_bytes() == b"keep"
    dangling = tmp_path / "dangling.nc"
    dangling.symlink_to(tmp_path / "nowhere.nc")
    assert main(["compare", *PULLOFF, "--out", str(dangling)]) == 2
    assert dangling.is_symlink() and not (tmp_path / "nowhere.nc").exists()


def test_fifo_target_is_refused_and_left_alone(tmp_path, capsys):
    fifo = tmp_path / "pipe.nc"
    os.mkfifo(fifo)
    assert main(["compare", *PULLOFF, "--out", str(fifo)]) == 2
    _one_error_line(capsys, "FIFO")
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode)


def test_device_target_is_refused(tmp_path, capsys):
    """As root, `--out /dev/null` replaced the device node; here a private node named *.nc."""
    with pytest.raises(ValueError, match="character device"):
        dio.validate_output_path("/dev/null")
    if os.geteuid() != 0:
        return  # only root can make a device node; the check above covers the rule
    node = tmp_path / "null.nc"
    os.mknod(node, stat.S_IFCHR | 0o666, os.makedev(1, 3))
    assert main(["compare", *PULLOFF, "--out", str(node)]) == 2
    _one_error_line(capsys, "character device")
    assert stat.S_ISCHR(os.lstat(node).st_mode)


def test_directory_target_is_refused(tmp_path, capsys):
    d = tmp_path / "d.nc"
    d.mkdir()
    assert main(["compare", *PULLOFF, "--out", str(d)]) == 2
    _one_error_line(capsys, "directory")
    assert main(["compare", *PULLOFF, "--out", str(tmp_path) + os.sep]) == 2


def test_read_only_file_is_refused_and_keeps_its_mode(tmp_path, capsys):
    ro = tmp_path / "ro.nc"
    ro.write_bytes(b"keep")
    os.chmod(ro, 0o444)
    assert main(["compare", *PULLOFF, "--out", str(ro)]) == 2
    _one_error_line(capsys, "read-only", "ro.nc", "0444")
    assert ro.read_bytes() == b"keep" and stat.S_IMODE(ro.stat().st_mode) == 0o444


# --- item 9: paths checked before computing ----------------------------------------------------------
def test_field_rejects_a_non_netcdf_name_before_computing(tmp_path, capsys, no_compute):
    out = tmp_path / "x.txt"
    assert main([*FIELD, "--out", str(out)]) == 2
    _one_error_line(capsys, ".nc", "x.txt")
    assert not out.exists()


@pytest.mark.parametrize("cmd", [["curve", *PULLOFF], ["compare", *PULLOFF], ["periphery", *PULLOFF], FIELD])
def test_empty_output_path_is_refused(cmd, capsys, no_compute):
    assert main([*cmd, "--out", ""]) == 2
    _one_error_line(capsys, "out", "empty")


def test_long_names_work_and_too_long_ones_fail_before_computing(tmp_path, capsys, no_compute):
    name_max = os.pathconf(tmp_path, "PC_NAME_MAX")
    too_long = tmp_path / ("b" * (name_max - 2) + ".nc")
    assert main([*FIELD, "--out", str(too_long)]) == 2
    _one_error_line(capsys, f"at most {name_max} bytes")
    longest = tmp_path / ("a" * (name_max - 3) + ".nc")
    assert main(["periphery", *PULLOFF, "--n-theta", "2", "--out", str(longest)]) == 0
    assert longest.is_file()


def test_missing_directory_fails_before_computing(tmp_path, capsys, no_compute):
    assert main([*FIELD, "--out", str(tmp_path / "no" / "f.nc")]) == 2
    _one_error_line(capsys, "does not exist")


# --- item 9: threads --------------------------------------------------------------------------------
@pytest.mark.parametrize("value", ["1000000", "0", "-3", "abc", "2.5"])
def test_threads_option_is_bounded(value, tmp_path, capsys, no_compute):
    assert main([*FIELD, "--threads", value, "--out", str(tmp_path / "f.nc")]) == 2
    _one_error_line(capsys, "--threads")


def test_bad_dhfield_threads_is_named(tmp_path, capsys, monkeypatch, no_compute):
    monkeypatch.setenv("DHFIELD_THREADS", "abc")
    assert main([*FIELD, "--out", str(tmp_path / "f.nc")]) == 2
    _one_error_line(capsys, "DHFIELD_THREADS", "'abc'")


# --- item 6: memory ---------------------------------------------------------------------------------
def test_field_too_large_for_memory_is_refused_before_allocating(tmp_path, capsys, monkeypatch, no_compute):
    """`field --n 100000` tried to allocate 74.5 GiB; the limit is tied to the memory available."""
    from dhfield.core import memory as _memory

    monkeypatch.setattr(_memory, "available_memory", lambda: 2**30)  # pretend 1 GiB is available
    # 160 B/cell x 4096^2 = 2.5 GiB > 0.8 GiB, while 1024^2 cells (0.16 GiB) fit
    assert main([*FIELD[:-1], "4096", "--out", str(tmp_path / "f.nc")]) == 2
    _one_error_line(capsys, "n=4096", "GiB", "available")
    fields.check_case_memory(1024)
    assert main([*FIELD[:-1], "100000", "--out", str(tmp_path / "f.nc")]) == 2
    _one_error_line(capsys, "n=100000")


def test_periphery_ray_count_is_bounded(capsys):
    """`periphery --n-theta 10000000` raised MemoryError."""
    assert main(["periphery", *PULLOFF, "--n-theta", "10000000"]) == 2
    _one_error_line(capsys, "n-theta", "100000")


# --- item 6: whatever escapes a subcommand is one line ----------------------------------------------
def test_memory_error_and_internal_errors_are_one_line(capsys, monkeypatch):
    from dhfield.cli import pulloff

    def oom(args):
        raise MemoryError()

    monkeypatch.setattr(pulloff, "run", oom)
    assert main(["pulloff", *PULLOFF]) == 2
    _one_error_line(capsys, "out of memory")

    def bug(args):
        raise RuntimeError("solver\ndid not converge")

    monkeypatch.setattr(pulloff, "run", bug)
    assert main(["pulloff", *PULLOFF]) == 1
    _one_error_line(capsys, "RuntimeError: solver did not converge", "DHFIELD_DEBUG", prefix="dhfield: internal error:")
    monkeypatch.setenv("DHFIELD_DEBUG", "1")
    with pytest.raises(RuntimeError):
        main(["pulloff", *PULLOFF])


def test_signals_in_main_give_their_exit_status(capsys, monkeypatch):
    import signal

    from dhfield.cli import pulloff

    def interrupted(args):
        signal.raise_signal(signal.SIGTERM)  # a real signal, converted to an exception by main()
        raise AssertionError("not reached")

    before = signal.getsignal(signal.SIGTERM)
    monkeypatch.setattr(pulloff, "run", interrupted)
    assert main(["pulloff", *PULLOFF]) == 143
    _one_error_line(capsys, "SIGTERM", prefix="dhfield: terminated")
    assert signal.getsignal(signal.SIGTERM) is before  # main() restored the handler

    def ctrl_c(args):
        raise KeyboardInterrupt

    monkeypatch.setattr(pulloff, "run", ctrl_c)
    assert main(["pulloff", *PULLOFF]) == 130
    _one_error_line(capsys, "SIGINT", prefix="dhfield: interrupted")


def test_cli_starts_without_the_heavy_imports():
    """Ctrl-C in the first 2.6 s (scipy's import, before main() runs) printed a traceback.

    Importing the CLI must not import scipy, numpy's linear algebra users or the models: they are
    imported inside main(), where a KeyboardInterrupt becomes one line and exit 130.
    """
    import subprocess
    import sys

    code = "import sys, dhfield.cli; print(sorted(m for m in ('scipy', 'dhfield.models.dh_elliptic', 'xarray') if m in sys.modules))"
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert res.returncode == 0, res.stderr
    assert res.stdout.strip() == "[]"


@pytest.mark.parametrize("command", ["field", "compare", "solve", "cycle"])
def test_help_says_what_the_command_does(capsys, command):
    """Issue 17: `field --help` had no description (usage and options only)."""
    with pytest.raises(SystemExit):
        main([command, "--help"])
    text = capsys.readouterr().out
    head = text.split("options:")[0]
    assert len(head.split("\n\n", 1)[-1].split()) >= 20, head   # a paragraph beyond the usage lines


def test_bem_commands_use_the_machine_unless_told(monkeypatch):
    """--threads wins, then $DHFIELD_THREADS, then the CPUs this process may use (at most 4); the
    library's own default stays 1 thread (results reproducible from one machine to another)."""
    import os

    from dhfield.bem import default_threads
    from dhfield.cli._common import CLI_DEFAULT_MAX_THREADS, command_threads

    monkeypatch.delenv("DHFIELD_THREADS", raising=False)
    monkeypatch.setattr(os, "getloadavg", lambda: (0.0, 0.0, 0.0))  # an idle machine (issue 42: load counts)
    assert default_threads() == 1
    assert command_threads(3) == 3
    cpus = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
    assert command_threads() == max(1, min(cpus, CLI_DEFAULT_MAX_THREADS))
    monkeypatch.setenv("DHFIELD_THREADS", "1")
    assert command_threads() == 1 and command_threads(2) == 2
