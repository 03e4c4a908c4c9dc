"""Tests of dhfield.core._docstrings: the shared numpydoc parameter text filled into docstrings."""
from __future__ import annotations

import importlib
import inspect
import pkgutil

import pytest

import dhfield.core
import dhfield.models
from dhfield.core import _docstrings
from dhfield.core._docstrings import DOCDICT, fill_doc, fill_docstring


def _public_functions_and_classes():
    """(qualified name, object) of every public function, class and method of dhfield.core and dhfield.models."""
    out = []
    for pkg in (dhfield.core, dhfield.models):
        for info in pkgutil.iter_modules(pkg.__path__, pkg.__name__ + "."):
            if info.name.rsplit(".", 1)[1].startswith("_"):
                continue
            mod = importlib.import_module(info.name)
            for name, obj in vars(mod).items():
                if name.startswith("_") or getattr(obj, "__module__", None) != mod.__name__:
                    continue
                if inspect.isfunction(obj):
                    out.append((f"{mod.__name__}.{name}", obj))
                elif inspect.isclass(obj):
                    out.append((f"{mod.__name__}.{name}", obj))
                    out.extend((f"{mod.__name__}.{name}.{k}", v) for k, v in vars(obj).items()
                               if not k.startswith("_") and inspect.isfunction(v))
    return out


def test_fill_indents_every_line_of_the_entry_as_the_placeholder():
    entries = {"pair": "a : float\n    First [m].\n\n    Still the first.\nb : int\n    Second [-]."}
    doc = "Summary.\n\n        Parameters\n        ----------\n        %(pair)s\n\n        Returns\n"
    assert fill_docstring(doc, entries) == (
        "Summary.\n\n        Parameters\n        ----------\n"
        "        a : float\n            First [m].\n\n            Still the first.\n"
        "        b : int\n            Second [-].\n\n        Returns\n")


def test_fill_keeps_the_other_lines_as_they_are():
    plain = "Compute x [%].\n\n    Tabs\tand 100 % stay; '%(x)d' is not a placeholder.\n"
    assert fill_docstring(plain, {}) == plain


def test_an_inline_placeholder_raises():
    with pytest.raises(ValueError, match="alone on its line"):
        fill_docstring("Compute x.\n\n    As in %(x)s.\n", {"x": "x : int\n    X [-]."})


def test_fill_doc_decorates_a_function_in_place():
    def f(control="load"):
        """Do it.

        Parameters
        ----------
        %(control)s
        """

    g = fill_doc(f)
    assert g is f
    assert "        control : {'load', 'displacement'}\n            Loading mode of the pull-off.\n" in f.__doc__
    assert "%(" not in f.__doc__


def test_unknown_placeholder_raises_naming_the_function_and_the_placeholder():
    def pull_off_somewhere():
        """Do it.

        Parameters
        ----------
        %(no_such_entry)s
        """

    with pytest.raises(KeyError, match=r"pull_off_somewhere.*%\(no_such_entry\)s"):
        fill_doc(pull_off_somewhere)


def test_a_stripped_docstring_is_left_alone():
    def f():
        pass

    assert fill_doc(f).__doc__ is None


def test_every_entry_is_a_numpydoc_item_with_units_in_brackets():
    """Each entry starts with a ``name : type`` line (or a Returns type), unindented, and every
    described quantity carries its unit in brackets."""
    for name, text in DOCDICT.items():
        lines = text.split("\n")
        assert lines[0] and not lines[0].startswith(" "), name
        assert all(line.startswith("    ") or not line.startswith(" ") for line in lines), name
        items = [i for i, line in enumerate(lines) if line and not line.startswith(" ")]
        for i in items:       # every item has an indented description
            assert i + 1 < len(lines) and lines[i + 1].startswith("    "), (name, lines[i])
        if name not in {"control", "material_units_checked", "pull_off_nondimensional_returns"}:
            assert "[" in text and "]" in text, name


def test_no_placeholder_is_left_in_a_public_docstring_of_core_and_models():
    objs = _public_functions_and_classes()
    assert len(objs) > 100
    left = [q for q, obj in objs if "%(" in (obj.__doc__ or "")]
    assert left == []


def test_the_shared_text_reaches_the_runtime_docstring():
    """A filled docstring reads the entry (what numpydoc validation and sphinx autodoc read)."""
    from dhfield.models import dh_elliptic_fields, jkr

    assert DOCDICT["control"] in inspect.cleandoc(jkr.pull_off_force.__doc__)
    assert DOCDICT["dh_parameters"] in inspect.cleandoc(dh_elliptic_fields.load.__doc__)
    assert inspect.signature(jkr.pull_off_force).parameters.keys() == {
        "effective_radius", "reduced_modulus", "work_of_adhesion", "control"}


def test_the_facility_imports_nothing_of_dhfield():
    src = inspect.getsource(_docstrings)
    assert "import dhfield" not in src and "from ." not in src and "from dhfield" not in src
