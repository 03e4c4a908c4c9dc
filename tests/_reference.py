"""Loader for the closed-form reference values in data/ (see data/README.md)."""
import csv
from pathlib import Path

DATA = Path(__file__).resolve().parent.parent / "data"


def circular_pull_off():
    """{(model, control): row} from data/circular_pull_off_closed_forms.csv."""
    with open(DATA / "circular_pull_off_closed_forms.csv") as fh:
        rows = csv.DictReader(line for line in fh if not line.startswith("#"))
        return {(r["model"], r["control"]): {k: (float(v) if k in ("W_star", "a_star", "delta_star") else v)
                                              for k, v in r.items()} for r in rows}
