"""dhfield.validity: the validated ranges and the warnings of the pull-off records (issue 16 split)."""
import numpy as np
import pytest

from dhfield import compare, validity


def test_validity_message_inside_and_outside():
    """Ranges from VALIDITY_RANGES (provenance in dhfield.validity): inside empty, outside says where."""
    assert validity.validity_message("dh-elliptic", 1.0, 0.9) == ""
    out = validity.validity_message("dh-elliptic", [1.0, 10.0], [0.9, 0.9])
    assert out[0] == "" and "mu in [0.5, 5]" in out[1]
    with pytest.raises(ValueError, match="model"):
        validity.validity_message("hertz", 1.0, 1.0)
    assert set(validity.VALIDITY_RANGES) == set(compare.MODEL_NAMES)


def test_join_warnings_skips_empty_and_broadcasts():
    assert validity.join_warnings("", "b") == "b" and validity.join_warnings("a", "b") == "a; b"
    out = validity.join_warnings(np.array(["", "x"], dtype=object), "y")
    assert list(out) == ["y", "x; y"]


def test_departure_warning_threshold():
    """2 % threshold (issue 10): -1 % is silent, -3 % warns and names the better model."""
    assert validity.departure_warning(-0.99, 1.0, 0.9, "load", two_axis_w_star=-1.0) == ""
    w = validity.departure_warning(-0.97, 1.0, 0.9, "load", two_axis_w_star=-1.0)
    assert "-3.0 %" in w and "dh-elliptic-two-axis" in w
