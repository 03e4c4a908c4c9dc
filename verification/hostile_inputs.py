"""Hostile-input campaign: try hundreds of bad inputs on the dhfield CLI and Python API (issue 9).

Every numeric option of every subcommand (found in the argparse parser, so new
subcommands are covered), bad output paths (directories, device nodes, FIFOs,
symbolic links, read-only files, missing directories, over-long and empty
names), bad environment variables, signals in the middle of a run, and bad
arguments to the public Python functions.  Each case runs in a forked child of
this process (dhfield is imported once) in its own temporary directory, with a
timeout.  Outcomes:

* ``clean error``     exit 2 and exactly one line on stderr, ``dhfield: error: ...``;
                      for the API, a ValueError naming the parameter;
* ``accepted``        exit 0 with a sane output (finite numbers; pull-off in [DMT, 0));
* ``clean signal``    exit 128 + n after signal n, one line, nothing left behind;
* ``noisy error``     exit 2 but more than one line on stderr (e.g. warnings first);
* ``unnamed error``   API ValueError that does not name the parameter;
* ``traceback``       a traceback, or an exception other than ValueError from the API;
* ``internal error``  the CLI's one-line report of an unexpected exception (exit 1);
* ``hang``            no exit within the timeout;
* ``silent wrong``    exit 0 (or a return value) with a non-finite or unphysical result;
* ``clobbered``       the target changed although it must not have, or a ``.part`` was left.

Usage::

    python verification/hostile_inputs.py            # the whole campaign (a few minutes)
    python verification/hostile_inputs.py --quick     # a subset (about a minute)
    python verification/hostile_inputs.py --issue18   # only the classes added for issue 18
    python verification/hostile_inputs.py --issue42-writes   # issue 42: sweep stores, memory, sets of files, paths
    python verification/hostile_inputs.py --issue42-inputs   # issue 42: '--opt=--', flagged fits, messages' units

It prints the counts per outcome and lists every case that is not clean.
Exit status 0 when there is no traceback, hang, silent wrong output or
clobbered file, else 1.
"""
from __future__ import annotations

import argparse
import contextlib
import io
import json
import os
import pickle
import signal
import stat
import sys
import tempfile
import time
import traceback
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

CLEAN = ("clean error", "accepted", "clean signal")
DEFECTS = ("traceback", "hang", "silent wrong", "clobbered")
TRACEBACK_STATUS = 99  # exit status of a child whose main() raised

#: Bad values for float options ("" and "abc" are not numbers; 1e400 overflows to inf).
FLOAT_VALUES = ("nan", "inf", "-inf", "1e308", "-1e308", "1e-308", "0", "-1", "abc", "", "1e400", "0x10")
#: Bad values for integer options.
INT_VALUES = ("0", "-1", "2.5", "abc", "", "1e3", "99999999999", "-99999999999", "nan")
QUICK_FLOAT_VALUES = ("nan", "-1", "abc", "1e308", "1e-308")
QUICK_INT_VALUES = ("0", "abc", "99999999999")

#: Small, fast valid invocations; the numeric options are mutated one at a time from these.
SI = ["--youngs-modulus", "1e6", "--poisson-ratio", "0.5", "--cylinder-radius", "0.01", "--skew-angle-deg",
      "60", "--work-of-adhesion", "0.05", "--adhesive-stress", "1e6"]
BASELINES = {
    "curve": [["--beta0", "0.9", "--mu", "1", "--n", "5"], [*SI, "--n", "5"]],
    "pulloff": [["--beta0", "0.9", "--mu", "1", "--json"], [*SI, "--json"]],
    "compare": [["--beta0", "0.9", "--mu", "1", "--json"], [*SI, "--json"]],
    "periphery": [["--beta0", "0.9", "--mu", "1", "--n-theta", "3", "--json"]],
    "field": [["--beta0", "0.9", "--mu", "1", "--a-star", "1.2", "--n", "16", "--out", "f.nc"]],
    "solve": [["--beta0", "0.9", "--mu", "1", "--n", "32", "--json"]],
    "fit": [["--pull-off-force", "-0.002", *SI, "--json"]],
    "sweep": [["--beta0", "0.9", "--mu", "1", "--models", "jkr", "--workers", "1", "--out", "s.nc", "--quiet"]],
}
#: Values used for required options of subcommands without a baseline, by option name.
GENERIC_VALUES = {"beta0": "0.9", "mu": "1", "a_star": "1.2", "n": "16", "n_theta": "3"}
FILE_SUFFIX = {"curve": ".nc", "compare": ".nc", "periphery": ".nc", "field": ".nc", "solve": ".nc", "sweep": ".nc"}
SIGNALS = ("SIGINT", "SIGTERM", "SIGHUP")
#: Non-zero exits that flag a computed result as not an answer (one line on stderr): counted clean.
FLAGGED_STATUS = {"solve": (3, 4, 5), "sweep": (3,), "fit": (3,)}


@dataclass
class Case:
    kind: str                 # "cli", "path", "env", "signal", "api"
    label: str
    argv: list = field(default_factory=list)
    env: dict = field(default_factory=dict)
    setup: object = None      # f(workdir) -> dict of facts to check afterwards
    expect: str = "reject"    # "reject", "ok", "either", "signal"
    signal_after: tuple = ()  # (signal name, seconds)
    api: object = None        # f() for API cases
    param: str = ""           # the parameter an API rejection must name
    check: object = None      # f(workdir, status, stdout, stderr) -> None or (outcome, detail), after classify
    outcome: str = ""
    detail: str = ""


# --------------------------------------------------------------------------- running a case in a fork
def _child(case: Case, workdir: Path, out_fd: int, err_fd: int) -> None:
    os.dup2(out_fd, 1)
    os.dup2(err_fd, 2)
    sys.stdout = io.TextIOWrapper(os.fdopen(1, "wb", closefd=False), line_buffering=True)
    sys.stderr = io.TextIOWrapper(os.fdopen(2, "wb", closefd=False), line_buffering=True)
    status = 0
    try:
        os.chdir(workdir)
        for k, v in case.env.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v
        signal.signal(signal.SIGINT, signal.default_int_handler)
        if case.kind == "api":
            try:
                value = case.api()
            except ValueError as exc:
                print(json.dumps({"raised": "ValueError", "message": str(exc)}))
            except Exception as exc:  # noqa: BLE001 - classified by the parent
                print(json.dumps({"raised": type(exc).__name__, "message": str(exc)}))
                traceback.print_exc()
            else:
                print(json.dumps({"returned": _summary(value)}))
        else:
            from dhfield.cli import main

            status = int(main(case.argv) or 0)
    except SystemExit as exc:
        status = exc.code if isinstance(exc.code, int) else 1
    except BaseException:  # noqa: BLE001 - a traceback is an outcome here
        traceback.print_exc()
        status = TRACEBACK_STATUS
    finally:
        with contextlib.suppress(Exception):
            sys.stdout.flush()
            sys.stderr.flush()
        os._exit(status)


def _summary(value):
    """Finite-ness and the numbers of an API return value, for the parent to judge."""
    nums = []

    def walk(v, depth=0):
        if depth > 3:
            return
        if isinstance(v, (int, float, np.number)) and not isinstance(v, bool):
            nums.append(float(v))
        elif isinstance(v, np.ndarray) and v.dtype.kind in "iuf":
            nums.extend(np.asarray(v, dtype=float).ravel()[:10000].tolist())
        elif isinstance(v, dict):
            for x in v.values():
                walk(x, depth + 1)
        elif isinstance(v, (list, tuple)):
            for x in v:
                walk(x, depth + 1)
        elif hasattr(v, "__dataclass_fields__"):
            for k in v.__dataclass_fields__:
                walk(getattr(v, k), depth + 1)

    if isinstance(value, dict) and "silent_wrong" in value:  # an API case that judges its own result
        return {"n": 1, "finite": True, "W_star": None, "silent_wrong": str(value["silent_wrong"])}
    walk(value)
    arr = np.asarray(nums, dtype=float)
    w = _w_star(value)
    # NaN marks quantities a model does not have (c* of JKR); only W* must always be finite
    return {"n": int(arr.size), "finite": w is None or bool(np.all(np.isfinite(w))), "W_star": w}


def _w_star(value):
    w = getattr(value, "W_star", None)
    if w is None and isinstance(value, dict):
        w = value.get("W_star")
    try:
        return [float(x) for x in np.ravel(w)] if w is not None else None
    except (TypeError, ValueError):
        return None


def run_case(case: Case, timeout: float) -> None:
    with tempfile.TemporaryDirectory(prefix="dhf-hostile-") as tmp:
        workdir = Path(tmp)
        (workdir / "cache").mkdir()
        case.env.setdefault("DHFIELD_CACHE", str(workdir / "cache"))
        facts = case.setup(workdir) if case.setup else {}
        with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
            pid = os.fork()
            if pid == 0:
                _child(case, workdir, out.fileno(), err.fileno())
            t0 = time.monotonic()
            sent = False
            status = None
            while True:
                done, wstatus = os.waitpid(pid, os.WNOHANG)
                if done:
                    status = os.waitstatus_to_exitcode(wstatus)
                    break
                elapsed = time.monotonic() - t0
                if case.signal_after and not sent and elapsed >= case.signal_after[1]:
                    os.kill(pid, getattr(signal, case.signal_after[0]))
                    sent = True
                if elapsed > timeout:
                    os.kill(pid, signal.SIGKILL)
                    os.waitpid(pid, 0)
                    break
                time.sleep(0.005)
            out.seek(0)
            err.seek(0)
            stdout = out.read().decode(errors="replace")
            stderr = err.read().decode(errors="replace")
        try:
            classify(case, status, stdout, stderr, workdir, facts, sent)
            if case.check is not None and case.outcome in CLEAN and status is not None:
                verdict = case.check(workdir, status, stdout, stderr)
                if verdict:
                    case.outcome, case.detail = verdict
        finally:
            if facts.get("teardown"):
                facts["teardown"]()


# --------------------------------------------------------------------------- classification
def _state(path: Path):
    """What a target is, to tell whether it was replaced or modified."""
    try:
        st = os.lstat(path)
    except FileNotFoundError:
        return None
    link = os.readlink(path) if stat.S_ISLNK(st.st_mode) else None
    data = path.read_bytes() if stat.S_ISREG(st.st_mode) else None
    return (stat.S_IFMT(st.st_mode), stat.S_IMODE(st.st_mode), st.st_ino, link, data)


def _left_behind(workdir: Path):
    return [str(p.relative_to(workdir)) for p in workdir.rglob("*") if p.name.endswith(".part")]


_NONFINITE = ("nan", "inf", "null")


def _sane_stdout(case: Case, stdout: str):
    """None if the accepted output looks right, else the reason."""
    text = stdout.strip()
    if text.startswith("{"):
        try:
            rec = json.loads(text)
        except ValueError:
            return "unparsable JSON"
        return _sane_record(case, rec)
    low = text.lower()
    for word in _NONFINITE:
        for tok in low.replace(",", " ").split():
            if tok.strip("[]()") in (word, "-" + word):
                return f"non-finite number ({tok}) in the output"
    return None


def _sane_record(case, rec):
    """Every pull-off record: W* finite and in [DMT, 0) = [-1, 0) (Eq. 34 normalisation), or a stated failure.

    Other nulls are fields a model does not have (e.g. c* of JKR) and are fine.
    """
    records = rec.get("models", [rec]) if isinstance(rec, dict) else []
    for m in records if isinstance(records, list) else []:
        if not isinstance(m, dict) or "W_star" not in m:
            continue
        w = m["W_star"]
        name = m.get("model", "")
        if w is None:
            if not (m.get("warning") or m.get("error")):
                return f"W* is null (non-finite) without a stated reason ({name})"
        elif not -1.0 - 1e-9 <= w < 0.0:
            return f"pull-off W* = {w} outside [DMT = -1, 0) ({name})"
    return None


def classify(case: Case, status, stdout: str, stderr: str, workdir: Path, facts: dict, sent: bool) -> None:
    lines = [ln for ln in stderr.strip().splitlines() if ln.strip()]
    left = _left_behind(workdir)
    changed = [name for name, before in facts.get("targets", {}).items() if _state(workdir / name) != before]
    if status is None:
        case.outcome, case.detail = "hang", "killed after the timeout"
        return
    if left:
        case.outcome, case.detail = "clobbered", f"left behind: {left}"
        return
    if "Traceback (most recent call last)" in stderr or status == TRACEBACK_STATUS:
        case.outcome, case.detail = "traceback", (lines[-1] if lines else "")[:160]
        if case.kind == "api" and stdout.strip().startswith("{"):
            with contextlib.suppress(ValueError):
                rec = json.loads(stdout.strip().splitlines()[0])
                case.detail = f"{rec.get('raised')}: {rec.get('message', '')}"[:160]
        return
    if case.kind == "api":
        return _classify_api(case, stdout)
    if changed and (case.expect in ("reject", "signal") or status != 0):
        case.outcome, case.detail = "clobbered", f"changed: {changed} (exit {status})"
        return
    if case.kind == "signal":
        if not sent:
            case.outcome, case.detail = "accepted", "finished before the signal"
            return
        want = 128 + getattr(signal, case.signal_after[0])
        if status == want and len(lines) == 1 and lines[0].startswith("dhfield: "):
            outputs = [p for p in workdir.iterdir() if p.name not in ("cache",)]
            case.outcome = "clean signal" if not outputs else "clobbered"
            case.detail = "" if not outputs else f"output present after the signal: {outputs}"
        elif status == 0:
            case.outcome, case.detail = "accepted", "finished before the signal took effect"
        else:
            case.outcome, case.detail = "traceback", f"exit {status}: {' | '.join(lines[-2:])[:160]}"
        return
    if status == 2:
        if lines and lines[-1].startswith("dhfield: error:"):
            case.outcome = "clean error" if len(lines) == 1 else "noisy error"
            case.detail = lines[-1][:160] if len(lines) == 1 else f"{len(lines)} lines: {lines[0][:100]}"
        else:
            case.outcome, case.detail = "traceback", f"exit 2 without the one-line error: {stderr[:160]}"
        return
    if status in FLAGGED_STATUS.get(case.argv[0] if case.argv else "", ()):
        # solve: 3 unconverged, 4 unresolved, 5 refused before solving (cannot be resolved within memory/time,
        # or --n far too coarse); sweep: 3 flagged cases; fit: 3 a parameter not identifiable -- the answer is
        # refused, in one line (beside any 'dhfield: warning:' lines of the result's own warning)
        said = [ln for ln in lines if not ln.startswith("dhfield: warning:")]
        if len(said) == 1:
            case.outcome, case.detail = "clean error", f"flagged, exit {status}: {said[0][:140]}"
        else:
            case.outcome, case.detail = "noisy error", f"flagged, exit {status}, {len(said)} lines"
        return
    if status == 1 and lines and lines[-1].startswith("dhfield: internal error"):
        case.outcome, case.detail = "internal error", lines[-1][:200]
        return
    if status == 0:
        reason = _sane_stdout(case, stdout)
        if reason:
            case.outcome, case.detail = "silent wrong", reason
        elif case.kind == "path" and case.expect == "reject":
            case.outcome, case.detail = "clobbered", "a path that must be refused was accepted"
        else:
            case.outcome = "accepted"
            case.detail = f"{len(lines)} warning line(s)" if lines else ""
        return
    case.outcome, case.detail = "traceback", f"exit {status}: {' | '.join(lines[-2:])[:160]}"


def _classify_api(case: Case, stdout: str) -> None:
    try:
        rec = json.loads(stdout.strip().splitlines()[0])
    except (ValueError, IndexError):
        case.outcome, case.detail = "traceback", "no result from the child"
        return
    if rec.get("raised") == "ValueError":
        msg = rec.get("message", "")
        named = case.param.lower() in msg.lower().replace("-", "_") or case.param.lower() in msg.lower()
        case.outcome = "clean error" if named and "\n" not in msg else "unnamed error"
        case.detail = msg[:160]
    elif "raised" in rec:
        case.outcome, case.detail = "traceback", f"{rec['raised']}: {rec.get('message', '')}"[:160]
    else:
        summ = rec["returned"]
        if summ.get("silent_wrong"):
            case.outcome, case.detail = "silent wrong", summ["silent_wrong"][:160]
        elif not summ["finite"]:
            case.outcome, case.detail = "silent wrong", "non-finite number in the result"
        elif "pull_off" in case.label and summ.get("W_star") and \
                any(not (-1.0 - 1e-9 <= w < 0.0) for w in summ["W_star"]):
            case.outcome, case.detail = "silent wrong", f"W* = {summ['W_star'][:3]} outside [DMT = -1, 0)"
        elif case.expect == "reject":
            case.outcome, case.detail = "silent wrong", "accepted an input that must be refused"
        else:
            case.outcome, case.detail = "accepted", ""


# --------------------------------------------------------------------------- building the cases
def subcommand_parsers():
    from dhfield.cli import build_parser

    parser = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return dict(sub.choices)


def _numeric_actions(sp):
    out = []
    for a in sp._actions:
        if not a.option_strings or a.dest == "help":
            continue
        t = a.type
        kind = "float" if t is float else "int" if t is int else getattr(t, "__name__", "") if t else ""
        if kind in ("float", "int", "thread_count"):
            out.append((a, "int" if kind == "thread_count" else kind))
    return out


def _baselines(name, sp):
    if name in BASELINES:
        return [[name, *b] for b in BASELINES[name]]
    argv = [name]
    for a in sp._actions:
        if a.required and a.option_strings:
            if a.dest not in GENERIC_VALUES and a.dest != "out":
                return []
            argv += [a.option_strings[0], GENERIC_VALUES.get(a.dest, f"o{FILE_SUFFIX.get(name, '.nc')}")]
        elif a.required:
            return []  # a positional we cannot invent
    return [argv]


def _with_value(baseline, action, value):
    opt = action.option_strings[0]
    nargs = action.nargs if isinstance(action.nargs, int) else 1
    argv = list(baseline)
    if opt in argv:
        i = argv.index(opt)
        j = i + 1
        while j < len(argv) and not argv[j].startswith("--"):
            j += 1
        vals = argv[i + 1:j] or ["1"] * nargs
        vals[0] = value
        return argv[:i + 1] + vals + argv[j:]
    return argv + [opt, value] + ["1"] * (nargs - 1)


def numeric_cases(parsers, quick):
    cases = []
    for name, sp in parsers.items():
        bases = _baselines(name, sp)
        if not bases:
            continue
        si_flags = {"--youngs-modulus", "--poisson-ratio", "--youngs-modulus-2", "--poisson-ratio-2",
                    "--cylinder-radius", "--radii", "--principal-radii", "--skew-angle-deg",
                    "--work-of-adhesion", "--adhesive-stress"}
        for action, kind in _numeric_actions(sp):
            opt = action.option_strings[0]
            base = bases[-1] if (opt in si_flags and len(bases) > 1) else bases[0]
            if opt in si_flags and len(bases) == 1 and not any(f in base for f in si_flags):
                continue  # this subcommand has no SI baseline
            values = (QUICK_INT_VALUES if quick else INT_VALUES) if kind == "int" else \
                (QUICK_FLOAT_VALUES if quick else FLOAT_VALUES)
            for v in values:
                cases.append(Case("cli", f"{name} {opt} {v!r}", _with_value(base, action, v), expect="either"))
    return cases


def _path_setups(suffix):
    """(label, out argument, setup, expectation) for hostile output paths."""
    def plain(name, content=b"previous\n", mode=0o644):
        def setup(w):
            (w / name).write_bytes(content)
            os.chmod(w / name, mode)
            return {"targets": {name: _state(w / name)}}
        return setup

    def directory(w):
        (w / f"d{suffix}").mkdir()
        return {"targets": {f"d{suffix}": _state(w / f"d{suffix}")}}

    def fifo(w):
        os.mkfifo(w / f"p{suffix}")
        return {"targets": {f"p{suffix}": _state(w / f"p{suffix}")}}

    def device(w):
        os.mknod(w / f"null{suffix}", stat.S_IFCHR | 0o666, os.makedev(1, 3))
        return {"targets": {f"null{suffix}": _state(w / f"null{suffix}")}}

    def symlink(w):
        (w / f"real{suffix}").write_bytes(b"keep\n")
        (w / f"link{suffix}").symlink_to(w / f"real{suffix}")
        return {"targets": {f"link{suffix}": _state(w / f"link{suffix}"), f"real{suffix}": _state(w / f"real{suffix}")}}

    def dangling(w):
        (w / f"dang{suffix}").symlink_to(w / f"nowhere{suffix}")
        return {"targets": {f"dang{suffix}": _state(w / f"dang{suffix}"), f"nowhere{suffix}": None}}

    def missing(w):
        return {"targets": {"nodir": None}}

    name_max = os.pathconf(tempfile.gettempdir(), "PC_NAME_MAX")
    longest = "a" * (name_max - len(suffix)) + suffix
    too_long = "b" * (name_max + 1 - len(suffix)) + suffix
    rows = [
        ("directory", f"d{suffix}", directory, "reject"),
        ("FIFO", f"p{suffix}", fifo, "reject"),
        ("symlink to a file", f"link{suffix}", symlink, "reject"),
        ("dangling symlink", f"dang{suffix}", dangling, "reject"),
        ("read-only file 0444", f"ro{suffix}", plain(f"ro{suffix}", mode=0o444), "reject"),
        ("missing directory", f"nodir/x{suffix}", missing, "reject"),
        ("empty path", "", None, "reject"),
        ("trailing slash", f"x{suffix}/", None, "reject"),
        (f"name of {name_max + 1} bytes", too_long, None, "reject"),
        (f"name of {name_max} bytes", longest, None, "ok"),
        ("existing writable file", f"old{suffix}", plain(f"old{suffix}", mode=0o640), "ok"),
        ("wrong suffix .txt", "x.txt", None, "reject"),
    ]
    if os.geteuid() == 0:
        rows.insert(1, ("device node (as /dev/null)", f"null{suffix}", device, "reject"))
    return rows


def path_cases(parsers, quick):
    cases = []
    for name, sp in parsers.items():
        if name not in FILE_SUFFIX or not any("--out" in a.option_strings for a in sp._actions):
            continue
        bases = _baselines(name, sp)
        if not bases:
            continue
        base = [a for a in bases[0]]
        if "--out" in base:
            i = base.index("--out")
            base = base[:i] + base[i + 2:]
        rows = _path_setups(FILE_SUFFIX[name])
        if quick:
            rows = rows[:4]
        for label, out, setup, expect in rows:
            if name == "sweep" and label in ("wrong suffix .txt", "directory", "trailing slash"):
                continue  # sweep writes FILE.nc or a directory
            cases.append(Case("path", f"{name} --out <{label}>", [*base, "--out", out], setup=setup, expect=expect))
    return cases


def input_cases(parsers, quick):
    """Bad input files: missing, garbage, a directory, a FIFO (must not block), an empty file."""
    def garbage(name):
        def setup(w):
            (w / name).write_bytes(b"\x89HDF garbage " * 50)
            return {}
        return setup

    def empty(name):
        def setup(w):
            (w / name).write_bytes(b"")
            return {}
        return setup

    def fifo(name):
        def setup(w):
            os.mkfifo(w / name)
            return {}
        return setup

    def directory(name):
        def setup(w):
            (w / name).mkdir()
            return {}
        return setup

    specs = [("missing", None), ("garbage", garbage), ("empty", empty), ("FIFO", fifo), ("directory", directory)]
    commands = []
    if "plot" in parsers:
        commands.append(("plot", lambda f: ["plot", f], "in.nc"))
    if "fit" in parsers and any("--data" in a.option_strings for a in parsers["fit"]._actions):
        commands.append(("fit --data", lambda f: ["fit", "--data", f, *SI, "--json"], "in.csv"))
    if "sweep" in parsers:
        commands.append(("sweep CONFIG", lambda f: ["sweep", f, "--out", "s.nc", "--quiet"], "in.toml"))
    cases = []
    for label, build, name in commands:
        for what, setup in specs[: 3 if quick else 5]:
            cases.append(Case("cli", f"{label} <{what} input file>", build(name),
                              setup=setup(name) if setup else None, expect="reject"))
    return cases


def env_cases(quick):
    base = ["field", "--beta0", "0.9", "--mu", "1", "--a-star", "1.2", "--n", "16", "--out", "f.nc"]
    cases = []
    for v in ("abc", "0", "-1", "1000000", "1.5", "", " 2 ", "1e3", "nan"):
        expect = "ok" if v.strip() in ("", "2") else "reject"
        cases.append(Case("env", f"DHFIELD_THREADS={v!r} field", base, env={"DHFIELD_THREADS": v}, expect=expect))

    def bomb(w):
        marker = w / "PWNED"
        blob = pickle.dumps(_Bomb(str(marker)))
        (w / "cache" / "fftw_wisdom.bin").write_bytes(blob)
        import pyfftw

        (w / "cache" / f"fftw_wisdom_pyfftw{pyfftw.__version__}.pickle").write_bytes(blob)
        return {"targets": {"PWNED": None}}

    def garbage(w):
        (w / "cache" / "fftw_wisdom.bin").write_bytes(os.urandom(4096))
        return {}

    def cache_is_file(w):
        (w / "cachefile").write_text("x")
        return {}

    specs = [("DHFIELD_CACHE with a pickle bomb", {}, bomb), ("DHFIELD_CACHE with garbage", {}, garbage),
             ("DHFIELD_CACHE is a file", {"DHFIELD_CACHE": "cachefile"}, cache_is_file),
             ("DHFIELD_CACHE under a file", {"DHFIELD_CACHE": "cachefile/sub"}, cache_is_file),
             ("DHFIELD_CACHE empty", {"DHFIELD_CACHE": ""}, None),
             ("HOME missing, no DHFIELD_CACHE", {"DHFIELD_CACHE": None, "HOME": "/nonexistent-home"}, None),
             ("DHFIELD_DEBUG=1 with a bad input", {"DHFIELD_DEBUG": "1"}, None)]
    for label, env, setup in specs:
        argv = base if "DEBUG" not in label else ["pulloff", "--beta0", "7", "--mu", "1"]
        cases.append(Case("env", label, argv, env=dict(env), setup=setup,
                          expect="reject" if "DEBUG" in label else "ok"))
    return cases[:4] + cases[-3:] if quick else cases


class _Bomb:
    def __init__(self, marker):
        self.marker = marker

    def __reduce__(self):
        return (exec, (f"open({self.marker!r}, 'w').write('pwned')",))


def signal_cases(quick):
    cases = []
    heavy = ["field", "--beta0", "0.9", "--mu", "1", "--a-star", "1.2", "--n", "1024", "--out", "f.nc"]
    times = (0.3, 2.0, 5.0) if quick else (0.3, 1.0, 2.5, 4.0, 6.0, 9.0)
    for sig in SIGNALS:
        for t in times:
            cases.append(Case("signal", f"{sig} after {t} s of field --n 1024", heavy, signal_after=(sig, t),
                              expect="signal"))
    for cmd in (["periphery", "--beta0", "0.9", "--mu", "1", "--n-theta", "50", "--out", "p.nc"],
                ["curve", "--beta0", "0.9", "--mu", "1", "--out", "c.nc"]):
        for sig in SIGNALS[: 1 if quick else 3]:
            cases.append(Case("signal", f"{sig} after 0.2 s of {cmd[0]}", cmd, signal_after=(sig, 0.2),
                              expect="signal"))
    for sig in SIGNALS:  # a real process: the signal lands while Python still imports dhfield
        cases.append(Case("process", f"{sig} after 0.3 s of a fresh `python -m dhfield.cli pulloff`",
                          [sys.executable, "-m", "dhfield.cli", "pulloff", "--beta0", "0.9", "--mu", "1"],
                          signal_after=(sig, 0.3), expect="signal"))
    return cases


def run_process(case: Case, timeout: float) -> None:
    """Run ``case.argv`` as a real process (not a fork) and send its signal."""
    import subprocess

    with tempfile.TemporaryDirectory(prefix="dhf-hostile-") as tmp:
        workdir = Path(tmp)
        env = dict(os.environ, DHFIELD_CACHE=str(workdir / "cache"))
        proc = subprocess.Popen(case.argv, cwd=workdir, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                text=True, preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
        time.sleep(case.signal_after[1])
        sent = proc.poll() is None
        if sent:
            proc.send_signal(getattr(signal, case.signal_after[0]))
        try:
            _, stderr = proc.communicate(timeout=timeout)
            status = proc.returncode
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.communicate()
            status, stderr = None, ""
        signum = getattr(signal, case.signal_after[0])
        lines = [ln for ln in stderr.strip().splitlines() if ln.strip()]
        if status is None:
            case.outcome, case.detail = "hang", "killed after the timeout"
        elif _left_behind(workdir):
            case.outcome, case.detail = "clobbered", f"left behind: {_left_behind(workdir)}"
        elif "Traceback (most recent call last)" in stderr:
            case.outcome, case.detail = "traceback", f"exit {status}: {lines[-1][:120] if lines else ''}"
        elif status in (-signum, 128 + signum) and len(lines) <= 1:
            case.outcome = "clean signal"
            case.detail = "ended by the signal's default action" if status < 0 else ""
        elif not sent or status == 0:
            case.outcome, case.detail = "accepted", "finished before the signal"
        else:
            case.outcome, case.detail = "traceback", f"exit {status}: {' | '.join(lines[-2:])[:120]}"


def api_cases(quick):
    """Bad arguments to the public Python functions."""
    from dhfield import bem
    from dhfield.analysis import compare, dimensional, fields
    from dhfield.models import dh_elliptic as model
    from dhfield import io as dio

    bad_scalars = [("nan", float("nan")), ("inf", float("inf")), ("-1", -1.0), ("0", 0.0), ("'abc'", "abc"),
                   ("None", None), ("1e308", 1e308), ("1e-308", 1e-308), ("[]", []),
                   ("masked", np.ma.masked_array([1.0, 2.0], mask=[False, True])), ("True", True)]
    if quick:
        bad_scalars = bad_scalars[:6]
    cases = []

    def add(label, fn, param, expect="either"):
        cases.append(Case("api", label, api=fn, param=param, expect=expect))

    for lab, v in bad_scalars:
        # True is the integer 1 and an empty array may give an empty result: either answer is fine
        must = "reject" if lab in ("nan", "inf", "-1", "0", "'abc'", "None") else "either"
        add(f"model.pull_off(mu={lab})", lambda v=v: model.pull_off(mu=v, beta0=0.9), "mu", must)
        add(f"model.pull_off(beta0={lab})", lambda v=v: model.pull_off(mu=1.0, beta0=v), "beta0", must)
        add(f"model.load_curve(mu={lab})", lambda v=v: model.load_curve(mu=v, beta0=0.9, n=5), "mu", must)
        add(f"model.load_curve(beta0={lab})", lambda v=v: model.load_curve(mu=1.0, beta0=v, n=5), "beta0", must)
        for name in ("jkr", "dmt", "md", "dh-circular", "jkr-elliptic"):
            add(f"compare.pull_off({name!r}, mu={lab})", lambda v=v, n=name: compare.pull_off(n, mu=v, beta0=0.9), "mu", must)
        add(f"fields.model_case(n={lab})", lambda v=v: fields.model_case(v, 0.9, 1.0, 1.2), "n",
            "reject" if lab != "1e-308" else "reject")
        add(f"bem.Grid(nx={lab})", lambda v=v: bem.Grid(v, 16, 0.1, 0.1), "nx", "reject")
        add(f"bem.Grid(dx={lab})", lambda v=v: bem.Grid(16, 16, v, 0.1), "dx",
            "reject" if lab not in ("1e308", "1e-308", "True", "[]", "masked") else "either")
    for n in (2.5, 0, -3, 1, "5"):
        add(f"model.load_curve(n={n!r})", lambda n=n: model.load_curve(mu=1.0, beta0=0.9, n=n), "n", "reject")
    add("model.pull_off(mu=array with nan)", lambda: model.pull_off(mu=np.array([1.0, np.nan]), beta0=0.9), "mu", "reject")
    add("model.pull_off(empty arrays)", lambda: model.pull_off(mu=np.array([]), beta0=np.array([])), "mu", "either")
    add("bem.surface_displacement(nan pressure)",
        lambda: bem.surface_displacement(np.full((16, 16), np.nan), 0.1), "pressure", "reject")
    add("bem.surface_displacement(1-D)", lambda: bem.surface_displacement(np.ones(16), 0.1), "pressure", "reject")
    add("fields.check_case_memory(100000)", lambda: fields.check_case_memory(100000), "n=100000", "reject")
    add("dimensional.contact_parameters(skew_angle=1e-12)",
        lambda: dimensional.contact_parameters(1e6, 0.5, 1e6, 0.5, 0.01, 1e-12, 0.05, 1e6), "skew_angle", "either")
    add("dimensional.contact_parameters(youngs_modulus=-1)",
        lambda: dimensional.contact_parameters(-1.0, 0.5, 1e6, 0.5, 0.01, 1.0, 0.05, 1e6), "youngs_modulus",
        "reject")
    add("dimensional.contact_parameters(poisson=0.7)",
        lambda: dimensional.contact_parameters(1e6, 0.7, 1e6, 0.5, 0.01, 1.0, 0.05, 1e6), "poisson", "reject")

    def write_to(target):
        import xarray as xr

        return lambda: dio.write_netcdf(xr.Dataset({"a": ("x", np.arange(3.0))}), target)

    for target in ("", "missing/x.nc", ".", "/proc/version", "x\0.nc"):
        add(f"io.write_netcdf(path={target!r})", write_to(target), "out", "reject")
    add("io.read_netcdf(path=/etc/passwd)", lambda: dio.read_netcdf("/etc/passwd"), "input file", "reject")
    add("io.read_netcdf(path=missing)", lambda: dio.read_netcdf("missing.nc"), "input file", "reject")
    return cases


# --------------------------------------------------------------------------- issue 18: new classes of input
#: Relative error beyond which a BEM pull-off that calls itself resolved and converged is a silent
#: wrong answer: the discretisation errors the solver states are a few per cent; the failures of
#: issue 18 were +58 % to +381 %.  Exponential law against Maugis-Dugdale (another law): 50 %.
BEM_SILENT_RTOL = 0.10
BEM_SILENT_RTOL_OTHER_LAW = 0.5
#: Issue 18: the ray-average closure at (beta0, mu) = (0.3, 10) gives -0.47 to -0.50.
CLOSURE_03_10 = -0.485


def _bem_verdict(mu, beta0, n, reference, rtol=BEM_SILENT_RTOL, **kw):
    """An API case: the BEM pull-off must be flagged (resolved/converged false) or near ``reference``."""
    def run():
        from dataclasses import fields

        from dhfield import bem
        from dhfield.analysis import compare
        from dhfield.analysis.bem_start import AdhesiveOptions

        ref = compare.pull_off("md", mu=mu, beta0=1.0)["W_star"] if reference == "md" else reference
        numerics = {f.name for f in fields(AdhesiveOptions)}
        res = bem.adhesive_pull_off(mu=mu, beta0=beta0, n=n, progress=False,
                                    **{k: v for k, v in kw.items() if k not in numerics},
                                    options=AdhesiveOptions(**{k: v for k, v in kw.items() if k in numerics}))
        ok = bool(getattr(res, "resolved", True)) and bool(res.converged)
        w = float(res.W_star)
        if ok and not (abs(w - ref) <= rtol * abs(ref)):
            return {"silent_wrong": f"W* = {w:.4g}, resolved and converged, reference {float(ref):.4g} "
                                    f"(> {rtol:.0%} off)"}
        return {"answer": w} if ok else {"flagged": True}   # a flagged W* is not an answer: not judged
    return run


def _json_w_check(reference, rtol=BEM_SILENT_RTOL):
    """A CLI check: `solve --json` exiting 0 must give W* within rtol of the reference."""
    def check(workdir, status, stdout, stderr):
        if status != 0:
            return None
        try:
            rec = json.loads(stdout.strip().splitlines()[0])
        except (ValueError, IndexError):
            return ("silent wrong", "unparsable JSON from solve")
        from dhfield.analysis import compare

        ref = compare.pull_off("md", mu=rec["mu"], beta0=1.0)["W_star"] if reference == "md" else reference
        w = rec.get("W_star")
        if w is None or abs(w - ref) > rtol * abs(ref):
            return ("silent wrong", f"exit 0 with W* = {w}, reference {ref:.4g}")
        return None
    return check


def _sweep_status_check(name="adh.nc"):
    """A CLI check: a sweep exiting 0 must not store an unresolved/unconverged adhesive case as ok."""
    def check(workdir, status, stdout, stderr):
        if status != 0:
            return None
        import xarray as xr

        with xr.open_dataset(workdir / name) as ds:
            st = ds["status"].sel(model="bem-adhesive").values
        if (st == 0).all():
            return ("silent wrong", "unresolved adhesive case stored with status 0 and exit 0")
        return None
    return check


def _nothing_written_check(*names):
    def check(workdir, status, stdout, stderr):
        present = [n for n in names if (workdir / n).exists()]
        return ("clobbered", f"wrote {present} into the working directory") if present else None
    return check


def _synthetic_sweep(path, n_ell=3, n_mu=4, models=("jkr", "dmt"), w_star=None, mu=None):
    import xarray as xr

    mu = np.geomspace(0.1, 10, n_mu) if mu is None else np.asarray(mu)
    beta0 = np.linspace(0.2, 1.0, n_ell)
    w = np.stack([np.full((n_ell, mu.size), -0.75 - 0.25 * i) for i, _ in enumerate(models)])
    ds = xr.Dataset({"W_star": (("model", "beta0", "mu"), w if w_star is None else w_star(w)),
                     "ellipticity": (("model", "beta0", "mu"), np.ones_like(w))},
                    coords={"model": list(models), "beta0": beta0, "mu": mu})
    complex_ = any(v.dtype.kind == "c" for v in ds.data_vars.values())
    ds.to_netcdf(path, **({"auto_complex": True} if complex_ else {}))


def _peer_setup(case, behaviour):
    """A listener on 127.0.0.1 that is not a dask scheduler; fills the port into ``case.argv``."""
    import socket
    import threading

    def setup(workdir):
        srv = socket.socket()
        srv.bind(("127.0.0.1", 0))
        srv.listen(8)
        srv.settimeout(0.1)
        port = srv.getsockname()[1]
        case.argv = [a.replace("PORT", str(port)) for a in case.argv]
        stop = threading.Event()
        conns = []

        def serve():
            while not stop.is_set():
                try:
                    c, _ = srv.accept()
                except OSError:
                    continue
                conns.append(c)
                try:
                    if behaviour == "garbage":
                        c.sendall(b"\xff" * 64)
                    elif behaviour == "close":
                        c.close()
                    elif behaviour == "http":
                        c.sendall(b"HTTP/1.1 400 Bad Request\r\nContent-Length: 0\r\n\r\n")
                    elif behaviour == "junk frames":
                        import struct

                        c.sendall(struct.pack("Q", 100) + struct.pack("Q", 10**6) + os.urandom(92))
                    elif behaviour == "drip":
                        def drip(c=c):
                            for b in (b"\x10", b"\x00"):
                                if stop.wait(1.0):
                                    return
                                with contextlib.suppress(OSError):
                                    c.sendall(b)
                        threading.Thread(target=drip, daemon=True).start()
                    # "silent": accept and say nothing
                except OSError:
                    pass

        t = threading.Thread(target=serve, daemon=True)
        t.start()

        def teardown():
            stop.set()
            t.join(5)
            for c in conns:
                with contextlib.suppress(OSError):
                    c.close()
            srv.close()

        return {"teardown": teardown}
    return setup


def hardening_cases(quick):
    """Issue 18's classes: API dtypes, file contents, TOML values, environment, network peers, BEM answers."""
    from dhfield import bem
    from dhfield.analysis import compare, dimensional
    from dhfield.models import dh_elliptic as model
    from dhfield.analysis.bem_start import AdhesiveOptions

    cases = []

    def api(label, fn, param, expect="either"):
        cases.append(Case("api", label, api=fn, param=param, expect=expect))

    # --- API dtypes: complex refused by name; other numeric dtypes accepted or refused by name
    api("model.pull_off(mu=complex array)", lambda: model.pull_off(mu=np.array([1 + 5j]), beta0=0.9), "mu", "reject")
    api("model.pull_off(beta0=complex array)", lambda: model.pull_off(mu=1.0, beta0=np.array([0.9 + 0j])), "beta0", "reject")
    api("compare.pull_off('jkr', mu=complex array)",
        lambda: compare.pull_off("jkr", mu=np.array([1 + 1j]), beta0=0.9), "mu", "reject")
    api("compare.pull_off('md', mu=complex scalar)", lambda: compare.pull_off("md", mu=1 + 0j, beta0=0.9), "mu", "reject")
    for lab, v in [("float32", np.float32(1.0)), ("float16", np.float16(1.0)), ("int64 array", np.array([1])),
                   ("bool array", np.array([True])), ("object array", np.array([1.0], dtype=object)),
                   ("big-endian array", np.array([1.0], dtype=">f8")), ("0-d array", np.array(1.0)),
                   ("uint8 array", np.array([3], dtype=np.uint8)), ("longdouble", np.longdouble(1.0))]:
        api(f"model.pull_off(mu={lab})", lambda v=v: model.pull_off(mu=v, beta0=0.9), "mu", "either")
    for lab, v in [("datetime64", np.datetime64("2020-01-01")), ("timedelta64", np.timedelta64(1, "s")),
                   ("dict", {"mu": 1.0}), ("set", {1.0})]:
        api(f"model.pull_off(mu={lab})", lambda v=v: model.pull_off(mu=v, beta0=0.9), "mu", "reject")
    for lab, v in [("str array '1.0'", np.array(["1.0"])), ("bytes b'1'", b"1")]:  # a numeric text may parse
        api(f"model.pull_off(mu={lab})", lambda v=v: model.pull_off(mu=v, beta0=0.9), "mu", "either")
    api("dimensional.contact_parameters(skew_angle=float32(pi/2))",
        lambda: dimensional.contact_parameters(1e6, 0.5, 1e6, 0.5, 0.01, np.float32(np.pi / 2), 0.05, 1e6),
        "skew_angle", "either")
    api("bem.adhesive_pull_off(mu=array([1.0]))", lambda: bem.adhesive_pull_off(mu=np.array([1.0]), beta0=0.9, n=16,
                                                                                progress=False), "mu", "either")
    api("bem.adhesive_pull_off(max_iter=0)", lambda: bem.adhesive_pull_off(mu=1.0, beta0=0.9, n=16, progress=False, options=AdhesiveOptions(max_iter=0)), "max_iter", "either")
    api("bem.adhesive_pull_off(mu=complex)", lambda: bem.adhesive_pull_off(mu=1 + 0j, beta0=0.9, n=16, progress=False),
        "mu", "reject")

    # --- BEM answers: flagged, or within their error of the reference (issue 18 item 1)
    bem_rows = [(30.0, 1.0, 64, "md", {}), (8.0, 1.0, 32, "md", {}), (5.0, 1.0, 32, "md", {}),
                (10.0, 0.3, 48, CLOSURE_03_10, {}), (1.0, 0.9, 64, -0.79, {"margin": 0.1}),
                (1.0, 0.9, 64, -0.79, {"margin": 0.3}), (1.0, 1.0, 32, "md", {})]
    if not quick:
        bem_rows += [(8.0, 1.0, 32, "md", {"law": "exponential"}), (10.0, 0.5, 48, None, {})]
    for mu, beta0, n, ref, kw in bem_rows:
        if ref is None:
            continue
        rtol = BEM_SILENT_RTOL_OTHER_LAW if kw.get("law") == "exponential" else BEM_SILENT_RTOL
        extra = "".join(f", {k}={v}" for k, v in kw.items())
        api(f"bem.adhesive_pull_off(mu={mu:g}, beta0={beta0:g}, n={n}{extra}) answer",
            _bem_verdict(mu, beta0, n, ref, rtol, **kw), "n", "either")
    for mu, beta0, n, ref in [(30, 1, 64, "md"), (10, 0.3, 48, CLOSURE_03_10), (8, 1, 32, "md")]:
        cases.append(Case("cli", f"solve --beta0 {beta0} --mu {mu} --n {n} --json answer",
                          ["solve", "--beta0", str(beta0), "--mu", str(mu), "--n", str(n), "--json"],
                          expect="either", check=_json_w_check(ref)))
    cases.append(Case("cli", "sweep adhesive (beta0 1, mu 8, n 32): status of an unresolved case",
                      ["sweep", "--beta0", "1", "--mu", "8", "--n", "32", "--quantities", "adhesive", "--workers",
                       "1", "--out", "adh.nc", "--quiet"], expect="either", check=_sweep_status_check()))
    for n in ("8192", "65536"):
        cases.append(Case("cli", f"solve --n {n} (memory estimate)", ["solve", "--beta0", "1", "--mu", "1", "--n", n],
                          expect="reject"))

    # --- file contents given to plot
    def plot_file(label, **kw):
        def setup(w):
            _synthetic_sweep(w / "in.nc", **kw)
            return {}
        cases.append(Case("cli", f"plot <{label}>", ["plot", "in.nc", "--out", "maps"], setup=setup,
                          expect="either"))

    plot_file("W_star a string variable", w_star=lambda w: w.astype(str))
    plot_file("W_star complex", w_star=lambda w: w + 1j)
    plot_file("duplicate model names", models=("jkr", "jkr"))
    plot_file("NaN in W_star", w_star=lambda w: np.where(w < -0.8, np.nan, w))
    plot_file("NaN in the mu axis", mu=[0.1, np.nan, 1.0, 10.0])
    plot_file("one point", n_ell=1, n_mu=1)
    plot_file("mu 0.3 1 3 10", mu=[0.3, 1.0, 3.0, 10.0])
    plot_file("unsorted mu axis", mu=[10.0, 0.1, 1.0, 3.0])
    if not quick:
        plot_file("600 x 600 points", n_ell=600, n_mu=600)

    def no_mu(w):
        import xarray as xr

        xr.Dataset({"W_star": (("model", "beta0"), np.ones((1, 2)))}, coords={"model": ["jkr"], "beta0": [0.5, 1.0]}
                   ).to_netcdf(w / "in.nc")
        return {}
    cases.append(Case("cli", "plot <no mu axis>", ["plot", "in.nc"], setup=no_mu, expect="reject"))

    def clobber_plot(w):
        _synthetic_sweep(w / "s.nc")
        for kind in ("pull_off", "ellipticity"):
            for fmt in ("png", "svg"):
                (w / f"s_{kind}.{fmt}").write_bytes(b"old")
        (w / "s_error.png").write_bytes(b"old")
        (w / "s_error.svg").mkdir()
        names = [p.name for p in w.iterdir() if p.name.startswith("s_")]
        return {"targets": {n: _state(w / n) for n in names}}
    cases.append(Case("cli", "plot with s_error.svg a directory (all outputs checked first)",
                      ["plot", "s.nc", "--out", ".", "--reference", "jkr"], setup=clobber_plot, expect="reject"))

    def new_dir(w):
        _synthetic_sweep(w / "s.nc")
        return {}
    cases.append(Case("cli", "plot --out new/nested/dir", ["plot", "s.nc", "--out", "new/nested/dir"], setup=new_dir,
                      expect="ok", check=lambda w, st, o, e: None if len(list((w / "new/nested/dir").glob("*.png")))
                      else ("silent wrong", "no PNG in the new directory")))

    # --- TOML values
    axes = '[axes]\nbeta0 = [0.9]\nmu = [1.0]\n[sweep]\nmodels = ["jkr"]\n'

    def toml(label, text, expect="reject", out=True, check=None, raw=None):
        def setup(w):
            (w / "c.toml").write_bytes(raw if raw is not None else text.encode())
            return {}
        argv = ["sweep", "c.toml", "--quiet"] + (["--out", "s.nc"] if out else [])
        cases.append(Case("cli", f"sweep TOML <{label}>", argv, setup=setup, expect=expect, check=check))

    toml('[run] out = "" (no --out)', axes + '[run]\nout = ""\n', out=False,
         check=_nothing_written_check("sweep.nc", "cases", "sweep.nc.cases"))
    toml('[run] out = "   "', axes + '[run]\nout = "   "\n', out=False)
    toml("[run] workers = 20", axes + "[run]\nworkers = 20\n", expect="either")
    toml("[run] workers = 10**6", axes + "[run]\nworkers = 1000000\n")
    toml("[run] workers = 0", axes + "[run]\nworkers = 0\n")
    toml("nested 5000 deep", axes + "[bem]\nhalf_width = " + "[" * 5000 + "]" * 5000 + "\n")
    toml("nested inline tables 3000 deep", axes + "[bem]\nhalf_width = " + "{a=" * 3000 + "1" + "}" * 3000 + "\n")
    toml("byte-order mark", "", expect="ok", raw=b"\xef\xbb\xbf" + axes.encode())
    toml("UTF-16", "", raw=b"\xff\xfe" + axes.encode("utf-16-le"))
    toml("NUL bytes", "", raw=axes.encode() + b"\x00\x00")
    toml("2 MiB of comments", "", raw=axes.encode() + b"#" * (2 << 20))
    toml("linspace num = 1e300", '[axes]\nbeta0 = [0.9]\nmu = {linspace = [0.1, 1, 1e300]}\n')
    toml("linspace num = inf", '[axes]\nbeta0 = [0.9]\nmu = {linspace = [0.1, 1, inf]}\n')
    toml("geomspace num = 2**62", '[axes]\nbeta0 = [0.9]\nmu = {geomspace = [0.1, 1, 4611686018427387904]}\n')
    toml("mu = true", '[axes]\nbeta0 = [0.9]\nmu = true\n')
    toml("mu = ['1']", "[axes]\nbeta0 = [0.9]\nmu = ['1']\n")
    toml("n = 2**63-1", '[axes]\nbeta0 = [0.9]\nmu = [1.0]\nn = [9223372036854775807]\n[sweep]\nquantities = ["adhesive"]\n')
    toml("chunk_points = 0", axes.replace('models = ["jkr"]', 'models = ["jkr"]\nchunk_points = 0'))
    toml("curve_points = 10**9", axes.replace('models = ["jkr"]', 'models = ["jkr"]\ncurve_points = 1000000000'))
    toml("models = [[1]]", '[axes]\nbeta0 = [0.9]\nmu = [1.0]\n[sweep]\nmodels = [[1]]\n')
    toml("date value", axes + "[bem]\nhalf_width = 1979-05-27\n")
    for address in ("tls://127.0.0.1:8786", "ucx://127.0.0.1:8786", "ws://127.0.0.1:8786", "inproc://x",
                    "tcp://127.0.0.1:0", "tcp://127.0.0.1:70000", "tcp://[::1", "tcp://host name:1"):
        toml(f"scheduler = {address!r}", axes + f'[run]\nscheduler = "{address}"\n')
        cases.append(Case("cli", f"sweep --scheduler {address!r}", ["sweep", "--beta0", "0.9", "--mu", "1", "--models",
                                                                    "jkr", "--scheduler", address, "--out", "s.nc",
                                                                    "--quiet"], expect="reject"))

    # --- network peers on 127.0.0.1 (each answers within CONNECT_TIMEOUT = 5 s, or is refused)
    for behaviour in ("silent", "http", "garbage", "close", "junk frames", "drip"):
        c = Case("cli", f"sweep --scheduler <peer on 127.0.0.1: {behaviour}>",
                 ["sweep", "--beta0", "0.9", "--mu", "1", "--models", "jkr", "--workers", "1", "--scheduler",
                  "tcp://127.0.0.1:PORT", "--out", "s.nc", "--quiet"], expect="reject")
        c.setup = _peer_setup(c, behaviour)
        cases.append(c)

    # --- environment
    solve = ["solve", "--beta0", "1", "--mu", "1", "--n", "16", "--json", "--out", "o.nc"]
    for k, v, expect in [("DHFIELD_THREADS", "abc", "reject"), ("DHFIELD_THREADS", "0", "reject"),
                         ("DHFIELD_THREADS", "99999", "reject"), ("TMPDIR", "/nonexistent", "either"),
                         ("MPLCONFIGDIR", "/nonexistent", "either"), ("OMP_NUM_THREADS", "abc", "either")]:
        argv = solve if k != "MPLCONFIGDIR" else ["plot", "s.nc", "--out", "m"]
        cases.append(Case("env", f"{k}={v!r} {argv[0]}", argv, env={k: v}, expect=expect,
                          setup=new_dir if argv[0] == "plot" else None))
    # --- output names: non-UTF-8 (a name in another encoding reaches Python with surrogate escapes)
    bad_name = os.fsdecode(b"\xff\xfe.nc")
    for argv in (["compare", "--beta0", "0.9", "--mu", "1", "--out", bad_name],
                 ["sweep", "--beta0", "0.9", "--mu", "1", "--models", "jkr", "--workers", "1", "--out", bad_name,
                  "--quiet"]):
        cases.append(Case("path", f"{argv[0]} --out <non-UTF-8 name>", argv, expect="reject"))
    return cases[:40] if quick else cases


# --------------------------------------------------------------------------- issue 42: sweep stores and writes
def _md_sweep_in(w, mu, out="s.nc", beta0=(0.9, 1.0)):
    """Run the small Maugis-Dugdale sweep (beta0 0.9, 1) over ``mu`` into ``w/out`` (a test's setup)."""
    from dhfield.sweep import config_from_mapping, run_sweep

    cfg = config_from_mapping({"axes": {"beta0": list(beta0), "mu": list(mu)}, "sweep": {"models": ["md"]}})
    run_sweep(cfg, out=w / out, scheduler="synchronous", progress=False)


def _md_argv(mu, out="s.nc"):
    return ["sweep", "--beta0", "0.9", "1", "--mu", *map(str, mu), "--models", "md", "--workers", "1", "--quiet",
            "--out", out]


def _sweep_values_check(mu, out="s.nc"):
    """A CLI check: an exit-0 sweep must hold Maugis-Dugdale's own W* at its (beta0, mu), not another config's."""
    def check(workdir, status, stdout, stderr):
        if status != 0:
            return None
        import warnings

        import xarray as xr

        from dhfield.analysis.compare import pull_off

        with xr.open_dataset(workdir / out) as ds:
            got = ds["W_star"].sel(model="md").values
            b, m = ds["beta0"].values, ds["mu"].values
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            want = np.array([[float(pull_off("md", beta0=bb, mu=mm).W_star) for mm in m] for bb in b])
        if list(m) != list(map(float, mu)) or not np.allclose(got, want, rtol=1e-12, atol=0):
            return ("silent wrong", f"stored W* {got.ravel()[:4]} at mu {list(m)}, Maugis-Dugdale gives "
                                    f"{want.ravel()[:4]}")
        return None
    return check


def _empty_dir_check(name):
    def check(workdir, status, stdout, stderr):
        left = sorted(p.name for p in (workdir / name).iterdir())
        return ("clobbered", f"written through the link into {name}/: {left}") if left else None
    return check


def _absent_check(*names):
    def check(workdir, status, stdout, stderr):
        there = [n for n in names if os.path.lexists(workdir / n)]
        return ("clobbered", f"created {there}") if there else None
    return check


def _dead_pid() -> int:
    import subprocess

    proc = subprocess.Popen([sys.executable, "-c", "pass"])
    proc.wait()
    return proc.pid


def _api_main(argv, want_status, want_in=None, unwanted=None):
    """Run the CLI in the child; a silent_wrong record unless it exits ``want_status`` with the expected line."""
    from dhfield.cli import main

    err = io.StringIO()
    with contextlib.redirect_stderr(err):
        status = main(argv)
    text = " ".join(err.getvalue().split())
    if status != want_status:
        return {"silent_wrong": f"exit {status}, expected {want_status}: {text[:140]}"}
    if want_in and want_in not in text:
        return {"silent_wrong": f"the message lacks {want_in!r}: {text[:140]}"}
    if unwanted and unwanted in text:
        return {"silent_wrong": f"the message says {unwanted!r}: {text[:140]}"}
    return {"ok": 1}


def _limit_memory(nbytes):
    from dhfield.core import memory as _memory

    _memory.available_memory = lambda: nbytes


def _no_allocation():
    """Setting up a BEM problem (its arrays) before the memory check is a defect: raise where it would happen."""
    from dhfield.analysis import bem_start as adhesive_start

    def allocated(*args, **kwargs):
        raise AssertionError("the BEM problem was set up (its arrays allocated) before the memory check")

    adhesive_start.paper_problem = allocated


def _adhesive_run_sweep(n, mu=(1.0,), workers=1, scheduler="synchronous"):
    from dhfield.sweep import config_from_mapping, run_sweep

    cfg = config_from_mapping({"axes": {"beta0": [1.0], "mu": list(mu), "n": [n]},
                               "sweep": {"quantities": ["adhesive"]}})
    return run_sweep(cfg, out="a.nc", scheduler=scheduler, workers=workers, progress=False)


def _interrupt_between_renames(write):
    """Call ``write()`` with SIGINT delivered right after the first file of its set is moved into place."""
    real = os.replace
    calls = []

    def replace(src, dst):
        real(src, dst)
        calls.append(dst)
        if len(calls) == 1:
            os.kill(os.getpid(), signal.SIGINT)

    os.replace = replace
    try:
        write()
    except KeyboardInterrupt:
        pass
    finally:
        os.replace = real


def _table_pair_api():
    from dhfield.io.table import write_table

    write_table({"a_star": [1.0]}, "x.csv", title="old")
    old = (Path("x.csv").read_bytes(), Path("x.csv.json").read_bytes())
    _interrupt_between_renames(lambda: write_table({"a_star": [2.0]}, "x.csv", title="new"))
    new = (Path("x.csv").read_bytes(), Path("x.csv.json").read_bytes())
    if (new[0] == old[0]) != (new[1] == old[1]):
        return {"silent_wrong": "the CSV and its sidecar are of different writes: "
                                f"CSV {'old' if new[0] == old[0] else 'new'}, sidecar "
                                f"{'old' if new[1] == old[1] else 'new'}"}
    return {"ok": 1}


def _figure_set_api():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from dhfield.io.figures import figure_paths, save_figure

    paths = figure_paths("f.png")
    for p in paths:
        p.write_bytes(b"old")
    fig = plt.figure()
    _interrupt_between_renames(lambda: save_figure(fig, paths, 50))
    states = ["old" if p.read_bytes() == b"old" else "new" for p in paths]
    if len(set(states)) > 1:
        return {"silent_wrong": f"PNG/SVG/PDF of different writes: {states}"}
    return {"ok": 1}


def _solve_plot_interrupted_api():
    from dhfield.io import solve_plot

    for name in ("t.nc", "t.png", "t.svg", "t.pdf"):
        Path(name).write_bytes(b"old")

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    solve_plot.solve_figure = interrupted
    rec = _api_main(["solve", "--beta0", "1", "--mu", "1", "--n", "16", "--out", "t.nc", "--plot", "t.png"], 130)
    changed = [n for n in ("t.nc", "t.png", "t.svg", "t.pdf") if Path(n).read_bytes() != b"old"]
    if changed:
        return {"silent_wrong": f"interrupted while plotting, yet {changed} were replaced"}
    return rec


def _sweep_interrupted_api():
    from dhfield.sweep import engine

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    engine._consolidate = interrupted
    return _api_main(["sweep", "--beta0", "0.9", "1", "--mu", "0.5", "1", "--models", "md", "--chunk-points", "1",
                      "--workers", "1", "--quiet", "--out", "s.nc"], 130,
                     want_in="4 finished case(s) are stored", unwanted="no output was written")


def store_and_write_cases(quick):
    """Issue 42's classes: sweep stores that cannot mix configs (finding 1), memory planned on every BEM route
    (finding 6), multi-file outputs committed as a set (finding 9), output paths (finding 10)."""
    cases = []

    # --- finding 1: a case is reused only if its fingerprint and coordinates match
    def no_manifest(w):
        _md_sweep_in(w, (0.5, 1.0))
        (w / "s.nc.cases" / "manifest.json").unlink()
        return {}

    def garbage_manifest(text):
        def setup(w):
            _md_sweep_in(w, (0.5, 1.0))
            (w / "s.nc.cases" / "manifest.json").write_text(text)
            return {}
        return setup

    def swapped_manifest(w):   # the mu = 0.5, 1 cases under the manifest of the mu = 5, 10 sweep
        _md_sweep_in(w, (5.0, 10.0), out="b.nc")
        _md_sweep_in(w, (0.5, 1.0))
        (w / "s.nc.cases" / "manifest.json").write_bytes((w / "b.nc.cases" / "manifest.json").read_bytes())
        return {}

    def copied_case(w):        # another config's case file under this store's key
        _md_sweep_in(w, (0.5, 1.0), out="a.nc")
        _md_sweep_in(w, (5.0, 10.0))
        for p in (w / "a.nc.cases").glob("pull_off__*.nc"):
            (w / "s.nc.cases" / p.name).write_bytes(p.read_bytes())
        return {}

    def legacy_case(w):        # a case file without the identifying attributes, and no manifest
        import netCDF4

        _md_sweep_in(w, (0.5, 1.0))
        (w / "s.nc.cases" / "manifest.json").unlink()
        for p in (w / "s.nc.cases").glob("pull_off__*.nc"):
            with netCDF4.Dataset(p, "a") as nc:
                for k in ("sweep_fingerprint", "case_key", "case_coordinates"):
                    if k in nc.ncattrs():
                        nc.delncattr(k)
        return {}

    def garbage_case(w):
        _md_sweep_in(w, (5.0, 10.0))
        for p in (w / "s.nc.cases").glob("pull_off__*.nc"):
            p.write_bytes(b"\x89HDF garbage" * 10)
        return {}

    rows = [("manifest.json deleted, another mu", no_manifest, (5.0, 10.0), "reject"),
            ("manifest.json deleted, the same config", no_manifest, (0.5, 1.0), "ok"),
            ("manifest.json is '[]'", garbage_manifest("[]"), (5.0, 10.0), "reject"),
            ("manifest.json is '{'", garbage_manifest("{"), (5.0, 10.0), "reject"),
            ("manifest.json of another config over these cases", swapped_manifest, (5.0, 10.0), "ok"),
            ("another config's case file under this key", copied_case, (5.0, 10.0), "ok"),
            ("a case file without fingerprint, no manifest", legacy_case, (5.0, 10.0), "reject"),
            ("a garbage case file", garbage_case, (5.0, 10.0), "ok")]
    for label, setup, mu, expect in rows:
        cases.append(Case("cli", f"sweep store <{label}>", _md_argv(mu), setup=setup, expect=expect,
                          check=_sweep_values_check(mu)))

    # --- finding 6: every BEM route plans its grid against the memory available, before allocating
    def api(label, fn, param, expect="reject"):
        cases.append(Case("api", label, api=fn, param=param, expect=expect))

    def limited(nbytes, fn):
        def run():
            _limit_memory(nbytes)
            _no_allocation()
            return fn()
        return run

    from dhfield.analysis import bem_start as adhesive_start
    from dhfield.analysis.bem_spring import bem_unloading_branch

    api("run_sweep(adhesive, n=[256]) with 20 MiB available", limited(20 * 2**20, lambda: _adhesive_run_sweep(256)),
        "axes.n")
    api("run_sweep(adhesive, n=[256], 2 mu on 2 workers) with 50 MiB available",
        limited(50 * 2**20, lambda: _adhesive_run_sweep(256, mu=(1.0, 2.0), workers=2, scheduler="processes")),
        "workers")
    api("adhesive_pull_off(n=64) with 1 MiB available",
        limited(2**20, lambda: adhesive_start.adhesive_pull_off(beta0=1.0, mu=1.0, n=64)), "n=64")
    api("adhesive_pull_off(n=64, control='displacement') with 1 MiB available",
        limited(2**20, lambda: adhesive_start.adhesive_pull_off(beta0=1.0, mu=1.0, n=64, control="displacement")),
        "n=64")
    api("adhesive_pull_off(n=64, search='predicted') with 1 MiB available",
        limited(2**20, lambda: adhesive_start.adhesive_pull_off(beta0=1.0, mu=10.0, n=64, search="predicted")),
        "n=64")
    api("bem_unloading_branch(n=64) with 1 MiB available",
        limited(2**20, lambda: bem_unloading_branch(beta0=1.0, mu=1.0, n=64)), "n=64")
    api("adhesive_case(n=64) (a sweep's task) with 1 MiB available",
        limited(2**20, lambda: __import__("dhfield.sweep.tasks", fromlist=["x"]).adhesive_case(1.0, 1.0, n=64)),
        "n=64")
    for argv in (["sweep", "--quantities", "adhesive", "--beta0", "1", "--mu", "1", "--n", "8192", "--workers", "1",
                  "--quiet", "--out", "a.nc"],
                 ["solve", "--beta0", "1", "--mu", "1", "--n", "8192"],
                 ["solve", "--beta0", "1", "--mu", "1", "--n", "8192", "--machine-stiffness", "0"],
                 ["cycle", "--model", "bem", "--beta0", "1", "--mu", "1", "--n", "8192", "--machine-stiffness", "1"]):
        api(f"{' '.join(argv[:1] + argv[-4:])} with 8 GiB available: exit 2",
            limited(8 * 2**30, lambda argv=argv: _api_main(argv, 2, want_in="n")), "n", expect="either")

    # --- finding 9: files written together are committed as a set; an interrupt says what was written
    api("CSV + sidecar, SIGINT between the renames", _table_pair_api, "", expect="either")
    api("figure PNG/SVG/PDF, SIGINT between the renames", _figure_set_api, "", expect="either")
    api("solve --out t.nc --plot t.png, Ctrl-C while plotting", _solve_plot_interrupted_api, "", expect="either")
    api("sweep, Ctrl-C after its cases are stored: says so and how to resume", _sweep_interrupted_api, "",
        expect="either")

    # --- finding 10: output paths of a sweep and of a CSV
    def store_link(w):
        (w / "real").mkdir()
        (w / "s.nc.cases").symlink_to(w / "real")
        return {}

    def dir_link(w):
        (w / "real").mkdir()
        (w / "d").symlink_to(w / "real")
        return {}

    def dangling_store(w):
        (w / "s.nc.cases").symlink_to(w / "nowhere")
        return {}

    def existing_dir(w):
        (w / "runs.d").mkdir()
        return {}

    base = ["sweep", "--beta0", "0.9", "--mu", "1", "--models", "jkr", "--workers", "1", "--quiet", "--out"]
    cases += [
        Case("path", "sweep --out s.nc <s.nc.cases a symlink to a directory>", [*base, "s.nc"], setup=store_link,
             expect="reject", check=_empty_dir_check("real")),
        Case("path", "sweep --out <a symlink to a directory>", [*base, "d"], setup=dir_link, expect="reject",
             check=_empty_dir_check("real")),
        Case("path", "sweep --out s.nc <s.nc.cases a dangling symlink>", [*base, "s.nc"], setup=dangling_store,
             expect="reject", check=_absent_check("nowhere", "s.nc")),
        Case("path", "sweep --out x.txt", [*base, "x.txt"], expect="reject", check=_absent_check("x.txt")),
        Case("path", "sweep --out x.csv", [*base, "x.csv"], expect="reject", check=_absent_check("x.csv")),
        Case("path", "sweep --out <an existing directory runs.d>", [*base, "runs.d"], setup=existing_dir,
             expect="ok"),
        Case("path", "sweep --out <a new directory name>", [*base, "newdir"], expect="ok"),
    ]

    def sidecar_only(w):
        (w / "c.csv.json").write_text('{"columns": {}}\n')
        return {"targets": {"c.csv.json": _state(w / "c.csv.json")}}

    def csv_and_sidecar(w):
        (w / "c.csv").write_text("a\n1\n")
        (w / "c.csv.json").write_text('{"columns": {}}\n')
        return {}

    def stale_part(name, where="."):
        def setup(w):
            (w / where).mkdir(exist_ok=True)
            (w / where / f".{name[:32]}.{_dead_pid()}-abcdefgh.part").write_bytes(b"partial")
            return {}
        return setup

    curve = ["curve", "--beta0", "0.9", "--mu", "1", "--n", "5", "--out"]
    cases += [
        Case("path", "curve --out c.csv <c.csv.json exists, c.csv does not>", [*curve, "c.csv"],
             setup=sidecar_only, expect="reject", check=_absent_check("c.csv")),
        Case("path", "curve --out c.csv <c.csv and c.csv.json exist>", [*curve, "c.csv"], setup=csv_and_sidecar,
             expect="ok"),
        Case("path", "curve --out c.nc <a killed writer's .part beside it>", [*curve, "c.nc"],
             setup=stale_part("c.nc"), expect="ok"),
        Case("path", "curve --out c.csv <a killed writer's .part of the sidecar>", [*curve, "c.csv"],
             setup=stale_part("c.csv.json"), expect="ok"),
        Case("path", "sweep --out s.nc <a killed writer's .part of a case>", [*base, "s.nc"],
             setup=stale_part("pull_off__jkr__00000_00000.nc", "s.nc.cases"), expect="ok"),
    ]
    return cases[:12] if quick else cases


def _stderr_check(must=(), must_not=(), status=None, stdout_must=()):
    """A ``Case.check``: stderr contains every text of ``must`` and none of ``must_not`` (the exit status is
    ``status`` if given; stdout contains every text of ``stdout_must``)."""
    def check(workdir, st, stdout, stderr):
        if status is not None and st != status:
            return "silent wrong", f"exit {st}, expected {status}: {' | '.join(stderr.splitlines())[:140]}"
        missing = [m for m in must if m not in stderr] + [m for m in stdout_must if m not in stdout]
        present = [m for m in must_not if m in stderr]
        if missing or present:
            return "unnamed error", (f"missing {missing} " if missing else "") + (f"has {present} " if present else "") \
                + f"in: {' | '.join(stderr.splitlines())[:120]}"
        return None
    return check


#: A load curve deep on the JKR side (PDMS, dgamma 0.05 J/m^2, sigma0 1e8 Pa: mu ~ 3700), where the load does not
#: depend on sigma0 (JKR has no adhesive stress): a fit cannot identify it.
_JKR_SIDE = ("--youngs-modulus", "1.8e6", "--poisson-ratio", "0.49", "--cylinder-radius", "3e-3", "--skew-angle-deg",
             "60")


def _jkr_side_csv(workdir, name="jkr.csv"):
    import math

    from dhfield.analysis import dimensional as dim

    p = dim.contact_parameters(1.8e6, 0.49, 1.8e6, 0.49, 3e-3, math.pi / 3, 0.05, 1e8)
    a = p.length_unit * np.linspace(0.5, 3.0, 12)
    w = dim.load_curve_si(p, semi_major=a, model="md-elliptic")["force"]
    (workdir / name).write_text("force,semi_major\n" + "".join(f"{float(x)!r},{float(y)!r}\n" for x, y in zip(w, a)))


def _without_option(argv, opt):
    """``argv`` without ``opt`` and its values."""
    if opt not in argv:
        return list(argv)
    i = argv.index(opt)
    j = i + 1
    while j < len(argv) and not argv[j].startswith("--"):
        j += 1
    return argv[:i] + argv[j:]


def input_message_cases(parsers, quick):
    """Issue 42's classes: options given as ``--opt=--`` (finding 11), flagged fits (finding 5), messages in the
    user's units and warnings as one line (finding 12)."""
    from dhfield.analysis import compare

    cases = []

    # --- finding 11: "--opt=--" (argparse: an empty list) refused in one line naming the option, for every option
    #     that takes a value, of every subcommand with a baseline
    for name, sp in parsers.items():
        bases = _baselines(name, sp)
        if not bases:
            continue
        for a in sp._actions:
            if not a.option_strings or a.nargs == 0 or a.dest == "help":
                continue
            opt = a.option_strings[-1] if a.option_strings[-1].startswith("--") else a.option_strings[0]
            argv = _without_option(bases[0], opt) + [f"{opt}=--"]
            cases.append(Case("cli", f"{name} {opt}=--", argv, expect="reject",
                              check=_stderr_check(must=(f"argument {opt}: expected",))))
    cases.append(Case("cli", "cycle --machine-stiffness=-- --json",
                      ["cycle", "--beta0", "1", "--mu", "1", "--machine-stiffness=--", "--json"], expect="reject",
                      check=_stderr_check(must=("argument --machine-stiffness",))))
    for model in (compare.MODEL_NAMES[:3] if quick else compare.MODEL_NAMES):
        cases.append(Case("api", f"compare.pull_off({model!r}, beta0=[], mu=1)",
                          api=lambda m=model: compare.pull_off(m, beta0=[], mu=1.0), param="beta0", expect="reject"))
        cases.append(Case("api", f"compare.pull_off({model!r}, beta0=0.9, mu=np.array([]))",
                          api=lambda m=model: compare.pull_off(m, beta0=0.9, mu=np.array([])), param="mu",
                          expect="reject"))
    cases.append(Case("api", "compare.compare(beta0=(), mu=1)", api=lambda: compare.compare(beta0=(), mu=1.0),
                      param="beta0", expect="reject"))

    # --- finding 5: a fit that cannot identify sigma0 is flagged (exit 3), sigma0 printed as not identifiable
    def jkr_side(w):
        _jkr_side_csv(w)
        return {}
    cases.append(Case("cli", "fit --data <JKR-side curve: sigma0 not identifiable>",
                      ["fit", "--data", "jkr.csv", *_JKR_SIDE], setup=jkr_side, expect="either",
                      check=_stderr_check(must=("dhfield: fit is not an answer: max_adhesive_stress not identifiable",),
                                          status=3, stdout_must=("max_adhesive_stress          not identifiable",))))
    cases.append(Case("cli", "fit --data <JKR-side curve> --json",
                      ["fit", "--data", "jkr.csv", *_JKR_SIDE, "--json"], setup=jkr_side, expect="either",
                      check=_stderr_check(status=3, stdout_must=('"max_adhesive_stress": null',
                                                                 '"not_identifiable": ["max_adhesive_stress"]'))))

    # --- finding 12: messages in the user's units
    si = ["--youngs-modulus", "1e6", "--poisson-ratio", "0.5", "--cylinder-radius", "0.01", "--work-of-adhesion",
          "0.05", "--adhesive-stress", "1e6"]
    for lo in ("-1", "-0.003", "-1e300"):
        cases.append(Case("cli", f"curve <SI> --load-min={lo} (below the pull-off)",
                          ["curve", *si, "--skew-angle-deg", "60", f"--load-min={lo}", "--load-max", "1"],
                          expect="reject", check=_stderr_check(must=(" N of md-elliptic", " N\n"), must_not=("W*",))))
    for deg in ("0.0354", "0.01", "1e-300"):
        cases.append(Case("cli", f"pulloff <SI> --skew-angle-deg {deg}", ["pulloff", *si, "--skew-angle-deg", deg],
                          expect="reject", check=_stderr_check(must=("degrees",), must_not=("rad",))))
    for cell in ("nan", "inf", "-inf", "NaN"):
        def bad_cell(w, cell=cell):
            (w / "d.csv").write_text(f"force,semi_major\n1e-3,1e-4\n{cell},2e-4\n2e-3,3e-4\n")
            return {}
        cases.append(Case("cli", f"fit --data <a {cell} cell>", ["fit", "--data", "d.csv", *_JKR_SIDE],
                          setup=bad_cell, expect="reject", check=_stderr_check(must=("data row 2",),
                                                                               must_not=("np.", "float64"))))

    def many_rows(w):   # MAX_DATA_ROWS lowered to 10 in this process (the child inherits it), restored after
        import dhfield.io.fit as io_fit

        saved = getattr(io_fit, "MAX_DATA_ROWS", None)  # None: a version without the limit
        io_fit.MAX_DATA_ROWS = 10
        (w / "many.csv").write_text("force,semi_major\n" + "".join(f"{1e-3 * (k - 5)!r},{1e-4 * (k + 1)!r}\n"
                                                                   for k in range(11)))
        return {"teardown": lambda: setattr(io_fit, "MAX_DATA_ROWS", saved)}
    cases.append(Case("cli", "fit --data <more rows than MAX_DATA_ROWS>", ["fit", "--data", "many.csv", *_JKR_SIDE],
                      setup=many_rows, expect="reject",
                      check=_stderr_check(must=("many.csv' has 11 data rows",), must_not=("a_star",))))
    axes = '[axes]\nbeta0 = [0.9]\nmu = [1.0]\n[sweep]\nmodels = ["jkr"]\n'
    for key, digits, text in (("sweep.chunk_points", 5000, axes + "chunk_points = " + "9" * 5000 + "\n"),
                              ("axes.mu", 5000, '[axes]\nbeta0 = [0.9]\nmu = [' + "1" * 5000 + ']\n'),
                              ("run.workers", 4301, axes + "[run]\nworkers = " + "1" * 4301 + "\n")):
        def toml(w, text=text):
            (w / "c.toml").write_text(text)
            return {}
        cases.append(Case("cli", f"sweep TOML <{key} = an integer of {digits} digits>",
                          ["sweep", "c.toml", "--out", "s.nc", "--quiet"], setup=toml,
                          expect="reject", check=_stderr_check(must=(f"key {key!r}",),
                                                               must_not=("set_int_max_str_digits",))))

    # --- finding 12: warnings are one 'dhfield: warning:' line, without a source path or a line of code
    def bad_wisdom(w):
        from dhfield.bem import _wisdom

        _wisdom._WISDOM_STATE["loaded"] = False
        (w / "cache" / "fftw_wisdom.bin").write_bytes(b"garbage\n")
        os.chmod(w / "cache" / "fftw_wisdom.bin", 0o644)
        return {}
    cases.append(Case("cli", "solve with a corrupt FFTW wisdom cache", ["solve", "--beta0", "1", "--mu", "1", "--n",
                                                                        "16", "--json"],
                      setup=bad_wisdom, expect="either",
                      check=_stderr_check(must=("dhfield: warning: ignoring the FFTW wisdom cache",),
                                          must_not=(".py:", "Warning:", "  return "))))
    for extra in ([], ["--control", "displacement"]):
        cases.append(Case("cli", f"sweep over the domain's corners {' '.join(extra)}: no Python warning",
                          ["sweep", "--beta0", "2e-4", "0.5", "1", "--mu", "1e-6", "1", "1e12", "--models",
                           *(["md-elliptic", "jkr"] if quick else list(compare.MODEL_NAMES[:6])), *extra,
                           "--workers", "1", "--out", "s.nc", "--quiet"], expect="either",
                          check=_stderr_check(must_not=(".py:", "Warning:"))))
    return cases


# --------------------------------------------------------------------------- main
def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="a subset (about a minute)")
    ap.add_argument("--timeout", type=float, default=60.0, help="seconds per case before it counts as a hang")
    ap.add_argument("--only", default=None, help="run only cases whose label contains this text")
    ap.add_argument("--issue18", action="store_true",
                    help="only the classes added for issue 18 (API dtypes, file contents, TOML values, "
                         "environment, network peers on 127.0.0.1, BEM answers)")
    ap.add_argument("--issue42-writes", action="store_true",
                    help="only the classes added for issue 42's findings 1, 6, 9, 10 (sweep stores, memory "
                         "planned on every BEM route, files written as a set, output paths)")
    ap.add_argument("--issue42-inputs", action="store_true",
                    help="only the classes added for issue 42's findings 5, 11, 12 (options given as '--opt=--', "
                         "flagged fits, messages in the user's units, warnings as one line)")
    args = ap.parse_args(argv)

    parsers = subcommand_parsers()
    cases = input_message_cases(parsers, args.quick) if args.issue42_inputs else \
        store_and_write_cases(args.quick) if args.issue42_writes else hardening_cases(args.quick) if args.issue18 else (numeric_cases(parsers, args.quick) + path_cases(parsers, args.quick)
             + input_cases(parsers, args.quick) + env_cases(args.quick)
             + signal_cases(args.quick) + api_cases(args.quick) + hardening_cases(args.quick)
             + store_and_write_cases(args.quick) + input_message_cases(parsers, args.quick))
    if args.only:
        cases = [c for c in cases if args.only in c.label]
    tty = sys.stderr.isatty()
    t0 = time.monotonic()
    for i, case in enumerate(cases, 1):
        (run_process if case.kind == "process" else run_case)(case, args.timeout)
        if tty:
            print(f"\r[{i}/{len(cases)}] {time.monotonic() - t0:6.0f} s  {case.label[:60]:60s}", end="",
                  file=sys.stderr, flush=True)
    if tty:
        print(file=sys.stderr)

    counts = {}
    for c in cases:
        counts[c.outcome] = counts.get(c.outcome, 0) + 1
    kinds = {}
    for c in cases:
        kinds[c.kind] = kinds.get(c.kind, 0) + 1
    print(f"hostile inputs tried: {len(cases)} in {time.monotonic() - t0:.0f} s "
          f"({', '.join(f'{k} {v}' for k, v in kinds.items())}); subcommands: {', '.join(parsers)}")
    order = ["clean error", "accepted", "clean signal", "noisy error", "unnamed error", "internal error",
             "traceback", "hang", "silent wrong", "clobbered"]
    for name in order + sorted(set(counts) - set(order)):
        print(f"  {name:16s} {counts.get(name, 0):5d}")
    bad = [c for c in cases if c.outcome not in CLEAN]
    if bad:
        print("\nnot clean:")
        for c in sorted(bad, key=lambda c: (order.index(c.outcome) if c.outcome in order else 99, c.label)):
            print(f"  [{c.outcome}] {c.label}: {c.detail}")
    return 1 if any(c.outcome in DEFECTS for c in cases) else 0


if __name__ == "__main__":
    sys.exit(main())
