"""Persistent FFTW wisdom of the half-space operators (private: the operators load and save it).

The plans FFTW measures for a transform size are kept as "wisdom" in
``$DHFIELD_CACHE/fftw_wisdom.bin`` (default ``~/.cache/dhfield``), so that the next
process plans that size at once.  The file is plain bytes (:func:`encode_wisdom`:
magic, pyfftw version, the three wisdom strings, SHA-256), never a pickle; a file
that is corrupt, foreign, not a regular file, owned by another user or writable by
others is ignored with a :class:`WisdomCacheWarning` and rewritten.  Writes are
atomic; a cache that cannot be read or written is harmless (an optimisation only).
"""
from __future__ import annotations

import contextlib
import hashlib
import os
import stat
import tempfile
import threading
import warnings
from pathlib import Path

import pyfftw

__all__ = ["cache_dir", "encode_wisdom", "decode_wisdom", "load_wisdom", "save_wisdom", "WisdomCacheWarning",
           "WISDOM_MAGIC"]

_WISDOM_LOCK = threading.Lock()
_WISDOM_STATE = {"loaded": False, "saved": None}

#: First bytes of a wisdom cache file; the digit is the format version.
WISDOM_MAGIC = b"DHFIELD-FFTW-WISDOM-1\n"
#: Largest wisdom cache file read [bytes] (real ones are a few kB).
_WISDOM_MAX_BYTES = 4 * 2**20
_WISDOM_PARTS = 3  # pyfftw: double, single, long-double wisdom


class WisdomCacheWarning(UserWarning):
    """The FFTW wisdom cache file was ignored (corrupt, foreign or unsafe); it is rewritten."""


def cache_dir() -> Path:
    """Directory for persistent caches: ``$DHFIELD_CACHE`` or ``~/.cache/dhfield``."""
    env = os.environ.get("DHFIELD_CACHE")
    return Path(env) if env else Path.home() / ".cache" / "dhfield"


def _wisdom_path() -> Path:
    return cache_dir() / "fftw_wisdom.bin"


def _wisdom_header() -> bytes:
    return WISDOM_MAGIC + f"pyfftw {pyfftw.__version__}\n".encode("ascii")


def encode_wisdom(wisdom) -> bytes:
    """The cache-file bytes of ``pyfftw.export_wisdom()``: plain bytes, never a pickle.

    Layout: :data:`WISDOM_MAGIC`, a ``pyfftw <version>`` line, then for each of
    the three wisdom strings its length (8 bytes, little-endian) and its bytes,
    then the SHA-256 of everything before.
    """
    parts = tuple(wisdom)
    if len(parts) != _WISDOM_PARTS or not all(isinstance(w, bytes) for w in parts):
        raise ValueError("wisdom must be the 3-tuple of bytes of pyfftw.export_wisdom()")
    body = _wisdom_header() + b"".join(len(w).to_bytes(8, "little") + w for w in parts)
    return body + hashlib.sha256(body).digest()


def decode_wisdom(data: bytes) -> tuple:
    """The wisdom tuple stored by :func:`encode_wisdom`; ValueError saying why if ``data`` is not one."""
    header = _wisdom_header()
    if not data.startswith(WISDOM_MAGIC):
        raise ValueError("not a dhfield wisdom file (bad magic)")
    if not data.startswith(header):
        raise ValueError("written by another pyfftw version")
    if len(data) < len(header) + 32 or hashlib.sha256(data[:-32]).digest() != data[-32:]:
        raise ValueError("checksum mismatch (corrupt or truncated)")
    body, pos, parts = data[:-32], len(header), []
    for _ in range(_WISDOM_PARTS):
        if pos + 8 > len(body):
            raise ValueError("truncated")
        n = int.from_bytes(body[pos:pos + 8], "little")
        pos += 8
        if pos + n > len(body):
            raise ValueError("truncated")
        part = bytes(body[pos:pos + n])
        pos += n
        if part and not part.startswith(b"(fftw-3"):
            raise ValueError("not FFTW wisdom text")
        parts.append(part)
    if pos != len(body):
        raise ValueError("trailing bytes")
    return tuple(parts)


def _read_wisdom_file(path: Path):
    """The decoded wisdom of ``path``, None if absent; ValueError saying why it is unusable."""
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_NONBLOCK", 0))
    except FileNotFoundError:
        return None
    except OSError as exc:
        raise ValueError(f"cannot be opened ({exc.strerror})") from None
    with os.fdopen(fd, "rb") as fh:
        st = os.fstat(fh.fileno())
        if not stat.S_ISREG(st.st_mode):
            raise ValueError("not a regular file")
        if hasattr(os, "getuid") and st.st_uid != os.getuid():
            raise ValueError("owned by another user")
        if st.st_mode & 0o022:
            raise ValueError("writable by other users")
        data = fh.read(_WISDOM_MAX_BYTES + 1)
    if len(data) > _WISDOM_MAX_BYTES:
        raise ValueError(f"larger than {_WISDOM_MAX_BYTES} bytes")
    return decode_wisdom(data)


def load_wisdom() -> None:
    """Import the cached FFTW wisdom once per process (a warning, never an error, when it is unusable)."""
    with _WISDOM_LOCK:
        if _WISDOM_STATE["loaded"]:
            return
        _WISDOM_STATE["loaded"] = True
        path = _wisdom_path()
        try:
            wisdom = _read_wisdom_file(path)
        except ValueError as exc:
            warnings.warn(f"ignoring the FFTW wisdom cache {str(path)!r}: {exc}; it will be rewritten",
                          WisdomCacheWarning, stacklevel=3)
            return
        except Exception:  # noqa: BLE001 - an unreadable cache is harmless
            return
        if wisdom is not None:
            pyfftw.import_wisdom(wisdom)
            _WISDOM_STATE["saved"] = wisdom


def save_wisdom() -> None:
    """Write the FFTW wisdom gathered so far to ``$DHFIELD_CACHE/fftw_wisdom.bin`` (atomically).

    Operators (:class:`dhfield.bem.operator.HalfSpaceOperator`) save it when they are built; call this after planning outside them
    (e.g. a benchmark's own pyfftw plans).  Nothing is written when the wisdom is
    unchanged, and a failure to write is ignored (the cache is an optimisation).
    """
    with _WISDOM_LOCK:
        try:
            wisdom = pyfftw.export_wisdom()
            if wisdom == _WISDOM_STATE["saved"]:
                return
            path = _wisdom_path()
            path.parent.mkdir(mode=0o700, parents=True, exist_ok=True)
            fd, tmp = tempfile.mkstemp(prefix=".wisdom.", suffix=".part", dir=path.parent)  # mode 0600
            try:
                with os.fdopen(fd, "wb") as fh:
                    fh.write(encode_wisdom(wisdom))
                os.replace(tmp, path)
            except BaseException:
                with contextlib.suppress(OSError):
                    os.unlink(tmp)
                raise
            _WISDOM_STATE["saved"] = wisdom
        except Exception:  # noqa: BLE001 - an unwritable cache is harmless
            pass
