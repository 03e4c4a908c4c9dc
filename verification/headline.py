"""The report's first screen: one sentence and one table on which model to use.

Both come from the stored BEM ground truth as the library tabulates it
(:mod:`dhfield.analysis.model_error`: every model's W* at the stored cases of
``data/adhesive_ground_truth_extended.nc``) and from the model registry
(:data:`dhfield.analysis.compare.RECOMMENDED_MODEL`); no number is typed in.

The error of a model at a stored case is :func:`dhfield.analysis.model_error.stored_case_error`: its
deviation from the stored BEM W* plus the BEM's own stated error, relative to the BEM W*,
the same estimate every pull-off of :mod:`dhfield.analysis.compare` carries as ``model_error``.

``python -m verification.headline`` prints the sentence and the table (Markdown).
"""
from __future__ import annotations

import itertools

import numpy as np

__all__ = ["WITHIN", "ModelRow", "model_rows", "within_box", "headline_sentence", "headline_table", "headline"]

#: The tolerance of the table's "within" column: 1 % of the BEM pull-off (issue 40).
WITHIN = 0.01


class ModelRow:
    """One model's error against the stored truth.

    Attributes
    ----------
    model : str
        Registry name of the model.
    n_cases, n_answered, n_within : int
        Stored cases, cases the model answers, answered cases within :data:`WITHIN`.
    worst, median : float
        Largest and median error over the answered cases [-] (NaN when none answered).
    worst_beta0, worst_mu : float
        The case of the largest error [-].
    box : tuple or None
        ``((beta0_lo, beta0_hi), (mu_lo, mu_hi), n)``: :func:`within_box`.
    """

    def __init__(self, model, beta0, mu, error):
        ok = np.isfinite(error)
        self.model = model
        self.n_cases = int(error.size)
        self.n_answered = int(ok.sum())
        self.n_within = int(np.sum(error[ok] <= WITHIN))
        self.worst = float(np.max(error[ok])) if ok.any() else float("nan")
        self.median = float(np.median(error[ok])) if ok.any() else float("nan")
        k = int(np.nanargmax(np.where(ok, error, -np.inf))) if ok.any() else 0
        self.worst_beta0, self.worst_mu = float(beta0[k]), float(mu[k])
        self.box = within_box(beta0, mu, error)


def within_box(beta0, mu, error, tol=WITHIN):
    """The largest box of stored cases in which every case is answered and within ``tol``.

    Parameters
    ----------
    beta0, mu, error : ndarray
        The stored cases and a model's error at each (NaN: not answered) [-].
    tol : float
        Tolerance on the error [-].

    Returns
    -------
    tuple or None
        ``((beta0_lo, beta0_hi), (mu_lo, mu_hi), n)``: the box, spanned by stored values of
        beta0 and mu, holding the most stored cases ``n`` (ties: the wider span in beta0, then in
        mu); None when no case is within ``tol``.
    """
    good = np.isfinite(error) & (error <= tol)
    if not good.any():
        return None
    bs, ms = np.unique(beta0), np.unique(mu)
    best, key = None, None
    for (i, j) in itertools.combinations_with_replacement(range(bs.size), 2):
        in_b = (beta0 >= bs[i]) & (beta0 <= bs[j])
        for (k, m) in itertools.combinations_with_replacement(range(ms.size), 2):
            inside = in_b & (mu >= ms[k]) & (mu <= ms[m])
            n = int(inside.sum())
            if n == 0 or not np.all(good[inside]):
                continue
            cand = (n, j - i, m - k)
            if key is None or cand > key:
                key, best = cand, ((float(bs[i]), float(bs[j])), (float(ms[k]), float(ms[m])), n)
    return best


def model_rows(models=None):
    """One :class:`ModelRow` per model of the registry, the recommended model first.

    Parameters
    ----------
    models : sequence of str, optional
        Registry names (default: every model tabulated at the stored cases).

    Returns
    -------
    list of ModelRow
    """
    from dhfield.analysis import _truth_table
    from dhfield.analysis.compare import RECOMMENDED_MODEL
    from dhfield.analysis.model_error import stored_case_error

    names = list(models) if models is not None else list(_truth_table.W_STAR_MODEL)
    names.sort(key=lambda n: n != RECOMMENDED_MODEL)
    return [ModelRow(n, *stored_case_error(n)) for n in names]


def _pct(x, digits=2):
    return "—" if not np.isfinite(x) else f"{100 * x:.{digits}f} %"


def _span(lo, hi):
    return f"{lo:g}" if lo == hi else f"{lo:g}–{hi:g}"


def _angle(beta0):
    from dhfield.core.geometry import skew_angle

    return float(np.degrees(skew_angle(beta0)))


def headline_sentence(rows=None):
    """The first sentence of the report: which model, how close to the truth, over what domain.

    Parameters
    ----------
    rows : list of ModelRow, optional
        :func:`model_rows` (computed when omitted).

    Returns
    -------
    str
        One Markdown sentence.
    """
    from dhfield.analysis.compare import DEFAULT_MODEL, RECOMMENDED_MODEL
    from dhfield.analysis.model_error import VERIFIED_BETA0, VERIFIED_MU

    rows = model_rows() if rows is None else rows
    r = next(x for x in rows if x.model == RECOMMENDED_MODEL)
    default = " (the default of the CLI and the Python API)" if DEFAULT_MODEL == RECOMMENDED_MODEL else ""
    answered = ("every one" if r.n_answered == r.n_cases else f"{r.n_answered}") + f" of the {r.n_cases}"
    return (f"**Use `{r.model}`**{default}: its pull-off is within "
            f"**{_pct(r.worst)}** of the self-consistent adhesive BEM (median {_pct(r.median)}; deviation plus the "
            f"BEM's own stated error) at {answered} stored cases, which span β0 = {_span(*VERIFIED_BETA0)} "
            f"(crossing angles {_angle(VERIFIED_BETA0[0]):.0f}–{_angle(VERIFIED_BETA0[1]):.0f}°) and "
            f"μ = {_span(*VERIFIED_MU)}; outside that box no BEM case checks any model, and every answer "
            f"there is flagged.")


def headline_table(rows=None):
    """The first table of the report: each model's worst and median error and where it is within 1 %.

    Parameters
    ----------
    rows : list of ModelRow, optional
        :func:`model_rows` (computed when omitted).

    Returns
    -------
    str
        A Markdown pipe table, the recommended model first.
    """
    from dhfield.analysis.compare import RECOMMENDED_MODEL

    rows = model_rows() if rows is None else rows
    lines = [f"| model | worst error | median error | cases within {100 * WITHIN:g} % | "
             f"largest box of stored cases within {100 * WITHIN:g} % |",
             "|---|---:|---:|---:|---|"]
    for r in rows:
        name = f"`{r.model}` (recommended)" if r.model == RECOMMENDED_MODEL else f"`{r.model}`"
        worst = _pct(r.worst) + (f" (β0 = {r.worst_beta0:g}, μ = {r.worst_mu:g})" if np.isfinite(r.worst) else "")
        cases = f"{r.n_within} of {r.n_cases}" + (f" ({r.n_cases - r.n_answered} refused)"
                                                  if r.n_answered < r.n_cases else "")
        if r.box is None:
            box = "none"
        else:
            (b0, b1), (m0, m1), n = r.box
            box = f"β0 {_span(b0, b1)}, μ {_span(m0, m1)} ({n} cases)"
        lines.append(f"| {name} | {worst} | {_pct(r.median)} | {cases} | {box} |")
    return "\n".join(lines)


def headline():
    """``(sentence, table)``: :func:`headline_sentence` and :func:`headline_table` on one set of rows."""
    rows = model_rows()
    return headline_sentence(rows), headline_table(rows)


if __name__ == "__main__":  # pragma: no cover
    s, t = headline()
    print(s + "\n\n" + t)
