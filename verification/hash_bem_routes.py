"""SHA-256 of every array and scalar of the BEM pull-off routes: a bit-for-bit reference for refactors.

Runs small but real cases of every route of :func:`dhfield.bem.adhesive_pull_off`
(located, bracket, march, displacement control by continuation) and of
:func:`dhfield.bem.refine_pull_off`, on the sphere and on an ellipse (beta0 < 1),
with ``keep_states=True``, and prints one line per result field: the route, the
field and the SHA-256 of its bytes (arrays: dtype, shape and data; states: every
array and scalar of every :class:`~dhfield.bem.ContactState`; wall times left out).
Two runs of the same code print the same lines; diff the output of two commits::

    PYTHONPATH=$PWD .venv/bin/python -m verification.hash_bem_routes > hashes.txt

``--skip FIELD`` leaves a field out everywhere (e.g. one added since the reference run).

About 1-2 minutes on one core.
"""
from __future__ import annotations

import dataclasses
import hashlib
import sys

import numpy as np

#: (label, mu, beta0, n, keyword arguments of adhesive_pull_off)
CASES = (
    ("located-sphere", 2.0, 1.0, 128, dict(search="located")),
    ("located-ellipse", 1.0, 0.6, 128, dict(search="located")),
    ("located-two-levels", 1.0, 1.0, 256, dict(search="located")),
    ("bracket-sphere", 2.0, 1.0, 64, dict(search="bracket")),
    ("bracket-nested", 1.0, 1.0, 128, dict(search="bracket", nested=True)),
    ("bracket-ellipse", 1.0, 0.6, 64, dict(search="bracket")),
    ("march-sphere", 1.0, 1.0, 64, dict(search="march")),
    ("march-ellipse", 1.0, 0.6, 48, dict(search="march")),
    ("displacement-sphere", 2.0, 1.0, 64, dict(control="displacement")),
    ("displacement-ellipse", 1.0, 0.6, 64, dict(control="displacement")),
    ("exponential-sphere", 1.0, 1.0, 64, dict(law="exponential", search="bracket")),
)
#: Fields never hashed: wall times differ between runs.
SKIP = {"elapsed"}


def digest(value) -> str:
    """SHA-256 of a value's bytes (arrays: dtype, shape and data; containers: their items in order)."""
    h = hashlib.sha256()

    def feed(v):
        if dataclasses.is_dataclass(v) and not isinstance(v, type):
            h.update(type(v).__name__.encode())
            for f in dataclasses.fields(v):
                if f.name not in SKIP:
                    h.update(f.name.encode())
                    feed(getattr(v, f.name))
        elif isinstance(v, np.ndarray):
            h.update(str(v.dtype).encode() + repr(v.shape).encode())
            h.update(np.ascontiguousarray(v).tobytes() if v.dtype != object else repr(v.tolist()).encode())
        elif isinstance(v, dict):
            for k in sorted(v):
                h.update(repr(k).encode())
                feed(v[k])
        elif isinstance(v, (list, tuple)):
            h.update(f"{type(v).__name__}{len(v)}".encode())
            for item in v:
                feed(item)
        elif isinstance(v, float):
            h.update(np.float64(v).tobytes())
        else:
            h.update(repr(v).encode())

    feed(value)
    return h.hexdigest()


#: The hashed fields of a BEM pull-off record (:class:`dhfield.core.records.PullOff`), in the order of
#: the BEM's former record type (AdhesivePullOff), so that the lines of a run before and after
#: the one-record change match; ``ellipticity`` and ``adhesive_ellipticity`` were ``beta_ab`` and
#: ``beta_cd``.  The record's other keys (model, geometry, sin_skew, v, at_zero_contact, warning)
#: are constants or functions of these.
FIELDS = ("mu", "beta0", "n", "law", "control", "W_star", "a_star", "b_star", "c_star", "d_star", "ellipticity",
          "adhesive_ellipticity", "delta_star", "converged", "n_steps", "iterations", "residual", "failures",
          "resolved", "half_width_x", "half_width_y", "elapsed", "path", "W_star_error", "note", "search")


def result_lines(label, res):
    """One line per field of :data:`FIELDS` of a BEM pull-off record (its path: one line per path field)."""
    for name in FIELDS:
        if name in SKIP:
            continue
        v = getattr(res, name)
        if name == "path":
            for g in dataclasses.fields(v):
                if g.name not in SKIP:
                    yield f"{label} path.{g.name} {digest(getattr(v, g.name))}"
        else:
            yield f"{label} {name} {digest(v)}"


def main(argv=None):
    """``argv``: case labels to run (default all); ``--skip FIELD`` leaves a field out everywhere
    (e.g. a field added since the reference run, to compare the rest)."""
    from dhfield.bem import adhesive_pull_off, refine_pull_off
    from dhfield.analysis.bem_start import AdhesiveOptions

    argv = list(argv or ())
    while "--skip" in argv:
        k = argv.index("--skip")
        SKIP.add(argv[k + 1])
        del argv[k:k + 2]
    only = set(argv)
    results = {}
    for label, mu, beta0, n, kw in CASES:
        if only and label not in only:
            continue
        kw = dict(kw)
        nested = kw.pop("nested", None)     # a numerical setting: AdhesiveOptions.nested
        res = adhesive_pull_off(mu=mu, beta0=beta0, n=n, progress=False, **kw,
                                options=AdhesiveOptions(keep_states=True, nested=nested))
        results[label] = res
        print(f"{label} route={res.search} W_star={res.W_star!r}", flush=True)
        for line in result_lines(label, res):
            print(line, flush=True)
    for label, coarse in (("refine-sphere", "march-sphere"), ("refine-ellipse", "march-ellipse")):
        if coarse in results:
            res = refine_pull_off(results[coarse], 2 * results[coarse].n, progress=False,
                                  options=AdhesiveOptions(keep_states=True))
            print(f"{label} route={res.search} W_star={res.W_star!r}", flush=True)
            for line in result_lines(label, res):
                print(line, flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
