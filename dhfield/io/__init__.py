"""Input/output at the edge of the library: netCDF (via xarray) and CSV.

Everything here is thin: the numpy core never imports this package.  All writes
are atomic (temporary file in the target directory, then ``os.replace``), so a
failed or interrupted write never leaves a partial file and never clobbers an
existing one.
"""
from __future__ import annotations

import contextlib
import datetime as _dt
import os
import tempfile
from pathlib import Path

from .. import PAPER_DOI, __version__

__all__ = ["atomic_path", "provenance_attrs", "write_netcdf", "read_netcdf", "check_writable"]

REFERENCES = (
    "Zini N.H.M., de Rooij M.B., Bazr Afshan Fadafan M., Ismail N., Schipper D.J. (2018) "
    "Extending the double-Hertz model to allow modeling of an adhesive elliptical contact. "
    f"Tribology Letters 66:30. doi:{PAPER_DOI}"
)


def check_writable(path, name: str = "out") -> Path:
    """Return ``path`` as a Path; raise ValueError naming ``name`` if it cannot be written.

    Valid: a file path (not a directory) whose directory exists and is writable.
    """
    p = Path(path)
    parent = p.parent if str(p.parent) else Path(".")
    valid = "a file path in an existing, writable directory"
    name = f"{name} (output path)"
    if p.exists() and p.is_dir():
        raise ValueError(f"{name} must be {valid}; got the directory {str(p)!r}")
    if not parent.is_dir():
        raise ValueError(f"{name} must be {valid}; directory {str(parent)!r} does not exist")
    if not os.access(parent, os.W_OK):
        raise ValueError(f"{name} must be {valid}; directory {str(parent)!r} is not writable")
    return p


@contextlib.contextmanager
def atomic_path(path):
    """Yield a temporary path next to ``path``; move it into place only on success."""
    p = check_writable(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{p.name}.", suffix=".part", dir=p.parent if str(p.parent) else ".")
    os.close(fd)
    umask = os.umask(0)
    os.umask(umask)
    try:
        yield Path(tmp)
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp creates 0600; give the usual permissions
        os.replace(tmp, p)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        raise


def provenance_attrs(title: str, **parameters) -> dict:
    """CF-style global attributes plus every input parameter as an attribute."""
    now = _dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")
    attrs = {
        "Conventions": "CF-1.10",
        "title": title,
        "institution": "dhfield",
        "source": f"dhfield {__version__}",
        "references": REFERENCES,
        "history": f"{now} created by dhfield {__version__}",
    }
    for key, value in parameters.items():
        if value is None:
            continue
        if isinstance(value, bool):
            value = int(value)
        attrs[f"param_{key}"] = value
    return attrs


def write_netcdf(ds, path) -> Path:
    """Write an xarray Dataset to netCDF4 atomically; return the final path.

    The Dataset first goes through :func:`dhfield.io.cf.finalize` (canonical
    dimension order, no ``_FillValue`` on coordinates), so every file is CF-clean.
    """
    from .cf import finalize

    p = Path(path)
    ds = finalize(ds)
    with atomic_path(p) as tmp:
        ds.to_netcdf(tmp, engine="netcdf4", format="NETCDF4")
    return p


def read_netcdf(path):
    """Read a netCDF file written by dhfield into memory; clear error if unreadable."""
    import xarray as xr

    p = Path(path)
    if not p.is_file():
        raise ValueError(f"input file does not exist or is not a file; got {str(p)!r}")
    try:
        with xr.open_dataset(p, engine="netcdf4") as ds:
            return ds.load()
    except Exception as exc:  # noqa: BLE001 - any backend failure is an unreadable file
        raise ValueError(f"input file is not a readable netCDF file: {str(p)!r} ({exc})") from None
