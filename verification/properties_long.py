"""Long run of the property-based tests (issue 9): many more hypothesis examples.

Run:  .venv/bin/python -m verification.properties_long [--examples 400]

Runs ``pytest tests/test_properties.py`` with HYPOTHESIS_PROFILE=long (randomised,
not derandomised) and prints the number of tests, examples per test and the outcome.
"""
from __future__ import annotations

import argparse
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--examples", type=int, default=400, help="max examples per test (default 400)")
    args = ap.parse_args(argv)
    env = dict(os.environ, HYPOTHESIS_PROFILE="long", DHFIELD_LONG_EXAMPLES=str(args.examples))
    cmd = [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "--hypothesis-show-statistics",
           "tests/test_properties.py"]
    print(f"property tests, profile 'long', up to {args.examples} examples per test", flush=True)
    res = subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True)
    lines = res.stdout.splitlines()
    n_pass = n_fail = 0
    for line in lines:
        parts = line.replace(",", "").split()
        if "passing" in parts and "failing" in parts and parts[0] == "-":
            n_pass += int(parts[parts.index("passing") - 1])
            n_fail += int(parts[parts.index("failing") - 1])
    print("\n".join(line for line in lines if line.startswith("FAILED") or " passed" in line
                    or " failed" in line))
    print(f"examples: {n_pass} passing, {n_fail} failing; exit status {res.returncode}")
    return res.returncode


if __name__ == "__main__":
    sys.exit(main())
