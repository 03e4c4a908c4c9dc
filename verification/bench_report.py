"""Benchmark of the verification report: ``--quick`` (target <= 60 s) and default (<= 10 min).

Usage::

    python -m verification.bench_report [--only quick|default] [--out-root DIR] [--keep]

Each mode runs ``python -m verification.report`` in a fresh subprocess (so the
time includes interpreter start-up and imports, as a user sees it) into its own
temporary output directory, and the wall time is compared with the target of
issue 5.  Per-section times are read back from the report's ``checks.json``.
Exit status: 0 if every timed mode met its target, 1 otherwise.  The report's own
PASS/FAIL status is printed but does not change the benchmark's verdict.
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
#: Wall-time targets of issue 5 [s].
TARGETS = {"quick": 60.0, "default": 600.0}


def time_report(mode: str, out: Path) -> dict:
    """Run the report once in ``mode`` ("quick" or "default") into ``out``; return timings.

    Returns
    -------
    dict
        ``mode``, ``seconds`` (wall time of the subprocess), ``target``, ``exit``
        (the report's exit status), ``sections`` (name -> seconds) and ``checks``
        ("passed/total").
    """
    cmd = [sys.executable, "-m", "verification.report", "--out", str(out), "--no-progress"]
    if mode == "quick":
        cmd.insert(3, "--quick")
    env = dict(os.environ, MPLBACKEND="Agg")
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True)
    seconds = time.perf_counter() - t0
    sections, checks = {}, "n/a"
    try:
        data = json.loads((out / "checks.json").read_text())
        sections = {s["name"]: s["seconds"] for s in data["sections"]}
        passed = sum(c["passed"] for c in data["checks"])
        checks = f"{passed}/{len(data['checks'])}"
    except (OSError, ValueError, KeyError):
        pass
    return {"mode": mode, "command": " ".join(["python", *cmd[1:]]), "seconds": seconds,
            "target": TARGETS[mode], "exit": proc.returncode, "sections": sections, "checks": checks,
            "stderr_tail": proc.stderr[-1500:]}


def main(argv=None) -> int:
    """Time the quick and the default report; print both against their targets."""
    p = argparse.ArgumentParser(prog="python -m verification.bench_report", description=__doc__.split("\n")[0])
    p.add_argument("--only", choices=("quick", "default"), help="time one mode only")
    p.add_argument("--out-root", default=None, help="directory for the two report outputs (default: temporary)")
    p.add_argument("--keep", action="store_true", help="keep the report outputs (printed at the end)")
    args = p.parse_args(argv)
    modes = [args.only] if args.only else ["quick", "default"]
    root = Path(args.out_root) if args.out_root else Path(tempfile.mkdtemp(prefix="dhfield-bench-"))
    root.mkdir(parents=True, exist_ok=True)
    print(f"machine: {platform.platform()}, {os.cpu_count()} cores, python {platform.python_version()}")
    results = []
    try:
        for mode in modes:
            print(f"timing the {mode} report ...", flush=True)
            r = time_report(mode, root / mode)
            results.append(r)
            ok = r["seconds"] <= r["target"]
            print(f"  {r['command']}")
            print(f"  {mode:8s} {r['seconds']:8.1f} s  (target <= {r['target']:.0f} s: {'MET' if ok else 'MISSED'}); "
                  f"report exit {r['exit']}, checks passed {r['checks']}")
            for name, sec in r["sections"].items():
                print(f"    {name:10s} {sec:8.1f} s")
            if r["exit"] not in (0, 1):
                print("  report stderr (tail):\n" + r["stderr_tail"])
    finally:
        if args.keep or args.out_root:
            print(f"outputs kept under {root}")
        else:
            shutil.rmtree(root, ignore_errors=True)
    print("\nmode      wall time   target   verdict")
    for r in results:
        print(f"{r['mode']:8s} {r['seconds']:9.1f} s {r['target']:6.0f} s   "
              f"{'MET' if r['seconds'] <= r['target'] else 'MISSED'}")
    return 0 if all(r["seconds"] <= r["target"] for r in results) else 1


if __name__ == "__main__":
    sys.exit(main())
