"""The FFTW wisdom cache is plain checksummed bytes, never a pickle; thread counts are bounded (issue 9, items 5, 9)."""
from __future__ import annotations

import os
import pickle
import subprocess
import sys
import textwrap
import warnings

import pyfftw
import pytest

from dhfield import bem
from dhfield.bem import _wisdom as op

#: Seconds a child Python may take to import dhfield and plan a 16 x 16 operator on a loaded 2-core machine.
CHILD_TIMEOUT = 120

_BUILD_SCRIPT = textwrap.dedent("""
    import numpy as np
    from dhfield import bem
    u = bem.HalfSpaceOperator(bem.Grid(16, 16, 0.1, 0.1), planner_effort="FFTW_ESTIMATE")(np.ones((16, 16)))
    print(repr(float(u[0, 0])))
""")


class _Bomb:
    """Unpickling this runs code: it writes the marker file."""

    def __init__(self, marker):
        self.marker = str(marker)

    def __reduce__(self):
        return (exec, (f"open({self.marker!r}, 'w').write('pwned')",))


def _build_with_cache(cache):
    env = dict(os.environ, DHFIELD_CACHE=str(cache))
    env.pop("DHFIELD_THREADS", None)
    res = subprocess.run([sys.executable, "-c", _BUILD_SCRIPT], env=env, capture_output=True, text=True,
                         timeout=CHILD_TIMEOUT)
    assert res.returncode == 0, res.stderr
    return res


def test_pickle_bomb_in_cache_is_never_executed(tmp_path):
    """Issue 9 item 5: a crafted pickle in $DHFIELD_CACHE ran arbitrary code (pickle.load)."""
    cache = tmp_path / "cache"
    cache.mkdir()
    marker = tmp_path / "pwned"
    bomb = pickle.dumps(_Bomb(marker))
    # under the name the old code read and under the current name
    (cache / f"fftw_wisdom_pyfftw{pyfftw.__version__}.pickle").write_bytes(bomb)
    (cache / "fftw_wisdom.bin").write_bytes(bomb)
    res = _build_with_cache(cache)
    assert not marker.exists()
    assert "ignoring the FFTW wisdom cache" in res.stderr  # at most a warning
    # ... and the cache was rewritten in the checksummed format
    wisdom = op.decode_wisdom((cache / "fftw_wisdom.bin").read_bytes())
    assert len(wisdom) == 3 and wisdom[0].startswith(b"(fftw-3")


def test_wisdom_round_trip_and_corruption_detected():
    wisdom = pyfftw.export_wisdom()
    data = op.encode_wisdom(wisdom)
    assert data.startswith(op.WISDOM_MAGIC)
    assert op.decode_wisdom(data) == tuple(wisdom)
    flipped = bytearray(data)
    flipped[len(data) // 2] ^= 0x01
    bad = {
        "bad magic": pickle.dumps(wisdom),
        "checksum": bytes(flipped),
        "truncated": data[:-1],
        "pyfftw version": data.replace(f"pyfftw {pyfftw.__version__}".encode(), b"pyfftw 0.0.0"),
        "empty": b"",
    }
    for what, blob in bad.items():
        with pytest.raises(ValueError):
            op.decode_wisdom(blob)
        assert what  # each case is named for the reader


def _load_from(monkeypatch, cache):
    monkeypatch.setenv("DHFIELD_CACHE", str(cache))
    monkeypatch.setattr(op, "_WISDOM_STATE", {"loaded": False, "saved": None})
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        op.load_wisdom()
    return [w for w in caught if issubclass(w.category, op.WisdomCacheWarning)]


def test_unsafe_or_foreign_cache_files_are_ignored_with_a_warning(tmp_path, monkeypatch):
    cache = tmp_path / "c"
    cache.mkdir()
    path = cache / "fftw_wisdom.bin"
    path.write_bytes(op.encode_wisdom(pyfftw.export_wisdom()))
    os.chmod(path, 0o600)
    assert _load_from(monkeypatch, cache) == []  # a good private file loads silently
    os.chmod(path, 0o666)
    warned = _load_from(monkeypatch, cache)
    assert len(warned) == 1 and "writable by other users" in str(warned[0].message)
    os.chmod(path, 0o600)
    path.write_bytes(b"garbage")
    assert len(_load_from(monkeypatch, cache)) == 1
    path.unlink()
    os.mkfifo(path)  # a FIFO must not block the reader
    warned = _load_from(monkeypatch, cache)
    assert len(warned) == 1 and "regular file" in str(warned[0].message)
    path.unlink()
    assert _load_from(monkeypatch, cache) == []  # no file: nothing to say


def test_thread_counts_are_bounded(monkeypatch):
    """Issue 9 item 9: --threads 1000000 was accepted, DHFIELD_THREADS=abc silently ignored."""
    grid = bem.Grid(16, 16, 0.1, 0.1)
    top = bem.max_threads()
    assert top == bem.THREADS_PER_CPU * (os.cpu_count() or 1)
    for bad in (0, -1, top + 1, 1_000_000, 2.0, "4", True):
        with pytest.raises(ValueError, match="threads"):
            bem.HalfSpaceOperator(grid, threads=bad, planner_effort="FFTW_ESTIMATE")
    assert bem.check_threads(top) == top
    for bad in ("abc", "0", "1000000", "1.5"):
        monkeypatch.setenv("DHFIELD_THREADS", bad)
        with pytest.raises(ValueError, match="DHFIELD_THREADS"):
            bem.default_threads()
        with pytest.raises(ValueError, match="DHFIELD_THREADS"):
            bem.get_operator(grid)
    monkeypatch.setenv("DHFIELD_THREADS", " 2 ")
    assert bem.default_threads() == min(2, top)
    monkeypatch.delenv("DHFIELD_THREADS")
    assert bem.default_threads() == 1
