"""dhfield.core.schema: one metadata table, record key lists and the canonical dimension order."""
import pytest

from dhfield.core import schema

#: Units a CF/UDUNITS parser accepts that dhfield uses; a new unit string must be added here knowingly.
KNOWN_UNITS = {"1", "m", "N", "Pa", "J m-2", "rad", "degree",
               "N m-1"}   # machine stiffness (issue 17); cf_units.Unit("N m-1") converts to kg s-2 with factor 1


def test_every_record_key_has_metadata():
    for keys in (schema.PULL_OFF_KEYS, schema.PULL_OFF_SI_KEYS, schema.LOAD_CURVE_HEADER_KEYS,
                 schema.LOAD_CURVE_KEYS, schema.LOAD_CURVE_SI_KEYS, schema.BEM_ADHESIVE_KEYS):
        assert len(set(keys)) == len(keys)
        for k in keys:
            assert k in schema.VARIABLES, k


def test_units_are_known_strings():
    for name, var in schema.VARIABLES.items():
        assert var.units in KNOWN_UNITS, (name, var.units)
        assert var.long_name


def test_si_outputs_units():
    assert schema.units("force") == "N"
    for k in ("semi_major", "semi_minor", "adhesive_semi_major", "adhesive_semi_minor", "approach"):
        assert schema.units(k) == "m"
    assert schema.units("work_of_adhesion") == "J m-2"
    assert schema.units("max_adhesive_stress") == "Pa"


def test_nondimensional_attrs_name_the_scale():
    a = schema.attrs("semi_major", nondimensional=True)
    assert a["units"] == "1" and "c_r" in a["long_name"]
    assert schema.attrs("beta0", nondimensional=True) == schema.attrs("beta0")


def test_si_record_contains_the_nondimensional_one():
    si = schema.PULL_OFF_SI_KEYS
    assert [k for k in si if k in schema.PULL_OFF_KEYS] == list(schema.PULL_OFF_KEYS)


def test_dim_order():
    assert len(set(schema.DIM_ORDER)) == len(schema.DIM_ORDER)
    assert schema.order_dims(("mu", "beta0")) == schema.GRID_DIMS == ("beta0", "mu")
    assert schema.order_dims(("theta", "mu", "beta0", "extra")) == ("beta0", "mu", "theta", "extra")
    for d in schema.DIM_ORDER:
        assert d in schema.VARIABLES or d in ("law_theta", "sample"), d


def test_unknown_name_is_a_value_error():
    with pytest.raises(ValueError, match="name"):
        schema.attrs("no_such_variable")
