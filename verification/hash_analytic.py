"""Hash every array and scalar of the analytic pull-offs, load curves, comparisons and CLI outputs.

A bit-for-bit regression harness for refactoring the analytic side (issue 16): run it
before and after a change and ``diff`` the two outputs.  Each line is ``<case> <sha1>``
(first 16 hex digits) of the exact bytes of a value: float arrays as float64 bytes with
their shape, strings and booleans by their repr, CLI outputs by their stdout text.

Usage::

    python -m verification.hash_analytic > /tmp/hash.txt
    python -m verification.hash_analytic --quick   # a smaller grid (no ray-average sweep)
"""
from __future__ import annotations

import contextlib
import hashlib
import io
import sys
from collections.abc import Mapping

import numpy as np

BETA0 = (0.3, 0.5, 0.8, 0.9, 0.99, 1.0)
MU = (0.05, 0.3, 1.0, 5.0, 20.0)
#: Scalar points for curves and the CLI (a subset of the grid).
POINTS = ((0.3, 0.3), (0.9, 1.0), (1.0, 5.0))
CONTROLS = ("load", "displacement")
SI = ["--youngs-modulus", "1e6", "--poisson-ratio", "0.5", "--cylinder-radius", "0.01",
      "--skew-angle-deg", "60", "--work-of-adhesion", "0.05", "--adhesive-stress", "2e5"]


def digest(value) -> str:
    h = hashlib.sha1()
    _feed(h, value)
    return h.hexdigest()[:16]


def _feed(h, value):
    if isinstance(value, Mapping):
        for k in value:
            h.update(repr(k).encode())
            _feed(h, value[k])
    elif isinstance(value, (list, tuple)):
        h.update(f"seq{len(value)}".encode())
        for v in value:
            _feed(h, v)
    elif isinstance(value, str):
        h.update(value.encode())
    else:
        arr = np.asarray(value)
        if arr.dtype.kind in "fiu":
            arr = np.ascontiguousarray(arr, dtype=np.float64)
            h.update(repr(arr.shape).encode())
            h.update(arr.tobytes())
        else:
            h.update(repr(arr.shape).encode())
            h.update(repr(arr.tolist()).encode())


def emit(name, value):
    """Print one line per field of a record (a mapping) or one line for a value."""
    if isinstance(value, Mapping):
        for k, v in value.items():
            print(f"{name}.{k} {digest(v)}", flush=True)
    else:
        print(f"{name} {digest(value)}", flush=True)


def cli(argv) -> str:
    from dhfield.cli import main

    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            rc = main(argv)
        except SystemExit as exc:
            rc = exc.code
    return f"rc={rc}\n{out.getvalue()}\nstderr:{err.getvalue()}"


def main(argv=None) -> int:
    import dhfield
    from dhfield.analysis import compare

    quick = "--quick" in (argv if argv is not None else sys.argv[1:])
    b, m = np.meshgrid(BETA0, MU, indexing="ij")
    b, m = b.ravel(), m.ravel()
    names = compare.MODEL_NAMES
    for control in CONTROLS:
        for name in names:
            if quick and name == "dh-elliptic-ray-average":
                continue
            emit(f"pull_off[{name},{control}]", compare.pull_off(name, mu=m, beta0=b, control=control))
        res = dhfield.pull_off(mu=m, beta0=b, control=control)
        emit(f"dhfield.pull_off[{control}]", {k: getattr(res, k) for k in (
            "mu", "beta0", "ellipticity", "control", "W_star", "a_star", "c_star", "v", "delta_star",
            "at_zero_contact")})
        for beta0, mu in POINTS:
            for name in names:
                emit(f"pull_off_scalar[{name},{control},{beta0},{mu}]", compare.pull_off(name, mu=mu, beta0=beta0, control=control))
            emit(f"compare[{control},{beta0},{mu}]", compare.compare(mu=mu, beta0=beta0, control=control))
    for beta0, mu in POINTS:
        c = dhfield.load_curve(mu=mu, beta0=beta0, n=40)
        emit(f"dhfield.load_curve[{beta0},{mu}]", {k: getattr(c, k) for k in (
            "mu", "beta0", "ellipticity", "a_star", "b_star", "c_star", "d_star", "v", "W_star", "delta_star")})
        for name in compare.CURVE_MODEL_NAMES:
            emit(f"load_curve[{name},{beta0},{mu}]", compare.load_curve(name, mu=mu, beta0=beta0, n=40))
            w_po = float(compare.pull_off(name, mu=mu, beta0=beta0, control="load", check_closure=False)["W_star"])
            w = w_po + np.array([0.0, 0.01, 0.5, 3.0])
            emit(f"load_curve_at_load[{name},{beta0},{mu}]", compare.load_curve_at_load(name, mu=mu, beta0=beta0, w_star=w))
    for beta0, mu in POINTS:
        nd = ["--beta0", str(beta0), "--mu", str(mu)]
        for control in CONTROLS:
            for name in names:
                emit(f"cli.pulloff[{name},{control},{beta0},{mu}]",
                     cli(["pulloff", *nd, "--model", name, "--control", control, "--json"]))
            emit(f"cli.compare[{control},{beta0},{mu}]", cli(["compare", *nd, "--control", control, "--json"]))
        for name in compare.CURVE_MODEL_NAMES:
            emit(f"cli.curve[{name},{beta0},{mu}]", cli(["curve", *nd, "--model", name, "--n", "20", "--json"]))
    for control in CONTROLS:
        for name in names:
            emit(f"cli.pulloff.si[{name},{control}]", cli(["pulloff", *SI, "--model", name, "--control", control,
                                                           "--json"]))
        emit(f"cli.compare.si[{control}]", cli(["compare", *SI, "--control", control, "--json"]))
    for name in compare.CURVE_MODEL_NAMES:
        emit(f"cli.curve.si[{name}]", cli(["curve", *SI, "--model", name, "--n", "20", "--json"]))
        emit(f"cli.curve.si.load[{name}]", cli(["curve", *SI, "--model", name, "--n", "20", "--json",
                                                "--load-min=-1e-4", "--load-max", "1e-3"]))
    emit("cli.pulloff.default", cli(["pulloff", "--beta0", "0.9", "--mu", "1"]))
    emit("cli.curve.ellipticity", cli(["curve", "--beta0", "0.9", "--mu", "1", "--ellipticity", "0.8", "--n", "20",
                                       "--model", "dh-elliptic", "--json"]))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
