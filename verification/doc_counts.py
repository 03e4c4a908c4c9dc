"""Counts of the documentation site: what is documented, validated, run and linked.

Prints

* the public names (every name in the ``__all__`` of a public module of dhfield) and how many
  have a reference page (their canonical object in the built site's ``objects.inv``; target: all);
* numpydoc validation errors of every public function, class and public method, per module
  (checks: all of numpydoc's except :data:`SKIPPED_CHECKS`; target 0);
* the gallery's examples and their run times (``docs/sg_execution_times.rst`` of the last
  ``make docs``);
* broken internal links of the built HTML (target 0);
* with ``--screenshots DIR``: headless-Chromium screenshots of the landing page, one API page,
  one gallery example and one theory page, and whether each page's images loaded.

Usage (after ``make docs``)::

    .venv/bin/python -m verification.doc_counts [--html docs/_build/html] [--screenshots out/doc_shots]

The helpers are shared with ``tests/test_docs.py``.
"""
from __future__ import annotations

import argparse
import html
import importlib
import inspect
import re
import shutil
import subprocess
import sys
import tempfile
import urllib.parse
import warnings
from collections import Counter, defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
HTML = DOCS / "_build" / "html"
CHROMIUM = Path("/usr/bin/chromium")

#: numpydoc checks not required: "See Also" (SA01), "Examples" (EX01) and an extended summary
#: (ES01) are welcome but optional sections in dhfield's style (docs/notes: numpydoc, units in
#: brackets, equations in Notes).
SKIPPED_CHECKS = frozenset({"SA01", "EX01", "ES01"})

#: Pages of the screenshots: landing page, an API page, a gallery example, a theory page.
SCREENSHOT_PAGES = ("index.html", "api/generated/dhfield.models.dh_elliptic.pull_off.html",
                    "auto_examples/plot_pull_off_vs_angle.html", "theory/model.html")


def _ext():
    if str(DOCS / "_ext") not in sys.path:
        sys.path.insert(0, str(DOCS / "_ext"))
    import dhfield_docs

    return dhfield_docs


def public_api() -> dict[str, dict[str, str]]:
    """``{module: {name: canonical "module.name"}}`` for every public name (docs/_ext/dhfield_docs.py)."""
    return _ext().public_api()


# --------------------------------------------------------------------------- reference pages
def inventory_names(html_dir: Path) -> set[str]:
    """Python object names in the built site's ``objects.inv``."""
    from sphinx.util.inventory import InventoryFile

    with open(html_dir / "objects.inv", "rb") as f:
        inv = InventoryFile.load(f, "", lambda base, uri: uri)
    names = set()
    for role, entries in inv.items():
        if role.startswith("py:"):
            names.update(entries)
    return names


def names_without_page(html_dir: Path, api=None) -> list[str]:
    """Public ``module.name`` whose canonical object has no entry in ``objects.inv``."""
    api = api or public_api()
    inv = inventory_names(html_dir)
    return sorted(f"{m}.{n}" for m, names in api.items() for n, home in names.items() if home not in inv)


# --------------------------------------------------------------------------- numpydoc validation
def validation_targets(api=None) -> list[tuple[str, str]]:
    """(module, dotted name) of every public function, class and public method, each once."""
    api = api or public_api()
    homes = sorted({h for names in api.values() for h in names.values()})
    out = []
    for h in homes:
        mod, name = h.rsplit(".", 1)
        obj = getattr(importlib.import_module(mod), name)
        if not (inspect.isfunction(obj) or inspect.isclass(obj)):
            continue
        out.append((mod, h))
        if inspect.isclass(obj):
            for k, v in vars(obj).items():
                if not k.startswith("_") and (inspect.isfunction(v) or isinstance(v, (property, classmethod,
                                                                                          staticmethod))):
                    out.append((mod, f"{h}.{k}"))
    return out


def validation_errors(modules=None, api=None) -> dict[str, list[tuple[str, str, str]]]:
    """numpydoc errors per module: ``{module: [(name, code, message), ...]}`` (modules: all if None)."""
    from numpydoc.validate import validate

    errors: dict[str, list] = defaultdict(list)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")     # numpydoc's "Unknown section" UserWarnings: counted below anyway
        for mod, target in validation_targets(api):
            if modules is not None and mod not in modules:
                continue
            errors[mod]  # every module appears, with 0 errors if so
            for code, msg in validate(target)["errors"]:
                if code not in SKIPPED_CHECKS:
                    errors[mod].append((target, code, msg))
    return dict(errors)


# --------------------------------------------------------------------------- internal links
_ATTR = re.compile(r"""<(a|link|img|script|iframe|source)\b[^>]*?\s(href|src)=(["'])(.*?)\3""", re.I | re.S)
_ID = re.compile(r"""<[a-z][^>]*?\s(?:id|name)=(["'])(.*?)\1""", re.I | re.S)


class _Page:
    """The links (``href``/``src``) and anchors (``id``, ``name``) of one HTML page."""

    def __init__(self, text: str):
        self.links = [(m.group(1).lower(), m.group(2).lower(), html.unescape(m.group(4)))
                      for m in _ATTR.finditer(text)]
        self.ids = {html.unescape(m.group(2)) for m in _ID.finditer(text)}


def _parse(path: Path, cache: dict):
    if path not in cache:
        cache[path] = _Page(path.read_text(encoding="utf-8", errors="replace"))
    return cache[path]


def broken_internal_links(html_dir: Path) -> list[str]:
    """Every relative ``href``/``src`` of the built HTML whose file, or ``#fragment`` in it, is missing."""
    html_dir = Path(html_dir)
    cache: dict = {}
    broken = []
    for page in sorted(html_dir.rglob("*.html")):
        if page.relative_to(html_dir).parts[0] in ("_static", "_sources", "_images"):
            continue   # theme templates and copies, not pages
        for tag, key, link in _parse(page, cache).links:
            url = urllib.parse.urlsplit(link)
            if url.scheme or url.netloc or link.startswith(("mailto:", "javascript:", "data:")):
                continue
            target = page if not url.path else (page.parent / urllib.parse.unquote(url.path)).resolve()
            if url.path.endswith("/") or target.is_dir():
                target = target / "index.html"
            rel = page.relative_to(html_dir)
            if not target.exists():
                broken.append(f"{rel}: {link} (no file)")
                continue
            frag = urllib.parse.unquote(url.fragment)
            if frag and target.suffix == ".html" and frag not in _parse(target, cache).ids:
                broken.append(f"{rel}: {link} (no #{frag})")
    return broken


# --------------------------------------------------------------------------- gallery
def gallery_times(docs: Path = DOCS) -> list[tuple[str, float]]:
    """(example, seconds) from ``sg_execution_times.rst`` of the last gallery run, slowest first."""
    path = docs / "sg_execution_times.rst"
    if not path.exists():
        return []
    text = path.read_text()
    rows = re.findall(r"``examples/(\S+?\.py)``\)\s*\n\s*- (\d+):(\d+\.\d+)", text)
    return sorted(((name, 60 * int(m) + float(s)) for name, m, s in rows), key=lambda r: -r[1])


def gallery_examples(docs: Path = DOCS) -> list[str]:
    return sorted(p.name for p in (docs / "examples").glob("plot_*.py"))


# --------------------------------------------------------------------------- headless Chromium
def _chromium(*args, timeout=90):
    profile = tempfile.mkdtemp(prefix="dhfield-chromium-")
    cmd = [str(CHROMIUM), "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
           "--disable-background-networking", "--disable-component-update", "--disable-sync",
           f"--user-data-dir={profile}", *args]
    try:
        return subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    finally:
        shutil.rmtree(profile, ignore_errors=True)


_PROBE = """<!doctype html><html><body>
<iframe id="f" src="{src}" width="1280" height="1600"></iframe><pre id="out">PENDING</pre>
<script>
document.getElementById('f').onload = function () {{
  var d = this.contentDocument, imgs = d ? d.images : [];
  for (var i = 0; i < imgs.length; i++) {{ imgs[i].loading = 'eager'; }}
  setTimeout(function () {{
    var res = ['IMAGES ' + imgs.length];
    for (var i = 0; i < imgs.length; i++) {{
      res.push((imgs[i].complete && imgs[i].naturalWidth > 0 ? 'OK ' : 'BROKEN ') + imgs[i].getAttribute('src'));
    }}
    document.getElementById('out').textContent = d ? res.join('\\n') : 'NO ACCESS';
  }}, 1500);
}};
</script></body></html>"""


def images_in_chromium(page: Path) -> tuple[int, list[str]]:
    """Open ``page`` in headless Chromium; return (number of images, those that did not load)."""
    page = Path(page).resolve()
    with tempfile.TemporaryDirectory() as tmp:
        probe = Path(tmp) / "probe.html"
        probe.write_text(_PROBE.format(src=page.as_uri()))
        res = _chromium("--allow-file-access-from-files", "--virtual-time-budget=10000", "--dump-dom",
                        probe.as_uri())
    m = re.search(r'<pre id="out">(.*?)</pre>', res.stdout, re.S)
    if not m or not m.group(1).startswith("IMAGES"):
        raise RuntimeError(f"Chromium did not report on {page}: {(m.group(1) if m else res.stderr)[-300:]}")
    lines = html.unescape(m.group(1)).splitlines()
    return int(lines[0].split()[1]), [ln[7:] for ln in lines[1:] if ln.startswith("BROKEN")]


def screenshot(page: Path, out: Path, size=(1280, 1600)) -> Path:
    """A PNG of ``page`` in headless Chromium (MathJax given time to typeset)."""
    _chromium("--virtual-time-budget=8000", f"--screenshot={out}", f"--window-size={size[0]},{size[1]}",
              Path(page).resolve().as_uri())
    if not Path(out).exists():
        raise RuntimeError(f"no screenshot of {page}")
    return Path(out)


# --------------------------------------------------------------------------- report
def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--html", type=Path, default=HTML, help="built site (default docs/_build/html)")
    ap.add_argument("--screenshots", type=Path, help="directory for the Chromium screenshots")
    args = ap.parse_args(argv)
    api = public_api()
    n_names = sum(len(v) for v in api.values())
    n_objects = len({h for v in api.values() for h in v.values()})
    print(f"public modules: {len(api)}; public names: {n_names} ({n_objects} distinct objects)")
    if (args.html / "objects.inv").exists():
        missing = names_without_page(args.html, api)
        print(f"names with a reference page: {n_names - len(missing)} / {n_names}")
        for name in missing:
            print(f"  no page: {name}")
    else:
        print(f"names with a reference page: no site at {args.html} (run make docs)")

    errors = validation_errors(api=api)
    total = sum(len(v) for v in errors.values())
    checked = len(validation_targets(api))
    print(f"numpydoc validation errors: {total} over {checked} functions, classes and methods "
          f"(checks: all but {', '.join(sorted(SKIPPED_CHECKS))})")
    for mod in sorted(errors, key=lambda m: (-len(errors[m]), m)):
        codes = Counter(code for _, code, _ in errors[mod])
        print(f"  {mod:28s} {len(errors[mod]):4d}  " + " ".join(f"{c}:{k}" for c, k in sorted(codes.items())))

    examples = gallery_examples()
    times = dict(gallery_times())
    print(f"gallery examples: {len(examples)}")
    for name in examples:
        t = times.get(name)
        print(f"  {name:32s} " + (f"{t:6.1f} s" if t is not None else "   not run (make docs runs it)"))

    if args.html.exists():
        broken = broken_internal_links(args.html)
        pages = len(list(args.html.rglob("*.html")))
        print(f"broken internal links: {len(broken)} (over {pages} pages)")
        for b in broken[:50]:
            print(f"  {b}")
    if args.screenshots:
        if not CHROMIUM.exists():
            print(f"screenshots: skipped ({CHROMIUM} not found)")
        else:
            args.screenshots.mkdir(parents=True, exist_ok=True)
            for rel in SCREENSHOT_PAGES:
                page = args.html / rel
                out = screenshot(page, args.screenshots / (rel.replace("/", "_").replace(".html", ".png")))
                n_img, bad = images_in_chromium(page)
                print(f"screenshot {out}: {n_img} images, {len(bad)} not loaded" + (f" {bad}" if bad else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
