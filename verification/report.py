"""Build the dhfield verification report: one self-contained HTML file plus a Markdown summary.

Usage::

    python -m verification.report [--out out] [--quick] [--sections a,b] [--no-progress] [--jobs N]

The builder

* starts from a clean output directory: it removes the artefacts of a previous
  report under ``--out`` (``report.html``, ``summary.md``, ``checks.json`` and the
  per-section directories ``<out>/<section>/``) and nothing else;
* discovers the section modules ``verification/sec_<name>.py`` in the fixed order
  :data:`SECTION_ORDER` (whichever exist) and runs each one with
  ``run(outdir=<out>/<name>, quick, progress)`` (see :mod:`verification._api`);
  a section that fails to import or raises is reported as a FAILED check, the
  other sections still run;
* writes ``report.html`` (figures embedded as base64 data URIs, CSS inline, no
  external resource), ``summary.md`` (the PASS/FAIL table with links to the
  figure and netCDF files) and ``checks.json`` (the same table, machine-readable),
  each atomically (temporary file, then ``os.replace``);
* opens both ``report.html`` and ``summary.md`` with the **first screen**
  (:func:`first_screen`, from :mod:`verification.headline`): one sentence (which model to use,
  how close it is to the stored BEM ground truth, over what domain) and one table (each model's
  worst and median error there, and where it is within 1 %); then the **verdict**: what the
  checks conclude about the paper, in words and numbers, gathered from every
  section's ``Section.verdict`` in :data:`VERDICT_ORDER` (the adhesion map and the
  recommended model first, then the adhesive ground truth), then "which model to use
  when" (``Section.guide``);
  the PASS/FAIL count and the checks table come after it;
* turns the literature and equation references of the checks table into links a
  reader can open (:func:`link_references`: DOIs, report-section anchors);
* exits with status 1 if any check failed or any section crashed, else 0.

The builder contains no physics: the sections call the library and return their
checks, figures and tables.  Progress lines go to stderr as
``[2/4] models: <message> (12.3 s)``.
"""
from __future__ import annotations

import argparse
import base64
import contextlib
import datetime as _dt
import html
import importlib
import json
import os
import platform
import re
import shutil
import sys
import tempfile
import time
import traceback
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

from verification._api import VECTOR_FORMATS, Check, Section
from verification._style import figure_style

__all__ = ["SECTION_ORDER", "VERDICT_ORDER", "SectionResult", "main", "run_sections", "render_html",
           "render_summary", "markdown_to_html", "link_references", "collect_verdict", "first_screen"]

#: Section modules in report order: ``verification/sec_<name>.py``.  The report opens with the
#: adhesion map (its first figure) and the recommended model.
SECTION_ORDER = ("map", "analytic", "models", "fields", "periphery", "adhesive")
#: Whose verdict leads: the adhesion map (the recommended model against the ground truth, and over
#: the whole domain), then the self-consistent adhesive solution (ground truth), the closures against
#: elliptical JKR, the periphery/Eq. (30) analysis, the analytic core, the BEM.
#: Sections not named here follow in :data:`SECTION_ORDER`.
VERDICT_ORDER = ("map", "adhesive", "models", "periphery", "analytic", "fields")
#: The section whose verdict is the ground truth; the verdict says so when it is absent.
GROUND_TRUTH_SECTION = "adhesive"
#: Files of a previous report that the builder removes from ``--out`` before running.
REPORT_FILES = ("report.html", "summary.md", "checks.json")

_ROOT = Path(__file__).resolve().parent.parent


# --------------------------------------------------------------------------- running


@dataclass
class SectionResult:
    """One section's outcome: the returned :class:`Section` (or a stand-in on failure)."""

    name: str
    section: Section
    seconds: float
    outdir: Path
    crashed: bool = False
    error: str = ""
    checks: list[Check] = field(default_factory=list)


def _available_sections(requested=None):
    """Names of the section modules to run, in :data:`SECTION_ORDER`.

    Parameters
    ----------
    requested : sequence of str, optional
        Subset asked for on the command line; unknown names raise ValueError.

    Returns
    -------
    list of str
        Requested (or all) names whose module file exists.  A requested name whose
        file is missing is kept, so that the run reports it as a failed import.
    """
    here = Path(__file__).resolve().parent
    if requested:
        unknown = [s for s in requested if s not in SECTION_ORDER]
        if unknown:
            raise ValueError(f"--sections must be a comma-separated subset of {','.join(SECTION_ORDER)}; "
                             f"got {','.join(unknown)!r}")
        return [s for s in SECTION_ORDER if s in requested]
    return [s for s in SECTION_ORDER if (here / f"sec_{s}.py").is_file()]


def _failed_section(name, title, message, tb):
    text = f"**This section did not complete.** {message}\n\n```\n{tb.rstrip()}\n```"
    check = Check(name=f"section '{name}' runs without error", value=float("nan"), tolerance=float("nan"),
                  passed=False, reference=message, comparison="runs")
    return Section(title=title, text=text, checks=[check])


#: A caption must cite what it reproduces: "Eq. (31)", "Eqs. 13b/15", "Fig. 4", "Figs. 4-7", "Eq. B2".
_CITATION = re.compile(r"\b(Eqs?\.\s*\(?[AB]?\d|Figs?\.\s*\d|Equations?\s*\(?\d|Figures?\s*\d)", re.IGNORECASE)


def _validate_section(name, sec):
    """Return a list of contract problems of a returned Section (empty when fine)."""
    problems = []
    if not isinstance(sec, Section):
        return [f"run() returned {type(sec).__name__}, not verification._api.Section"]
    for fig in sec.figures:
        p = Path(fig.path)
        if not p.is_file():
            problems.append(f"figure file missing: {p}")
        if not str(fig.caption).strip():
            problems.append(f"figure without caption: {p.name}")
        elif not _CITATION.search(str(fig.caption)):
            problems.append(f"figure caption cites no equation or paper figure: {p.name}")
    for ds in sec.datasets:
        if not Path(ds).is_file():
            problems.append(f"dataset file missing: {ds}")
    for chk in sec.checks:
        if not isinstance(chk, Check):
            problems.append(f"check of type {type(chk).__name__}, not Check")
    return problems


def _run_one(name: str, i: int, total: int, outdir: Path, quick: bool, progress: Callable[[str], None]):
    """Import and run one section; a failure becomes a failed Section, never an exception."""
    outdir.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()

    def sec_progress(msg):
        progress(f"[{i}/{total}] {name}: {msg} ({time.perf_counter() - t0:.1f} s)")

    sec_progress("start")
    crashed, error = False, ""
    try:
        module = importlib.import_module(f"verification.sec_{name}")
    except BaseException as exc:  # noqa: BLE001 - a broken section must not stop the report
        if isinstance(exc, KeyboardInterrupt):
            raise
        crashed, error = True, f"import of verification.sec_{name} failed: {exc!r}"
        sec = _failed_section(name, f"{name} (import failed)", error, traceback.format_exc())
    else:
        try:
            with figure_style():  # print-size fonts for every figure the section draws
                sec = module.run(outdir, quick, sec_progress)
            problems = _validate_section(name, sec)
            if problems and not isinstance(sec, Section):
                crashed, error = True, problems[0]
                sec = _failed_section(name, name, error, "")
            elif problems:
                sec.checks.append(Check(f"section '{name}' follows the report contract",
                                        float(len(problems)), 0.0, False,
                                        "; ".join(problems)[:500], "<="))
        except BaseException as exc:  # noqa: BLE001
            if isinstance(exc, KeyboardInterrupt):
                raise
            crashed, error = True, f"run() raised {exc!r}"
            sec = _failed_section(name, f"{name} (crashed)", error, traceback.format_exc())
    dt = time.perf_counter() - t0
    n_fail = sum(not c.passed for c in sec.checks)
    sec_progress(f"done: {len(sec.checks)} checks, {n_fail} failed, {len(sec.figures)} figures"
                 + (f" -- {error}" if error else ""))
    return SectionResult(name, sec, dt, outdir, crashed, error, list(sec.checks))


def _stderr_progress(line):
    print(line, file=sys.stderr, flush=True)


def _silent_progress(line):
    pass


def _run_one_in_worker(name, i, total, outdir, quick, show_progress):
    """Entry point of a worker process (picklable arguments only)."""
    import matplotlib

    matplotlib.use("Agg")
    return _run_one(name, i, total, outdir, quick, _stderr_progress if show_progress else _silent_progress)


def run_sections(out: Path, names, quick: bool, progress: Callable[[str], None], jobs: int = 1,
                 show_progress: bool = True):
    """Import and run each section; never raises for a section's failure.

    Parameters
    ----------
    out : Path
        Report directory; section ``name`` writes under ``out/name``.
    names : list of str
        Section names in order.
    quick : bool
        Passed to every section's ``run``.
    progress : callable
        ``progress(line)`` prints one progress line (used when ``jobs == 1``).
    jobs : int
        Number of sections run at the same time, each in its own process
        (``jobs > 1``); results keep the order of ``names``.
    show_progress : bool
        Whether worker processes print progress lines to stderr (``jobs > 1``).

    Returns
    -------
    list of SectionResult
    """
    total = len(names)
    if jobs <= 1 or total <= 1:
        return [_run_one(name, i, total, out / name, quick, progress) for i, name in enumerate(names, 1)]
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor

    ctx = multiprocessing.get_context("spawn")

    def isolated(i, name):
        # one process per section: a worker that dies (signal, os._exit) only fails its own section
        try:
            with ProcessPoolExecutor(max_workers=1, mp_context=ctx) as pool:
                return pool.submit(_run_one_in_worker, name, i, total, out / name, quick, show_progress).result()
        except Exception as exc:  # noqa: BLE001
            error = f"worker process failed: {exc!r}"
            sec = _failed_section(name, f"{name} (crashed)", error, traceback.format_exc())
            return SectionResult(name, sec, float("nan"), out / name, True, error, list(sec.checks))

    with ThreadPoolExecutor(max_workers=min(jobs, total)) as threads:
        futures = [threads.submit(isolated, i, name) for i, name in enumerate(names, 1)]
        results = {name: fut.result() for name, fut in zip(names, futures)}
    return [results[name] for name in names]


# --------------------------------------------------------------------------- cleaning


def clean_output(out: Path):
    """Remove a previous report's artefacts from ``out`` (and nothing else).

    Removes :data:`REPORT_FILES` and the directories ``out/<section>`` for every
    name of :data:`SECTION_ORDER`.  Symbolic links are unlinked, never followed.
    """
    out.mkdir(parents=True, exist_ok=True)
    for name in REPORT_FILES:
        p = out / name
        if p.is_symlink() or p.is_file():
            p.unlink()
    for name in SECTION_ORDER:
        p = out / name
        if p.is_symlink() or p.is_file():
            p.unlink()
        elif p.is_dir():
            shutil.rmtree(p)
    for stale in out.glob(".report.html.*.part"):
        stale.unlink()


# --------------------------------------------------------------------------- metadata


def _git_commit():
    from dhfield.io import git_commit

    return git_commit(short=12)


def collect_metadata(argv, quick):
    """Header facts: version, date, commit, command line, machine."""
    try:
        import dhfield
        version = dhfield.__version__
        doi = getattr(dhfield, "PAPER_DOI", "")
    except Exception:  # noqa: BLE001 - the header must not fail
        version, doi = "unavailable", ""
    import numpy
    import scipy
    return {
        "dhfield version": version,
        "paper": f"Zini et al., Tribology Letters 66:30 (2018), doi:{doi}" if doi else "",
        "date (UTC)": _dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%d %H:%M:%S"),
        "git commit": _git_commit(),
        "command line": " ".join(["python -m verification.report", *argv]),
        "mode": "quick" if quick else "default",
        "machine": f"{platform.platform()}; {platform.machine()}; {os.cpu_count()} cores",
        "python": f"{platform.python_version()} (numpy {numpy.__version__}, scipy {scipy.__version__})",
    }


# --------------------------------------------------------------------------- formatting


def _fmt(x):
    try:
        x = float(x)
    except (TypeError, ValueError):
        return str(x)
    if x != x:
        return "nan"
    if x == 0:
        return "0"
    if abs(x) >= 1e4 or abs(x) < 1e-3:
        return f"{x:.3e}"
    return f"{x:.6g}"


def _rel(path: Path, base: Path) -> str:
    try:
        return Path(os.path.relpath(Path(path).resolve(), base.resolve())).as_posix()
    except ValueError:  # other drive on Windows
        return Path(path).as_posix()


_INLINE_CODE = re.compile(r"`([^`]+)`")
_BOLD = re.compile(r"\*\*(.+?)\*\*")
_ITALIC = re.compile(r"(?<![\*\w])\*(?!\s)(.+?)(?<!\s)\*(?![\*\w])")
_LINK = re.compile(r"\[([^\]]+)\]\(([^)\s]+)\)")


_CODE_SLOT = re.compile("\x00(\\d+)\x00")


def _inline(text: str) -> str:
    """Inline Markdown (code, bold, italic, links) to HTML; everything else escaped.

    Code spans are set aside first (as numbered slots), so that bold, italic and links may
    enclose them (``**Use `md-elliptic`**``) and nothing inside a code span is read as markup.
    """
    codes = []

    def slot(m):
        codes.append(f"<code>{html.escape(m.group(1))}</code>")
        return f"\x00{len(codes) - 1}\x00"

    s = html.escape(_INLINE_CODE.sub(slot, text.replace("\x00", "")), quote=False)
    s = _LINK.sub(lambda m: f'<a href="{html.escape(m.group(2))}">{m.group(1)}</a>', s)
    s = _BOLD.sub(r"<strong>\1</strong>", s)
    s = _ITALIC.sub(r"<em>\1</em>", s)
    return _CODE_SLOT.sub(lambda m: codes[int(m.group(1))], s)


def _table_row(line: str):
    line = line.strip()
    if line.startswith("|"):
        line = line[1:]
    if line.endswith("|"):
        line = line[:-1]
    return [c.strip() for c in line.split("|")]


_SEP = re.compile(r"^\s*\|?\s*:?-{2,}:?\s*(\|\s*:?-{2,}:?\s*)*\|?\s*$")


def markdown_to_html(text: str) -> str:
    """Render the Markdown subset used by the sections to HTML.

    Supported: ATX headings, paragraphs, ``-``/``*``/``1.`` lists, pipe tables,
    fenced code blocks, inline code, bold, italic and links.  Raw HTML is escaped.

    Parameters
    ----------
    text : str
        Markdown source.

    Returns
    -------
    str
        HTML fragment.
    """
    lines = (text or "").splitlines()
    out, para = [], []
    i = 0

    def flush():
        if para:
            out.append("<p>" + _inline(" ".join(s.strip() for s in para)) + "</p>")
            para.clear()

    while i < len(lines):
        line = lines[i]
        stripped = line.strip()
        if stripped.startswith("```"):
            flush()
            j = i + 1
            block = []
            while j < len(lines) and not lines[j].strip().startswith("```"):
                block.append(lines[j])
                j += 1
            out.append("<pre><code>" + html.escape("\n".join(block)) + "</code></pre>")
            i = j + 1
            continue
        if not stripped:
            flush()
            i += 1
            continue
        m = re.match(r"^(#{1,6})\s+(.*)$", stripped)
        if m:
            flush()
            level = min(len(m.group(1)) + 2, 6)  # section titles are <h2>; text headings start at <h3>
            out.append(f"<h{level}>{_inline(m.group(2))}</h{level}>")
            i += 1
            continue
        if stripped.startswith("|") and i + 1 < len(lines) and _SEP.match(lines[i + 1]):
            flush()
            head = _table_row(stripped)
            rows = []
            j = i + 2
            while j < len(lines) and lines[j].strip().startswith("|"):
                rows.append(_table_row(lines[j]))
                j += 1
            t = ["<table><thead><tr>" + "".join(f"<th>{_inline(h)}</th>" for h in head) + "</tr></thead><tbody>"]
            for r in rows:
                t.append("<tr>" + "".join(f"<td>{_inline(c)}</td>" for c in r) + "</tr>")
            t.append("</tbody></table>")
            out.append("".join(t))
            i = j
            continue
        m = re.match(r"^\s*([-*]|\d+\.)\s+(.*)$", line)
        if m:
            flush()
            ordered = m.group(1)[0].isdigit()
            tag = "ol" if ordered else "ul"
            items = []
            j = i
            while j < len(lines):
                mm = re.match(r"^\s*([-*]|\d+\.)\s+(.*)$", lines[j])
                if mm and (mm.group(1)[0].isdigit()) == ordered:
                    items.append(mm.group(2))
                elif lines[j].strip() and lines[j].startswith((" ", "\t")) and items:
                    items[-1] += " " + lines[j].strip()  # continuation line
                else:
                    break
                j += 1
            out.append(f"<{tag}>" + "".join(f"<li>{_inline(it)}</li>" for it in items) + f"</{tag}>")
            i = j
            continue
        para.append(line)
        i += 1
    flush()
    return "\n".join(out)


#: Literature cited by the checks, with the DOI a reader can open (percent-encoded parentheses,
#: so that the Markdown link syntax survives).
REFERENCE_LINKS = (
    (r"Zini et al\.?,? (?:\(2018\)|2018)", "10.1007/s11249-017-0976-8"),
    (r"Greenwood\s*(?:&|–|-|and)\s*Johnson\s*(?:\(1998\)|1998)|\bGJ98\b", "10.1088/0022-3727/31/22/017"),
    (r"Johnson\s*(?:&|and)\s*Greenwood\s*(?:\(2005\)|2005)|\bJG05\b", "10.1088/0022-3727/38/7/012"),
    (r"Johnson,?\s*Kendall\s*(?:&|and)\s*Roberts\s*(?:\(1971\)|1971)|\bJKR \(1971\)", "10.1098/rspa.1971.0141"),
    (r"Derjaguin et al\.?\s*(?:\(1975\)|1975)|\bDMT \(1975\)", "10.1016/0021-9797%2875%2990018-1"),
    (r"Maugis\s*(?:\(1992\)|1992)", "10.1016/0021-9797%2892%2990285-T"),
    (r"Johnson\s*(?:\(1985\)|1985)", "10.1017/CBO9781139171731"),
)
#: "Eq. (31)", "Eqs. (13b)/(15)", "Eq. 27": equations of Zini et al. (2018), linked to the paper.
_EQ_REF = re.compile(r"\bEqs?\.\s*(?:\(\s*[AB]?\d+[a-z]?\s*\)|[AB]?\d+[a-z]?)")
#: "report section periphery": an anchor in this report.
_SECTION_REF = re.compile(r"report section (\w+)")
_MD_LINK_OR_CODE = re.compile(r"(\[[^\]]*\]\([^)]*\)|`[^`]*`)")


def link_references(text: str, equations: bool = True) -> str:
    """Markdown links for the references of a check: DOIs of the cited papers and section anchors.

    "Johnson & Greenwood (2005)" becomes a link to its DOI, "Eq. (31)" a link to the
    paper (Zini et al. 2018; only when ``equations``) and "report section fields" a
    link to that section of report.html.  Existing links and inline code are left alone.
    """
    def outside_links(text, pattern, repl):
        pieces = _MD_LINK_OR_CODE.split(text)
        return "".join(p if k % 2 else re.sub(pattern, repl, p) for k, p in enumerate(pieces))

    text = str(text)
    for pattern, doi in REFERENCE_LINKS:
        text = outside_links(text, pattern, lambda m, d=doi: f"[{m.group(0)}](https://doi.org/{d})")
    if equations:
        text = outside_links(text, _EQ_REF, lambda m: f"[{m.group(0)}](https://doi.org/{REFERENCE_LINKS[0][1]})")
    return outside_links(text, _SECTION_REF,
                         lambda m: f"[report section {m.group(1)}](report.html#{_anchor(m.group(1))})")


def collect_verdict(results):
    """The report's lead: ``(verdict, guide)``, lists of ``(section name, Markdown line)``.

    Verdict lines come from ``Section.verdict`` in :data:`VERDICT_ORDER`; a section
    that crashed or has failed checks is flagged in place of (or before) its lines,
    and the absence of the ground-truth section is said, not hidden.
    """
    rank = {name: k for k, name in enumerate(VERDICT_ORDER)}
    order = sorted(results, key=lambda r: (rank.get(r.name, len(rank)), SECTION_ORDER.index(r.name)
                                           if r.name in SECTION_ORDER else len(SECTION_ORDER)))
    verdict, guide = [], []
    names = {r.name for r in results}
    if GROUND_TRUTH_SECTION not in names:
        verdict.append((GROUND_TRUTH_SECTION,
                        "*Ground truth:* no self-consistent adhesive solution in this run (report section "
                        f"`{GROUND_TRUTH_SECTION}` absent), so the closures below are judged against elliptical "
                        "JKR (Johnson & Greenwood 2005), which is exact only as μ → ∞."))
    for r in order:
        n_fail = sum(not c.passed for c in r.checks)
        if r.crashed:
            verdict.append((r.name, f"**Section `{r.name}` did not complete** ({r.error}): its conclusions are "
                                    "missing from this verdict."))
            continue
        lines = list(getattr(r.section, "verdict", []) or [])
        if n_fail and lines:
            verdict.append((r.name, f"**Section `{r.name}` has {n_fail} failed check(s)**: its conclusions "
                                    "below are not verified."))
        verdict += [(r.name, line) for line in lines]
        guide += [(r.name, line) for line in (getattr(r.section, "guide", []) or [])]
    return verdict, guide


def _checks_status(results):
    rows = [c for r in results for c in r.checks]
    n_fail = sum(not c.passed for c in rows)
    ok = n_fail == 0 and not any(r.crashed for r in results)
    return ok, n_fail, len(rows)


_CSS = """
body{font-family:-apple-system,"Segoe UI",Helvetica,Arial,sans-serif;margin:0;color:#1b1b1b;background:#fff;
line-height:1.45}
main{max-width:1100px;margin:0 auto;padding:1.5em 2em 4em}
h1{font-size:1.7em;margin-bottom:.2em}
h2{border-bottom:2px solid #ccd;padding-bottom:.2em;margin-top:2.2em}
table{border-collapse:collapse;margin:.8em 0;font-size:.88em}
th,td{border:1px solid #ccd;padding:.25em .55em;text-align:left;vertical-align:top}
th{background:#eef0f6}
td.num{text-align:right;font-family:ui-monospace,Menlo,Consolas,monospace;white-space:nowrap}
.pass{background:#dff3df;color:#145214;font-weight:bold}
.fail{background:#fadbd8;color:#8a1010;font-weight:bold}
.verdict{font-size:1.25em;padding:.6em 1em;border-radius:4px;display:inline-block;margin:.6em 0}
figure{margin:1.4em 0;padding:.6em;border:1px solid #e2e4ec;border-radius:4px;background:#fcfcfe}
figure img{max-width:100%;height:auto;display:block;margin:0 auto}
figcaption{font-size:.9em;color:#333;margin-top:.4em}
code,pre{font-family:ui-monospace,Menlo,Consolas,monospace;font-size:.9em;background:#f3f4f8}
pre{padding:.6em;overflow-x:auto}
dl.meta{display:grid;grid-template-columns:max-content auto;gap:.15em 1em;font-size:.9em}
dl.meta dt{font-weight:bold}dl.meta dd{margin:0}
nav ul{padding-left:1.2em}
.small{font-size:.85em;color:#555}
section.lead{border-left:5px solid #3b5b9a;background:#f5f7fc;padding:.4em 1.2em .8em;margin:.6em 0 1.2em}
section.lead h2{margin-top:.4em;border:none}
section.lead li{margin:.35em 0}
section.first{border-left-color:#1b7837;background:#f3faf3}
p.headline{font-size:1.15em}
"""


def _img_tag(path: Path, alt: str) -> str:
    data = Path(path).read_bytes()
    suffix = Path(path).suffix.lower()
    mime = {".png": "image/png", ".svg": "image/svg+xml", ".jpg": "image/jpeg", ".jpeg": "image/jpeg",
            ".gif": "image/gif"}.get(suffix, "application/octet-stream")
    b64 = base64.b64encode(data).decode("ascii")
    return f'<img src="data:{mime};base64,{b64}" alt="{html.escape(alt)}">'


def _checks_table_html(rows):
    head = ("<table><thead><tr><th>section</th><th>check</th><th>value</th><th>relation</th>"
            "<th>tolerance</th><th>verdict</th><th>reference</th></tr></thead><tbody>")
    body = []
    for sec_name, c in rows:
        cls = "pass" if c.passed else "fail"
        body.append(
            f"<tr><td><a href='#{_anchor(sec_name)}'>{html.escape(sec_name)}</a></td><td>{_inline(c.name)}</td><td class=num>{_fmt(c.value)}</td>"
            f"<td>{html.escape(c.comparison)}</td><td class=num>{_fmt(c.tolerance)}</td>"
            f"<td class={cls}>{'PASS' if c.passed else 'FAIL'}</td><td>{_inline(link_references(c.reference))}</td></tr>")
    return head + "".join(body) + "</tbody></table>"


def _anchor(name):
    return "sec-" + re.sub(r"[^a-z0-9]+", "-", name.lower())


def first_screen():
    """The report's first screen: ``(sentence, table)`` in Markdown (:func:`verification.headline.headline`).

    Which model to use, how close it is to the stored BEM ground truth and over what domain, then
    every model's worst and median error there.  A failure to build it is said in the sentence
    (the report still runs), with an empty table.
    """
    try:
        from verification.headline import headline

        return headline()
    except Exception as exc:  # noqa: BLE001 - the first screen must not stop the report
        return (f"**The first screen could not be built** ({exc!r}): see the verdict below.", "")


def _first_screen_html(screen):
    sentence, table = screen
    return ("<section id='first-screen' class='lead first'><h2>Which model to use</h2>"
            f"<p class=headline>{_inline(sentence)}</p>" + markdown_to_html(table)
            + "<p class=small>Error: a model's deviation from the stored BEM pull-off plus the BEM's own "
              "stated error, relative to the BEM pull-off, at each stored case (<code>dhfield.analysis.model_error</code>); "
              "the box is the largest one, spanned by stored β0 and μ, in which every case is within 1 %. "
              "The detail is below: <a href='#verdict'>verdict</a>, <a href='#guide'>which model when</a>, "
              "<a href='#summary'>checks</a>.</p></section>")


def _lead_html(results):
    """The verdict and "which model to use when", as the first content of the report."""
    verdict, guide = collect_verdict(results)

    def items(rows):
        return "".join(f"<li>{_inline(link_references(line, equations=False))} <a class=small href='#{_anchor(name)}'>"
                       f"[{html.escape(name)}]</a></li>" for name, line in rows)

    parts = ["<section id='verdict' class='lead'><h2>Verdict: what the checks conclude about the paper</h2>",
             "<p class=small>Zini et al. (2018), doi:10.1007/s11249-017-0976-8, extended double-Hertz model of "
             "an adhesive elliptical contact. Every number below is computed by the report section named in "
             "brackets.</p>",
             f"<ul>{items(verdict)}</ul>" if verdict else "<p>No section stated a verdict.</p>"]
    if guide:
        parts.append(f"<h3 id='guide'>Which model to use when</h3><ul>{items(guide)}</ul>")
    parts.append("</section>")
    return "".join(parts)


def render_html(results, meta, out: Path, total_seconds: float, screen=None) -> str:
    """The complete, self-contained HTML report as a string.

    The first screen (:func:`first_screen`, or ``screen``) first, then the verdict, then the checks.
    """
    all_rows = [(r.name, c) for r in results for c in r.checks]
    ok, n_fail, n_all = _checks_status(results)
    verdict = (f"<div class='verdict pass'>ALL {n_all} CHECKS PASS</div>" if ok else
               f"<div class='verdict fail'>{n_fail} OF {n_all} CHECKS FAIL"
               + (" (a section crashed)" if not n_fail else "") + "</div>")
    parts = ["<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>",
             "<meta name='viewport' content='width=device-width, initial-scale=1'>",
             "<title>dhfield verification report</title>", f"<style>{_CSS}</style></head><body><main>",
             "<h1>dhfield verification report</h1>",
             _first_screen_html(screen if screen is not None else first_screen()),
             _lead_html(results),
             verdict,
             "<p>Verification of the extended double-Hertz model of an adhesive elliptical contact "
             "(Zini et al., Tribology Letters 2018) as implemented in <code>dhfield</code>.</p>",
             "<dl class=meta>"]
    for k, v in meta.items():
        parts.append(f"<dt>{html.escape(k)}</dt><dd>{html.escape(str(v))}</dd>")
    parts.append(f"<dt>wall time</dt><dd>{total_seconds:.1f} s</dd></dl>")
    parts.append("<nav><h2>Contents</h2><ul><li><a href='#first-screen'>Which model to use</a></li>"
                 "<li><a href='#verdict'>Verdict</a></li>")
    for r in results:
        nf = sum(not c.passed for c in r.checks)
        badge = "<span class=pass>PASS</span>" if nf == 0 and not r.crashed else f"<span class=fail>{nf} FAIL</span>"
        parts.append(f"<li><a href='#{_anchor(r.name)}'>{html.escape(r.section.title)}</a> {badge} "
                     f"<span class=small>({r.seconds:.1f} s)</span></li>")
    parts.append("<li><a href='#summary'>Summary of checks</a></li></ul></nav>")
    parts.append("<h2 id='summary'>Summary of checks</h2>")
    parts.append(_checks_table_html(all_rows))
    for r in results:
        sec = r.section
        parts.append(f"<section id='{_anchor(r.name)}'><h2>{html.escape(sec.title)}</h2>")
        parts.append(f"<p class=small>Section <code>{html.escape(r.name)}</code>, {r.seconds:.1f} s; "
                     f"files under <code>{html.escape(_rel(r.outdir, out))}/</code>.</p>")
        parts.append(markdown_to_html(sec.text))
        for tbl in sec.tables:
            parts.append(markdown_to_html(tbl))
        for k, fig in enumerate(sec.figures, 1):
            p = Path(fig.path)
            if p.is_file():
                img = _img_tag(p, f"{sec.title}, figure {k}")
            else:
                img = f"<p class=fail>missing figure file {html.escape(str(p))}</p>"
            vecs = [v for v in (p.with_suffix("." + f) for f in VECTOR_FORMATS) if v.is_file()]
            files = html.escape(_rel(p, out)) + "".join(f", <a href='{html.escape(_rel(v, out))}'>"
                                                        f"{html.escape(_rel(v, out))}</a>" for v in vecs)
            parts.append(f"<figure>{img}<figcaption><strong>{html.escape(r.name)} figure {k}.</strong> "
                         f"{_inline(fig.caption)} <span class=small>[{files}]</span>"
                         f"</figcaption></figure>")
        if r.checks:
            parts.append("<h3>Checks</h3>" + _checks_table_html([(r.name, c) for c in r.checks]))
        if sec.datasets:
            parts.append("<h3>Datasets (netCDF)</h3><ul>")
            for ds in sec.datasets:
                rel = _rel(Path(ds), out)
                parts.append(f"<li><a href='{html.escape(rel)}'><code>{html.escape(rel)}</code></a></li>")
            parts.append("</ul>")
        parts.append("</section>")
    parts.append("</main></body></html>")
    return "\n".join(parts)


def _md_cell(s) -> str:
    return str(s).replace("|", "\\|").replace("\n", " ")


def render_summary(results, meta, out: Path, total_seconds: float, screen=None) -> str:
    """The Markdown summary: the first screen (:func:`first_screen`, or ``screen``), the verdict and
    model guide, then header, PASS/FAIL table, links."""
    all_rows = [(r.name, c) for r in results for c in r.checks]
    ok, n_fail, n_all = _checks_status(results)
    verdict, guide = collect_verdict(results)
    sentence, table = screen if screen is not None else first_screen()
    lines = ["# dhfield verification report: summary", "", "## Which model to use", "", sentence, ""]
    if table:
        lines += [table, ""]
    lines += ["## Verdict: what the checks conclude about the paper", ""]
    lines += [f"- {link_references(line, False)} ([{name}](report.html#{_anchor(name)}))" for name, line in verdict]
    if not verdict:
        lines.append("- No section stated a verdict.")
    if guide:
        lines += ["", "## Which model to use when", ""]
        lines += [f"- {link_references(line, False)} ([{name}](report.html#{_anchor(name)}))" for name, line in guide]
    lines += ["", f"**Checks: {'PASS' if ok else 'FAIL'}** ({n_all - n_fail} of {n_all} checks pass"
              + ("; a section crashed" if any(r.crashed for r in results) else "")
              + "). Full report: [report.html](report.html)", ""]
    for k, v in meta.items():
        lines.append(f"- **{k}:** {_md_cell(v)}")
    lines.append(f"- **wall time:** {total_seconds:.1f} s")
    lines += ["", "| section | check | value | relation | tolerance | verdict | reference |",
              "|---|---|---:|---|---:|---|---|"]
    for name, c in all_rows:
        lines.append(f"| {name} | {_md_cell(c.name)} | {_fmt(c.value)} | {_md_cell(c.comparison)} | "
                     f"{_fmt(c.tolerance)} | {'PASS' if c.passed else '**FAIL**'} | "
                     f"{_md_cell(link_references(c.reference))} |")
    lines.append("")
    lines.append("## Sections")
    for r in results:
        lines += ["", f"### {r.section.title}", "",
                  f"`{r.name}`: {r.seconds:.1f} s, {len(r.checks)} checks, "
                  f"{sum(not c.passed for c in r.checks)} failed" + (f"; **{r.error}**" if r.error else ""), ""]
        for k, fig in enumerate(r.section.figures, 1):
            rel = _rel(Path(fig.path), out)
            vecs = [v for v in (Path(fig.path).with_suffix("." + f) for f in VECTOR_FORMATS) if v.is_file()]
            alt = f" ({', '.join(f'[{v.suffix[1:].upper()}]({_rel(v, out)})' for v in vecs)})" if vecs else ""
            lines.append(f"- Figure {k}: [{rel}]({rel}){alt} — {_md_cell(fig.caption)}")
        for ds in r.section.datasets:
            rel = _rel(Path(ds), out)
            lines.append(f"- Dataset: [{rel}]({rel})")
    lines.append("")
    return "\n".join(lines)


def _json_value(x):
    x = float(x)
    return x if x == x and abs(x) != float("inf") else str(x)


def render_checks_json(results, meta, total_seconds, screen=None) -> str:
    verdict, guide = collect_verdict(results)
    sentence, table = screen if screen is not None else first_screen()
    return json.dumps({
        "meta": meta, "wall_time_s": total_seconds,
        "first_screen": {"sentence": sentence, "table": table},
        "verdict": [{"section": name, "text": line} for name, line in verdict],
        "guide": [{"section": name, "text": line} for name, line in guide],
        "sections": [{"name": r.name, "title": r.section.title, "seconds": r.seconds, "crashed": r.crashed,
                      "error": r.error} for r in results],
        "checks": [{"section": r.name, "name": c.name, "value": _json_value(c.value),
                    "tolerance": _json_value(c.tolerance), "comparison": c.comparison, "passed": bool(c.passed),
                    "reference": c.reference} for r in results for c in r.checks],
    }, indent=1)


def _write_text_atomic(path: Path, text: str):
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".part", dir=path.parent)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(text)
        os.chmod(tmp, 0o644)  # mkstemp creates 0600; the report is meant to be shared
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        raise


# --------------------------------------------------------------------------- CLI


def _parser():
    p = argparse.ArgumentParser(prog="python -m verification.report", description=__doc__.split("\n")[0])
    p.add_argument("--out", default="out", help="output directory (default: out)")
    p.add_argument("--quick", action="store_true", help="small resolutions: the whole report in <= 60 s")
    p.add_argument("--sections", default="",
                   help=f"comma-separated subset of {','.join(SECTION_ORDER)} (default: all that exist)")
    p.add_argument("--no-progress", action="store_true", help="do not print progress lines to stderr")
    p.add_argument("--jobs", type=int, default=1,
                   help="run up to this many sections at the same time, each in its own process (default 1)")
    p.add_argument("--scheduler", default=None,
                   help="run the heavy BEM loops as tasks of the sweep engine: 'processes' (local worker "
                        "processes) or a dask.distributed address tcp://host:port (default: serial)")
    return p


def main(argv=None) -> int:
    """Build the report; return the exit status (0 all pass, 1 any failure, 2 bad usage)."""
    argv = list(sys.argv[1:] if argv is None else argv)
    args = _parser().parse_args(argv)
    if args.jobs < 1:
        print(f"error: --jobs must be an integer >= 1; got {args.jobs}", file=sys.stderr)
        return 2
    if args.scheduler is not None:  # read by dhfield.sweep.map_cases, in this process and the section processes
        from dhfield.sweep.engine import SCHEDULER_ENV, check_scheduler_address

        if args.scheduler not in ("synchronous", "processes"):
            try:
                check_scheduler_address(args.scheduler)
            except ValueError as exc:
                print(f"error: --{exc}", file=sys.stderr)
                return 2
        os.environ[SCHEDULER_ENV] = args.scheduler
    try:
        requested = [s.strip() for s in args.sections.split(",") if s.strip()] or None
        names = _available_sections(requested)
    except ValueError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    import matplotlib
    matplotlib.use("Agg")

    out = Path(args.out)
    if out.exists() and not out.is_dir():
        print(f"error: --out must be a directory; got {str(out)!r}", file=sys.stderr)
        return 2
    clean_output(out)

    def progress(line):
        if not args.no_progress:
            print(line, file=sys.stderr, flush=True)

    t0 = time.perf_counter()
    progress(f"dhfield report: {len(names)} sections ({', '.join(names) or 'none'}), "
             f"{'quick' if args.quick else 'default'} mode, output in {out}/")
    meta = collect_metadata(argv, args.quick)
    results = run_sections(out, names, args.quick, progress, jobs=args.jobs, show_progress=not args.no_progress)
    total = time.perf_counter() - t0
    screen = first_screen()
    _write_text_atomic(out / "report.html", render_html(results, meta, out, total, screen))
    _write_text_atomic(out / "summary.md", render_summary(results, meta, out, total, screen))
    _write_text_atomic(out / "checks.json", render_checks_json(results, meta, total, screen))
    n_checks = sum(len(r.checks) for r in results)
    n_fail = sum(not c.passed for r in results for c in r.checks)
    crashed = [r.name for r in results if r.crashed]
    print(f"report: {out / 'report.html'}  summary: {out / 'summary.md'}  "
          f"{n_checks - n_fail}/{n_checks} checks pass"
          + (f"; crashed sections: {', '.join(crashed)}" if crashed else "") + f"  ({total:.1f} s)",
          file=sys.stderr)
    if n_fail:
        for r in results:
            for c in r.checks:
                if not c.passed:
                    print(f"FAIL [{r.name}] {c.name}: {_fmt(c.value)} {c.comparison} {_fmt(c.tolerance)}",
                          file=sys.stderr)
    return 1 if (n_fail or crashed or not names) else 0


if __name__ == "__main__":
    sys.exit(main())
