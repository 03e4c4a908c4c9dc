"""Resumable per-case store of a sweep: one netCDF file per finished case.

Layout of a store directory::

    manifest.json              the sweep's config and fingerprint (written first)
    <key>.nc                   a finished case (status "ok" or "not_converged")
    <key>.failed.nc            a case that raised; retried by the next run

Every file is written atomically (:func:`dhfield.io.write_netcdf`), so a sweep
killed at any instant leaves only whole files: a rerun reads the manifest,
skips every ``<key>.nc`` and computes the rest.  A store belongs to one config:
opening it with a different one is an error (use another output path).
"""
from __future__ import annotations

import json
import threading
from pathlib import Path

__all__ = ["CaseStore", "output_paths"]

_MANIFEST = "manifest.json"
#: HDF5 (under netCDF4) is not thread-safe: cases finishing in threads of one process
#: (a distributed worker with several threads, or processes=False) take turns.
_HDF5_LOCK = threading.Lock()


def output_paths(out) -> tuple[Path, Path]:
    """Consolidated file and store directory of an output path.

    ``out`` ending in ``.nc`` is the consolidated file, its store is
    ``<out>.cases/`` beside it; otherwise ``out`` is a directory holding
    ``sweep.nc`` and ``cases/``.

    Parameters
    ----------
    out : path-like
        The sweep's output path.

    Returns
    -------
    consolidated : pathlib.Path
        The consolidated netCDF file.
    store : pathlib.Path
        The directory of the per-case files.

    Examples
    --------
    >>> from dhfield.sweep.store import output_paths
    >>> [p.as_posix() for p in output_paths("runs/map.nc")]
    ['runs/map.nc', 'runs/map.nc.cases']
    >>> [p.as_posix() for p in output_paths("runs/map")]
    ['runs/map/sweep.nc', 'runs/map/cases']
    """
    p = Path(out)
    if p.suffix.lower() == ".nc":
        return p, p.with_name(p.name + ".cases")
    return p / "sweep.nc", p / "cases"


class CaseStore:
    """A directory of finished cases, tied to one config fingerprint.

    Parameters
    ----------
    directory : path
        Store directory (created with its parents if missing).
    fingerprint : str
        :meth:`dhfield.sweep.SweepConfig.fingerprint` of the sweep.
    manifest : dict, optional
        Written to ``manifest.json`` when the store is new.
    """

    def __init__(self, directory, fingerprint: str, manifest: dict | None = None):
        self.directory = Path(directory)
        self.fingerprint = fingerprint
        mpath = self.directory / _MANIFEST
        if mpath.is_file():
            try:
                old = json.loads(mpath.read_text()).get("fingerprint")
            except (OSError, ValueError):
                old = None
            if old != fingerprint:
                raise ValueError(f"out: the case store {str(self.directory)!r} belongs to a different sweep "
                                 "config; choose another output path or delete that directory")
            return
        if self.directory.exists() and not self.directory.is_dir():
            raise ValueError(f"out: {str(self.directory)!r} exists and is not a directory")
        try:
            self.directory.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise ValueError(f"out: cannot create the case store {str(self.directory)!r} ({exc.strerror})") \
                from None
        from ..io import atomic_path

        with atomic_path(mpath) as tmp:
            tmp.write_text(json.dumps({"fingerprint": fingerprint, **(manifest or {})}, indent=1))

    def path(self, key: str, failed: bool = False) -> Path:
        """File of case ``key`` (``failed``: the record of a case that raised).

        Parameters
        ----------
        key : str
            Case key (a file-name-safe string made by the sweep engine).
        failed : bool
            The path of the failure record instead of the finished file.

        Returns
        -------
        pathlib.Path
            ``<key>.nc`` or ``<key>.failed.nc`` in the store.
        """
        return self.directory / (f"{key}.failed.nc" if failed else f"{key}.nc")

    def is_done(self, key: str) -> bool:
        """Whether case ``key`` finished (successfully or not converged) in an earlier run.

        Parameters
        ----------
        key : str
            Case key (a file-name-safe string made by the sweep engine).

        Returns
        -------
        bool
            True if its finished file exists.
        """
        return self.path(key).is_file()

    def write(self, key: str, ds) -> Path:
        """Write case ``key`` atomically; a ``status`` attribute "failed" goes to the failed file.

        Parameters
        ----------
        key : str
            Case key (a file-name-safe string made by the sweep engine).
        ds : xarray.Dataset
            The case's result.

        Returns
        -------
        pathlib.Path
            The file written.
        """
        from ..io import write_netcdf

        failed = ds.attrs.get("status") == "failed"
        with _HDF5_LOCK:
            path = write_netcdf(ds, self.path(key, failed))
        if not failed:
            self.path(key, True).unlink(missing_ok=True)
        return path

    def read(self, key: str):
        """The Dataset of case ``key`` (its failed record if it has no finished file), or None.

        Parameters
        ----------
        key : str
            Case key (a file-name-safe string made by the sweep engine).

        Returns
        -------
        xarray.Dataset or None
            The stored case, or None if there is none.
        """
        from ..io import read_netcdf

        for p in (self.path(key), self.path(key, True)):
            if p.is_file():
                with _HDF5_LOCK:
                    return read_netcdf(p)
        return None

    def keys(self) -> list[str]:
        """The keys of the finished cases.

        Returns
        -------
        list of str
            Sorted keys (failure records excluded).
        """
        return sorted(p.name[:-3] for p in self.directory.glob("*.nc") if not p.name.endswith(".failed.nc"))
