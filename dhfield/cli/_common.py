"""Shared pieces of the ``dhfield`` command line: parser class, JSON output, common options."""
from __future__ import annotations

import argparse
import json
import math

__all__ = ["OneLineParser", "UsageError", "print_json", "add_model_arguments", "model_names",
           "compare_record"]


class UsageError(Exception):
    """A command-line usage error (reported in one line, exit status 2)."""


class OneLineParser(argparse.ArgumentParser):
    """argparse with usage errors reduced to one line and exit status 2."""

    def error(self, message):
        raise UsageError(f"{self.prog}: {message}")


def _json_default(obj):
    import numpy as np

    if isinstance(obj, np.generic):
        return obj.item()
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    raise TypeError(type(obj))


def print_json(payload) -> None:
    """Print ``payload`` as one JSON object; non-finite floats become null."""
    def clean(x):
        if isinstance(x, float) and not math.isfinite(x):
            return None
        if isinstance(x, dict):
            return {k: clean(v) for k, v in x.items()}
        if isinstance(x, list):
            return [clean(v) for v in x]
        return x

    print(json.dumps(clean(json.loads(json.dumps(payload, default=_json_default))), sort_keys=False))


def add_model_arguments(p) -> None:
    """The dimensionless model inputs every analytic subcommand takes."""
    p.add_argument("--beta0", type=float, required=True, help="initial ellipticity b/a in (0, 1]")
    p.add_argument("--mu", type=float, required=True, help="Tabor parameter (Eq. 35), > 0")


def model_names():
    from ..compare import MODEL_NAMES

    return MODEL_NAMES


def compare_record(model, args) -> dict:
    """Pull-off record of one registry model for ``args.mu``, ``args.beta0``, ``args.control``."""
    from ..compare import pull_off

    rec = pull_off(model, args.mu, args.beta0, args.control)
    return {k: (v if isinstance(v, str) else float(v)) for k, v in rec.items()}
