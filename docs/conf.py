"""Sphinx configuration of the dhfield documentation (``make docs``).

Everything that can drift from the code is generated at build time by
``_ext/dhfield_docs.py``: the API reference (from every public module's
``__all__``), the netCDF variables table (from :mod:`dhfield.core.schema`), the
verdict's numbers (from ``data/``) and the changelog page (from CHANGELOG.md).
The CLI reference comes from :func:`dhfield.cli.build_parser` via sphinx-argparse.
"""
import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = Path(os.environ.get("DHFIELD_DOCS_ROOT", HERE.parent)).resolve()   # a copy of docs/ sets it
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(HERE / "_ext"))

import dhfield  # noqa: E402

project = "dhfield"
author = "the dhfield developers"
copyright = "2026, the dhfield developers"
release = version = dhfield.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.mathjax",
    "sphinx.ext.intersphinx",
    "numpydoc",
    "sphinx_gallery.gen_gallery",
    "sphinxarg.ext",
    "dhfield_docs",
]


exclude_patterns = ["_build", "examples", "Thumbs.db", ".DS_Store", "auto_examples/*.ipynb", "auto_examples/*.py",
                    "auto_examples/*.zip", "auto_examples/*.md5", "auto_examples/*.json",
                    "sg_execution_times.rst"]
root_doc = "index"
# smart quotes and ellipses, but "--" stays two hyphens: option names such as --a-min appear in
# text generated from the CLI's help strings
smartquotes_action = "qe"
default_role = "code"
nitpicky = False
# numpydoc renames the citations of each docstring's References section; one listed there but not
# cited in the text would warn ("not referenced").  Listing sources without citing them inline is
# accepted here.
suppress_warnings = ["ref.citation"]

# -- autodoc / numpydoc -----------------------------------------
autodoc_default_options = {"member-order": "bysource"}
autodoc_typehints = "none"
autodoc_preserve_defaults = True
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
numpydoc_attributes_as_param_list = True
numpydoc_validation_checks = set()   # validation runs in tests/test_docs.py, not in the build

# -- math ---------------------------------------------------------------------
# MathJax 3 from its CDN by default; DHFIELD_MATHJAX names a local copy (e.g. the npm package's
# es5/tex-svg.js) for browsing offline, and is copied into _static.
_local_mathjax = os.environ.get("DHFIELD_MATHJAX")
if _local_mathjax:
    mathjax_path = Path(_local_mathjax).name

intersphinx_mapping = {}

# -- gallery ------------------------------------------------------------------
sphinx_gallery_conf = {
    "examples_dirs": "examples",
    "gallery_dirs": "auto_examples",
    "filename_pattern": r"/plot_",
    "within_subsection_order": "FileNameSortKey",
    "download_all_examples": False,
    "remove_config_comments": True,
    "show_memory": False,
    "matplotlib_animations": False,
    "image_scrapers": ("matplotlib",),
    "reset_modules": ("matplotlib",),
    "abort_on_example_error": True,
    "min_reported_time": 0,
    "write_computation_times": True,
}

# -- HTML ---------------------------------------------------------------------
html_theme = "pydata_sphinx_theme"
html_title = f"dhfield {release}"
html_static_path = ["_static"] + ([_local_mathjax] if _local_mathjax else [])
html_css_files = ["dhfield.css"]
html_show_sourcelink = False
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "header_links_before_dropdown": 7,
    # the pages of wide generated tables give the right-hand column to the table
    "secondary_sidebar_items": {"**": ["page-toc"], "theory/bem": [], "netcdf": []},
    "footer_start": ["copyright"],
    "footer_end": ["sphinx-version"],
}
html_sidebars = {"index": [], "citing": [], "changelog": [], "netcdf": [], "cli": []}   # no section navigation there
html_context = {"default_mode": "light"}
