"""Resumable per-case store of a sweep: one netCDF file per finished case.

Layout of a store directory::

    manifest.json              the sweep's config and fingerprint (written first)
    <key>.nc                   a finished case (status "ok" or "not_converged")
    <key>.failed.nc            a case that raised; retried by the next run

Every file is written atomically (:func:`dhfield.io.write_netcdf`), so a sweep
killed at any instant leaves only whole files: a rerun reads the manifest,
skips every ``<key>.nc`` and computes the rest.  A store belongs to one config:
opening it with a different one is an error (use another output path).

Each case file also carries the fingerprint of the config that computed it, its
key and its coordinates (attributes ``sweep_fingerprint``, ``case_key``,
``case_coordinates``), and a case is reused only when all three match the sweep
asking for it.  So a store whose ``manifest.json`` was deleted or replaced
cannot lend one config's cases to another: opening a store without a manifest
that holds case files of another (or an unknown) config is an error, and a
case file that does not match is computed again.  Case files of stores written
before the attributes existed are reused only under their own manifest.

A store directory that is a symbolic link is refused, as every other output is
(:func:`dhfield.io.validate_output_path`).
"""
from __future__ import annotations

import json
import os
import stat
import threading
from pathlib import Path

__all__ = ["CaseStore", "output_paths", "case_coordinates"]

_MANIFEST = "manifest.json"
#: Attributes of a case file naming what it belongs to (:meth:`CaseStore.matches`).
FINGERPRINT_ATTR, KEY_ATTR, COORDINATES_ATTR = "sweep_fingerprint", "case_key", "case_coordinates"
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


def case_coordinates(**values) -> str:
    """The coordinates of a case as the canonical JSON text stored with it (``case_coordinates``).

    Scalars are kept as they are; an array (e.g. a block of the analytic map, the contact sizes of
    a load curve) as its first value, last value and size.

    Parameters
    ----------
    **values
        The case's inputs, e.g. ``beta0=0.9, mu=1.0, n=64, law="dugdale"``.

    Returns
    -------
    str
        JSON with sorted keys.

    Examples
    --------
    >>> from dhfield.sweep.store import case_coordinates
    >>> case_coordinates(mu=[0.5, 1.0], beta0=0.9, model="md")
    '{"beta0": 0.9, "model": "md", "mu": {"first": 0.5, "last": 1.0, "size": 2}}'
    """
    import numpy as np

    out = {}
    for k, v in values.items():
        if v is None:
            continue
        a = np.asarray(v)
        if a.ndim == 0:
            item = a.item()
            out[k] = item if isinstance(item, (str, bool, int, float)) else str(item)
        else:
            flat = a.ravel()
            first, last = flat[0].item(), flat[-1].item()
            out[k] = {"first": first, "last": last, "size": int(flat.size)}
    return json.dumps(out, sort_keys=True)


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
        self._matched = {}     # case file -> ((mtime_ns, size), attributes) read by matches()
        _refuse_link(self.directory)
        mpath = self.directory / _MANIFEST
        #: True when the store's own manifest named this fingerprint (its legacy cases are trusted).
        self.adopted = False
        if mpath.is_file():
            try:
                old = json.loads(mpath.read_text()).get("fingerprint")
            except (OSError, ValueError, AttributeError):
                old = None
            if old != fingerprint:
                raise ValueError(f"out: the case store {str(self.directory)!r} belongs to a different sweep "
                                 "config; choose another output path or delete that directory")
            self.adopted = True
            return
        if self.directory.exists() and not self.directory.is_dir():
            raise ValueError(f"out: {str(self.directory)!r} exists and is not a directory")
        if self.directory.is_dir():
            self._refuse_foreign_cases()
        try:
            self.directory.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise ValueError(f"out: cannot create the case store {str(self.directory)!r} ({exc.strerror})") \
                from None
        from ..io import atomic_path

        with atomic_path(mpath) as tmp:
            tmp.write_text(json.dumps({"fingerprint": fingerprint, **(manifest or {})}, indent=1))

    def _refuse_foreign_cases(self) -> None:
        """A store without a manifest may hold only case files of this config (else ValueError, one line)."""
        foreign = unknown = 0
        for p in self.directory.glob("*.nc"):
            attrs = self._attributes(p)
            got = None if attrs is None else attrs.get(FINGERPRINT_ATTR)
            if got is None:
                unknown += 1
            elif got != self.fingerprint:
                foreign += 1
        if foreign or unknown:
            what = " and ".join(filter(None, (f"{foreign} of another sweep config" if foreign else "",
                                              f"{unknown} of an unknown one" if unknown else "")))
            raise ValueError(f"out: the case store {str(self.directory)!r} has no {_MANIFEST} and holds case files "
                             f"({what}); they are not reused: choose another output path or delete that directory")

    def _attributes(self, p: Path):
        """The identifying attributes of case file ``p`` ({} without them; None if unreadable), cached by stamp."""
        try:
            st = os.lstat(p)
        except OSError:
            return None
        if not stat.S_ISREG(st.st_mode):
            return None
        stamp = (st.st_mtime_ns, st.st_size)
        hit = self._matched.get(p)
        if hit is not None and hit[0] == stamp:
            return hit[1]
        import netCDF4

        from ..io import _SignalGuard

        try:
            with _HDF5_LOCK, _SignalGuard(defer=True), netCDF4.Dataset(p, "r") as nc:
                names = set(nc.ncattrs())
                attrs = {k: str(nc.getncattr(k)) for k in (FINGERPRINT_ATTR, KEY_ATTR, COORDINATES_ATTR)
                         if k in names}
        except (OSError, RuntimeError):
            attrs = None
        self._matched[p] = (stamp, attrs)
        return attrs

    def matches(self, key: str, coordinates: str | None = None, failed: bool = False) -> bool:
        """Whether the stored file of case ``key`` belongs to this sweep: fingerprint, key and coordinates.

        Parameters
        ----------
        key : str
            Case key (a file-name-safe string made by the sweep engine).
        coordinates : str, optional
            :func:`case_coordinates` of the case; not compared when None.
        failed : bool
            Check the failure record instead of the finished file.

        Returns
        -------
        bool
            True if the file exists and its ``sweep_fingerprint``, ``case_key`` and
            ``case_coordinates`` match; a file without them (written before they were kept)
            matches only in a store opened under its own manifest.
        """
        attrs = self._attributes(self.path(key, failed))
        if attrs is None:
            return False
        if FINGERPRINT_ATTR not in attrs:
            return self.adopted
        if attrs[FINGERPRINT_ATTR] != self.fingerprint or attrs.get(KEY_ATTR, key) != key:
            return False
        return coordinates is None or COORDINATES_ATTR not in attrs or \
            json.loads(attrs[COORDINATES_ATTR]) == json.loads(coordinates)

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

    def is_done(self, key: str, coordinates: str | None = None) -> bool:
        """Whether case ``key`` finished (successfully or not converged) in an earlier run of this sweep.

        Parameters
        ----------
        key : str
            Case key (a file-name-safe string made by the sweep engine).
        coordinates : str, optional
            :func:`case_coordinates` of the case (compared with the stored ones when given).

        Returns
        -------
        bool
            True if its finished file exists and belongs to this sweep (:meth:`matches`).
        """
        return self.matches(key, coordinates)

    def write(self, key: str, ds, coordinates: str | None = None) -> Path:
        """Write case ``key`` atomically; a ``status`` attribute "failed" goes to the failed file.

        The file carries the store's fingerprint, the key and ``coordinates``
        (attributes ``sweep_fingerprint``, ``case_key``, ``case_coordinates``).

        Parameters
        ----------
        key : str
            Case key (a file-name-safe string made by the sweep engine).
        ds : xarray.Dataset
            The case's result.
        coordinates : str, optional
            :func:`case_coordinates` of the case.

        Returns
        -------
        pathlib.Path
            The file written.
        """
        from ..io import write_netcdf

        _refuse_link(self.directory)
        ds = ds.copy()
        ds.attrs.update({FINGERPRINT_ATTR: self.fingerprint, KEY_ATTR: key})
        if coordinates is not None:
            ds.attrs[COORDINATES_ATTR] = coordinates
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

        for failed in (False, True):
            p = self.path(key, failed)
            if p.is_file() and self.matches(key, failed=failed):
                with _HDF5_LOCK:
                    return read_netcdf(p)
        return None

    def load(self, key: str, coordinates: str | None = None):
        """The Dataset of finished case ``key`` if it belongs to this sweep (:meth:`matches`), else None.

        One read of the file: :meth:`is_done` and :meth:`read` together, for a case about to be reused.

        Parameters
        ----------
        key : str
            Case key (a file-name-safe string made by the sweep engine).
        coordinates : str, optional
            :func:`case_coordinates` of the case (compared with the stored ones when given).

        Returns
        -------
        xarray.Dataset or None
            The stored case, or None if there is none of this sweep (it is then computed).
        """
        from ..io import read_netcdf

        p = self.path(key)
        try:
            st = os.lstat(p)
        except OSError:
            return None
        if not stat.S_ISREG(st.st_mode):
            return None
        try:
            with _HDF5_LOCK:
                ds = read_netcdf(p)
        except ValueError:          # unreadable: not a case of this sweep, computed again
            return None
        attrs = {k: str(ds.attrs[k]) for k in (FINGERPRINT_ATTR, KEY_ATTR, COORDINATES_ATTR) if k in ds.attrs}
        self._matched[p] = ((st.st_mtime_ns, st.st_size), attrs)
        return ds if self.matches(key, coordinates) else None

    def keys(self) -> list[str]:
        """The keys of the finished cases of this sweep (:meth:`matches`).

        Returns
        -------
        list of str
            Sorted keys (failure records and files of other configs excluded).
        """
        return sorted(k for k in (p.name[:-3] for p in self.directory.glob("*.nc")
                                  if not p.name.endswith(".failed.nc")) if self.matches(k))


def _refuse_link(directory: Path) -> None:
    """Refuse a store directory that is a symbolic link (ValueError, one line), as every output does."""
    if directory.is_symlink():
        raise ValueError(f"out: the case store must not be a symbolic link (dhfield does not write through "
                         f"links; name its target {os.path.realpath(directory)!r} instead); got "
                         f"{str(directory)!r}")
