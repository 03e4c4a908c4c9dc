"""``dhfield fit`` on the command line: replicates, uncertainty flags, warnings, data files with units."""
from __future__ import annotations

import pytest

from dhfield.cli import main


def _run(capsys, argv):
    code = main(argv)
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.parametrize("argv, where", [(["fit", "--bogus"], ""), (["fit", "--model", "hertz"], "fit: ")])
def test_usage_error_prefix_is_not_doubled(capsys, argv, where):
    # issue 17: "dhfield: error: dhfield: unrecognized arguments: ..." (main and argparse both named the program)
    code, out, err = _run(capsys, argv)
    assert code == 2 and out == "" and err.count("\n") == 1
    assert err.startswith(f"dhfield: error: {where}") and "dhfield: error: dhfield" not in err, err
