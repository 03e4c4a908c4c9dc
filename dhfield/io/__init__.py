"""Input/output at the edge of the library: netCDF and CSV.

Everything here is thin: the numpy core never imports this package.

Atomic writes
-------------
Every file is written to a temporary file in the target directory
(``.<name>.<pid>-<random>.part``, with the first 32 characters of the name and the
writer's process id; at most 58 bytes, so any legal target name works) and moved
into place with ``os.replace`` only when the write succeeded.  A failed or
interrupted write never leaves a partial file and never clobbers an existing
one.  A temporary file left by a writer that was killed outright (SIGKILL, a
power cut) is removed by the next write to the same target, once its process id
names no running process on this machine.

Files written together -- a CSV and its ``.json`` sidecar, a figure's PNG, SVG
and PDF, ``dhfield solve --out`` with ``--plot`` -- are committed as a set
(:func:`atomic_files`): each goes to its temporary file, and only when all of
them are complete are they moved into place, one after another with the signals
below deferred, so an interrupt leaves either all the new files or none of them
(the old ones kept).  :func:`written_files` lists what this process has moved
into place.

Which targets are accepted (:func:`validate_output_path`, called before any
computation):

* a regular file or a new name, in an existing, writable directory, with a
  name of at most ``NAME_MAX`` bytes (255 on Linux); an existing file keeps its
  permission bits;
* **symbolic links are refused**, not written through: replacing the link
  would break it, and writing through it would let a planted link redirect
  the output anywhere (name the link's target instead);
* non-regular files (directories, devices such as ``/dev/null``, FIFOs,
  sockets) are refused: a rename would replace the node itself;
* an existing read-only file (no write bit, or not writable by this user) is
  refused: the rename would otherwise replace it despite its mode.

Signals
-------
While a file is being written in the main thread, SIGINT, SIGTERM and SIGHUP
(unless ignored) are caught: the temporary file is removed and the signal is
then re-delivered to the handler that was in place before (so SIGINT still
raises ``KeyboardInterrupt`` and an unhandled SIGTERM still terminates the
process, only without a ``.part`` left behind).  netCDF files are written with
netCDF4 directly (no xarray file locks, which deadlock when an interrupt lands
inside them), in slabs of at most 16 MiB with the signals deferred to the slab
boundaries, so an interrupted write stops within one slab.
"""
from __future__ import annotations

import contextlib
import datetime as _dt
import errno
import os
import re
import shutil
import signal
import stat
import tempfile
import threading
from pathlib import Path

from .. import PAPER_DOI, __version__

__all__ = ["atomic_path", "atomic_files", "written_files", "provenance_attrs", "git_commit", "write_netcdf", "read_netcdf", "check_writable",
           "validate_output_path", "require_utf8_path", "format_size", "SignalExit", "CAUGHT_SIGNALS"]

REFERENCES = (
    "Zini N.H.M., de Rooij M.B., Bazr Afshan Fadafan M., Ismail N., Schipper D.J. (2018) "
    "Extending the double-Hertz model to allow modeling of an adhesive elliptical contact. "
    f"Tribology Letters 66:30. doi:{PAPER_DOI}"
)

#: Signals caught while a file is written (then re-delivered after the cleanup).
CAUGHT_SIGNALS = tuple(s for s in (getattr(signal, n, None) for n in ("SIGINT", "SIGTERM", "SIGHUP"))
                       if s is not None)

#: Largest slab written to netCDF between two signal checks [bytes].
_SLAB_BYTES = 16 * 2**20

#: Characters of the target name kept in the temporary name (bounds its length to 58 bytes).
_TEMP_NAME_CHARS = 32
#: The writer's process id and mkstemp's random part of a temporary name: ``<pid>-<8 characters>``.
_PART_TAIL = re.compile(r"(\d{1,10})-[A-Za-z0-9_]{8}")

#: Files moved into place by this process, in order (:func:`written_files`).
_WRITTEN: list = []
#: The set of files being written together in this thread (:func:`atomic_files`), or None.
_GROUP = threading.local()

_FALLBACK_NAME_MAX = 255
_FALLBACK_PATH_MAX = 4096


class SignalExit(BaseException):
    """A termination signal (SIGTERM, SIGHUP, ...) turned into an exception.

    A ``BaseException`` like ``KeyboardInterrupt``, so ``except Exception``
    does not swallow it.  ``exit_status`` is the shell convention 128 + signal.

    Parameters
    ----------
    signum : int
        The signal number.
    """

    def __init__(self, signum: int):
        self.signum = int(signum)
        super().__init__(f"terminated by {signal.Signals(self.signum).name}")

    @property
    def exit_status(self) -> int:
        """Exit status of a process killed by the signal: 128 + signal number."""
        return 128 + self.signum


class _Caught(BaseException):
    """Raised by :class:`_SignalGuard` to unwind a write; never escapes it."""


class _SignalGuard:
    """Catch :data:`CAUGHT_SIGNALS` for a block; re-deliver the first one after it.

    ``defer=False``: the first signal raises :class:`_Caught` at once (the
    block's cleanup runs).  ``defer=True``: the signal is only recorded and
    :meth:`check` raises at a point of the caller's choosing.  Either way, on
    leaving the block the previous handlers are restored and the signal is
    raised again for them.  Outside the main thread the guard does nothing.
    """

    def __init__(self, defer: bool = False):
        self.defer = defer
        self.caught = None
        self._previous = {}

    def _handler(self, signum, frame):  # noqa: ARG002 - signal handler signature
        if self.caught is not None:
            return  # already unwinding: never interrupt the cleanup
        self.caught = signum
        if not self.defer:
            raise _Caught(signum)

    def check(self) -> None:
        if self.caught is not None:
            raise _Caught(self.caught)

    def __enter__(self):
        if threading.current_thread() is not threading.main_thread():
            return self
        for s in CAUGHT_SIGNALS:
            prev = signal.getsignal(s)
            if prev in (signal.SIG_IGN, None):
                continue  # an ignored signal stays ignored (e.g. SIGINT of a background job)
            self._previous[s] = prev
            signal.signal(s, self._handler)
        return self

    def __exit__(self, exc_type, exc, tb):
        for s, prev in self._previous.items():
            signal.signal(s, prev)
        if self.caught is None:
            return False
        signum = self.caught
        signal.raise_signal(signum)  # the previous handler acts now (raises, or terminates the process)
        # it returned: a handler that only records the signal; the write is abandoned all the same
        if signum == getattr(signal, "SIGINT", None):
            raise KeyboardInterrupt from None
        raise SignalExit(signum) from None


# --------------------------------------------------------------------------- paths
def _limit(parent: Path, key: str, fallback: int) -> int:
    try:
        return int(os.pathconf(parent, key))
    except (OSError, ValueError):
        return fallback


def _kind(mode: int) -> str:
    for test, what in ((stat.S_ISDIR, "a directory"), (stat.S_ISCHR, "a character device"),
                       (stat.S_ISBLK, "a block device"), (stat.S_ISFIFO, "a FIFO (named pipe)"),
                       (stat.S_ISSOCK, "a socket"), (stat.S_ISLNK, "a symbolic link")):
        if test(mode):
            return what
    return "not a regular file"


def _check_target(p: Path, label: str):
    """The lstat of an existing target, or None; ValueError if it must not be replaced."""
    try:
        st = os.lstat(p)
    except FileNotFoundError:
        return None
    except OSError as exc:
        raise ValueError(f"{label} cannot be examined: {str(p)!r} ({exc.strerror})") from None
    if stat.S_ISLNK(st.st_mode):
        raise ValueError(f"{label} must not be a symbolic link (dhfield does not write through links; "
                         f"name its target {os.path.realpath(p)!r} instead); got {str(p)!r}")
    if not stat.S_ISREG(st.st_mode):
        raise ValueError(f"{label} must be a regular file or a new name; {str(p)!r} is {_kind(st.st_mode)}")
    if not st.st_mode & 0o222 or not os.access(p, os.W_OK):
        raise ValueError(f"{label} {str(p)!r} is read-only (mode {stat.S_IMODE(st.st_mode):04o}); dhfield "
                         "does not replace read-only files: make it writable or choose another name")
    return st


def validate_output_path(path, suffixes=None, name: str = "out") -> Path:
    """Check that ``path`` can be written by dhfield; return it as a Path.

    Call it before computing anything, so that a bad path fails at once.

    Parameters
    ----------
    path : str or path-like
        The output file.
    suffixes : sequence of str, optional
        Accepted file-name suffixes (compared case-insensitively), e.g.
        ``(".nc", ".csv")``; default: any.
    name : str, default "out"
        The parameter name used in error messages.

    Returns
    -------
    pathlib.Path
        ``path``, as a Path.

    Raises
    ------
    ValueError
        Naming ``name`` and the valid range, if the path is empty, has the wrong
        suffix, a file name longer than ``NAME_MAX`` bytes (255 on Linux) or a
        path longer than ``PATH_MAX``; if its directory does not exist or is not
        writable; or if it names a symbolic link, a non-regular file (directory,
        device, FIFO, socket) or a read-only file.  A ``.csv`` path's JSON
        sidecar (``.csv.json``) is checked in the same way, and an existing
        sidecar is replaced only with its CSV: a new CSV name whose sidecar
        already exists is refused.
    """
    label = f"{name} (output path)"
    text = os.fsdecode(path) if path is not None else ""
    valid = "a file path in an existing, writable directory"
    if not text.strip():
        raise ValueError(f"{label} must be {valid}; got an empty path {text!r}")
    if "\x00" in text:
        raise ValueError(f"{label} must not contain a NUL character; got {text!r}")
    if text.endswith(os.sep) or Path(text).name in ("", ".", ".."):
        raise ValueError(f"{label} must name a file, not a directory; got {text!r}")
    p = Path(text)
    if p.suffix.lower() == ".nc":
        require_utf8_path(os.path.abspath(text), label)
    if suffixes:
        suffixes = tuple(s.lower() for s in suffixes)
        if p.suffix.lower() not in suffixes:
            raise ValueError(f"{label} must end in {' or '.join(suffixes)}; got {text!r}")
    parent = p.parent if str(p.parent) else Path(".")
    if not parent.is_dir():
        raise ValueError(f"{label} must be {valid}; directory {str(parent)!r} does not exist")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise ValueError(f"{label} must be {valid}; directory {str(parent)!r} is not writable")
    name_max = _limit(parent, "PC_NAME_MAX", _FALLBACK_NAME_MAX)
    path_max = _limit(parent, "PC_PATH_MAX", _FALLBACK_PATH_MAX)
    targets = [p]
    if p.suffix.lower() == ".csv":
        targets.append(p.with_name(p.name + ".json"))  # the sidecar of dhfield.io.table
    for t in targets:
        n = len(os.fsencode(t.name))
        if n > name_max:
            raise ValueError(f"{label} file name must be at most {name_max} bytes here; "
                             f"{t.name[:20]!r}... has {n}")
        if len(os.fsencode(os.path.abspath(t))) >= path_max:
            raise ValueError(f"{label} must be shorter than {path_max} bytes (PATH_MAX); got "
                             f"{len(os.fsencode(os.path.abspath(t)))} bytes")
        _check_target(t, label)
    if len(targets) > 1 and not os.path.lexists(p) and os.path.lexists(targets[1]):
        # a sidecar is replaced only together with its CSV: alone, it may describe another table
        raise ValueError(f"{label} {text!r} does not exist but its JSON sidecar {str(targets[1])!r} does; "
                         "dhfield replaces a sidecar only together with its CSV: remove the sidecar or choose "
                         "another name")
    return p


def require_utf8_path(text: str, label: str = "out (output path)") -> None:
    """Refuse a file name that is not valid UTF-8: the netCDF library takes UTF-8 file names only.

    A name given in another encoding reaches Python with surrogate escapes
    (PEP 383); netCDF4 then failed with a bare codec error after the computation.

    Parameters
    ----------
    text : str
        The file name.
    label : str, default "out (output path)"
        The parameter named in the error message.

    Raises
    ------
    ValueError
        If ``text`` is not valid UTF-8.
    """
    try:
        str(text).encode("utf-8")
    except UnicodeEncodeError:
        shown = os.fsencode(text)
        raise ValueError(f"{label} must be valid UTF-8 for a netCDF file (the netCDF library takes UTF-8 file "
                         f"names only); got {shown!r}: rename it, or set a UTF-8 locale and use a UTF-8 "
                         "name") from None


def check_writable(path, name: str = "out") -> Path:
    """Check that ``path`` can be written, without a suffix check (kept for existing callers).

    Parameters
    ----------
    path : str or path-like
        The output file.
    name : str, default "out"
        The parameter name used in error messages.

    Returns
    -------
    pathlib.Path
        ``path``, as a Path (:func:`validate_output_path`).
    """
    return validate_output_path(path, None, name)


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def written_files() -> list:
    """The files this process has moved into place, in order (most recent last).

    Used by the command line to say exactly what was written before an interrupt.

    Returns
    -------
    list of pathlib.Path
        Every target of :func:`atomic_path` (and so of :func:`write_netcdf`) committed so far.
    """
    return list(_WRITTEN)


def _part_prefix(p: Path) -> str:
    """Temporary-name prefix of target ``p`` without the process id: ``.<first 32 characters>.``."""
    return f".{p.name[:_TEMP_NAME_CHARS]}."


def _remove_stale_parts(p: Path, parent: Path) -> None:
    """Remove the temporary files of target ``p`` left by writers that no longer run on this machine.

    A temporary name carries its writer's process id; one whose process is gone (a SIGKILL
    or a power cut ended the write) is stale.  Names without a process id, and those of
    running processes (including this one), are left alone.
    """
    prefix = _part_prefix(p)
    try:
        names = os.listdir(parent)
    except OSError:
        return
    for name in names:
        if not (name.startswith(prefix) and name.endswith(".part")):
            continue
        m = _PART_TAIL.fullmatch(name[len(prefix):-len(".part")])
        if m is None:
            continue
        pid = int(m.group(1))
        if pid == os.getpid():
            continue
        try:
            os.kill(pid, 0)
        except ProcessLookupError:   # no such process: the write died with it
            with contextlib.suppress(OSError):
                os.unlink(parent / name)
        except (PermissionError, OverflowError, OSError):   # another user's running process, or unknowable
            continue


@contextlib.contextmanager
def atomic_files():
    """Commit every file written in the block as one set: all of them, or none.

    Inside the block, :func:`atomic_path` (and so :func:`write_netcdf` and every
    writer of :mod:`dhfield.io`) writes each file to its temporary name and leaves
    it there.  When the block ends normally, every target is checked again, then
    all are moved into place, one after another with SIGINT, SIGTERM and SIGHUP
    deferred (a signal that arrives meanwhile acts once the last one is in place).
    If the block raises or is interrupted, every temporary file is removed and
    no target is touched.  Blocks nest: the outermost commits.

    Yields
    ------
    None

    Raises
    ------
    OSError
        One line naming the files moved into place and those not, if a rename
        fails after others succeeded (the filesystem refused it: rare).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from dhfield.io import atomic_files, atomic_path
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> with atomic_files():
    ...     with atomic_path(d / "a.txt") as tmp:
    ...         _ = tmp.write_text("a")
    ...     with atomic_path(d / "b.txt") as tmp:
    ...         _ = tmp.write_text("b")
    ...     print(sorted(q.name for q in d.iterdir() if not q.name.startswith(".")))
    []
    >>> sorted(q.name for q in d.iterdir())
    ['a.txt', 'b.txt']
    """
    if getattr(_GROUP, "staged", None) is not None:
        yield                     # an enclosing set commits these files with its own
        return
    staged = {}                   # target -> (temporary file, parameter name)
    _GROUP.staged = staged
    try:
        with _SignalGuard() as guard:
            try:
                yield
                guard.check()
                _commit(staged)
            finally:
                _GROUP.staged = None
                for tmp, _ in staged.values():
                    with contextlib.suppress(OSError):
                        os.unlink(tmp)
    finally:
        _GROUP.staged = None


def _commit(staged: dict) -> None:
    """Move every staged file into place, the signals deferred until the last one is in."""
    with _SignalGuard(defer=True):
        checked = [(final, tmp, _check_target(final, f"{name} (output path)"))
                   for final, (tmp, name) in staged.items()]   # every target first: none moved if one fails
        done = []
        for final, tmp, st in checked:
            try:
                os.chmod(tmp, stat.S_IMODE(st.st_mode) if st is not None else 0o666 & ~_umask())
                os.replace(tmp, final)
            except OSError as exc:
                rest = [str(f) for f, _, _ in checked if f not in done]
                written = f"written: {', '.join(map(str, done))}; " if done else "nothing was written; "
                raise OSError(f"could not move {str(final)!r} into place ({exc.strerror or exc}); {written}"
                              f"not written: {', '.join(rest)}") from None
            del staged[final]
            done.append(final)
            _WRITTEN.append(final)


@contextlib.contextmanager
def atomic_path(path, name: str = "out"):
    """Yield a temporary path next to ``path``; move it into place only on success.

    The target is checked with :func:`validate_output_path` (symbolic links,
    non-regular and read-only files are refused) and checked again just before
    the rename.  The new file gets the permission bits of the file it replaces,
    or ``0666 & ~umask`` for a new name.  If the block raises, or SIGINT,
    SIGTERM or SIGHUP arrives, the temporary file is removed; the signal is
    then re-delivered to the previous handler.  Inside :func:`atomic_files` (or
    another ``atomic_path``) the file is moved into place with the others of
    that set, when the outermost block ends.  Temporary files of this target
    left by writers that no longer run are removed first.

    Parameters
    ----------
    path : str or path-like
        The final file.
    name : str, default "out"
        The parameter name used in error messages.

    Yields
    ------
    pathlib.Path
        The temporary file to write.
    """
    p = validate_output_path(path, None, name)
    parent = p.parent if str(p.parent) else Path(".")
    _remove_stale_parts(p, parent)
    with atomic_files():
        staged = _GROUP.staged
        tmp = None
        try:
            fd, tmp = tempfile.mkstemp(prefix=f"{_part_prefix(p)}{os.getpid()}-", suffix=".part", dir=parent)
            os.close(fd)
            yield Path(tmp)
            _check_target(p, f"{name} (output path)")  # the target may have changed meanwhile
            if p in staged:          # written twice in one set: the later file wins
                with contextlib.suppress(OSError):
                    os.unlink(staged.pop(p)[0])
            staged[p] = (Path(tmp), name)
            tmp = None
        finally:
            if tmp is not None:
                with contextlib.suppress(FileNotFoundError):
                    os.unlink(tmp)
    # a signal caught in the block was re-raised by the guard; _Caught never gets here


def provenance_attrs(title: str, **parameters) -> dict:
    """Build CF-style global attributes plus every input parameter as an attribute.

    Parameters
    ----------
    title : str
        The file's title.
    **parameters
        Input parameters, stored as ``param_<name>`` (None skipped, bools as 0/1).

    Returns
    -------
    dict
        The global attributes.
    """
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


#: The checkout dhfield runs from (``git_commit`` asks git about it).
_CHECKOUT = Path(__file__).resolve().parents[2]


def git_commit(*, short=None, paths=None) -> str:
    """Name the git commit of the checkout dhfield runs from, for provenance.

    Parameters
    ----------
    short : int, optional
        Abbreviate the hash to this many hex digits (default: the full hash).
    paths : sequence of str, optional
        Report uncommitted changes of these paths only (relative to the checkout);
        default: of every tracked file.

    Returns
    -------
    str
        The hash, followed by ``" (uncommitted changes)"`` (or ``" (uncommitted
        changes in <paths>)"``) when tracked files differ from it; ``"unavailable"``
        outside a git checkout or without git.

    Examples
    --------
    >>> from dhfield.io import git_commit
    >>> isinstance(git_commit(short=12), str)
    True
    """
    import subprocess

    if not (_CHECKOUT / ".git").exists():  # an installed package: no checkout to name
        return "unavailable"
    rev = ["git", "rev-parse"] + ([f"--short={int(short)}"] if short else []) + ["HEAD"]
    status = ["git", "status", "--porcelain", "--untracked-files=no"] + (["--", *paths] if paths else [])
    try:
        head = subprocess.run(rev, cwd=_CHECKOUT, capture_output=True, text=True, timeout=10)
        if head.returncode != 0:
            return "unavailable"
        dirty = subprocess.run(status, cwd=_CHECKOUT, capture_output=True, text=True, timeout=10)
    except (OSError, subprocess.SubprocessError):
        return "unavailable"
    where = f" in {' '.join(paths)}" if paths else ""
    return head.stdout.strip() + (f" (uncommitted changes{where})" if dirty.stdout.strip() else "")


# --------------------------------------------------------------------------- netCDF
_NC4_ENCODING_KEYS = ("zlib", "complevel", "shuffle", "fletcher32", "contiguous", "chunksizes",
                      "compression", "least_significant_digit")


def _encoded_variables(ds):
    """CF-encoded variables and global attributes of ``ds`` (xarray's own encoder)."""
    from xarray import conventions

    variables, attrs = conventions.encode_dataset_coordinates(ds)
    return conventions.cf_encoder(variables, attrs)


def _set_attrs(target, attrs: dict, where: str) -> None:
    for key, value in attrs.items():
        if isinstance(value, bool):
            value = int(value)
        try:
            target.setncattr(key, value)
        except Exception as exc:  # noqa: BLE001 - netCDF4 raises several types for bad values
            raise ValueError(f"attribute {key!r} of {where} cannot be stored in netCDF: {value!r} ({exc})") \
                from None


def _write_encoded(nc, ds, variables, attrs, guard) -> None:
    import numpy as np

    sizes = dict(ds.sizes)
    for var in variables.values():  # the encoder may add dimensions (e.g. string lengths)
        sizes.update(zip(var.dims, var.shape))
    for dim, size in sizes.items():
        nc.createDimension(dim, size)
    _set_attrs(nc, attrs, "the dataset")
    for vname, var in variables.items():
        vattrs = dict(var.attrs)
        fill = vattrs.pop("_FillValue", None)
        data = np.asarray(var.values)
        if data.dtype.kind in "UO":
            dtype, data = str, data.astype(object)
        elif data.dtype.kind in "iufcS":
            dtype = data.dtype
        else:
            raise ValueError(f"variable {vname!r} has a dtype netCDF4 cannot store: {data.dtype}")
        enc = {k: var.encoding[k] for k in _NC4_ENCODING_KEYS if k in var.encoding}
        # no _FillValue: no pre-fill either (every element is written below)
        ncv = nc.createVariable(vname, dtype, var.dims, fill_value=False if fill is None else fill, **enc)
        ncv.set_auto_maskandscale(False)
        _set_attrs(ncv, vattrs, f"variable {vname!r}")
        if data.ndim == 0:
            ncv.assignValue(data.item() if dtype is str else data)
            continue
        row_bytes = max(1, data.nbytes // max(1, data.shape[0]))
        step = max(1, _SLAB_BYTES // row_bytes)
        for i in range(0, data.shape[0], step):
            guard.check()
            ncv[i:i + step] = data[i:i + step]
    guard.check()


def format_size(nbytes) -> str:
    """Format a byte count for people: "512 B", "3.4 KiB", "1.21 GiB" (never "0.0 MiB").

    Parameters
    ----------
    nbytes : int or float
        The count [bytes].

    Returns
    -------
    str
        The count with a binary unit.
    """
    n = float(nbytes)
    for unit in ("B", "KiB", "MiB", "GiB", "TiB"):
        if abs(n) < 1024 or unit == "TiB":
            return f"{int(n)} B" if unit == "B" else f"{n:.3g} {unit}"
        n /= 1024
    return f"{n:.3g} TiB"  # pragma: no cover


def _write_failed(exc, final: Path, tmp: Path) -> OSError:
    """An OSError in one line for a failed netCDF write (disk full is the usual cause)."""
    free = None
    with contextlib.suppress(OSError):
        free = shutil.disk_usage(tmp.parent).free
    detail = " ".join(str(exc).split()) or type(exc).__name__
    hint = ""
    if isinstance(exc, OSError) and exc.errno in (errno.ENOSPC, errno.EDQUOT, errno.EFBIG):
        hint = f" ({os.strerror(exc.errno)}" + (f"; {format_size(free)} free" if free is not None else "") + ")"
    elif free is not None and free < 2**20:
        hint = f" (no space left on device: {format_size(free)} free)"
    return OSError(f"could not write the netCDF file {str(final)!r}: {detail}{hint}; nothing was written")


def write_netcdf(ds, path, name: str = "out") -> Path:
    """Write an xarray Dataset to netCDF4 atomically.

    The Dataset first goes through :func:`dhfield.io.cf.finalize` (canonical
    dimension order, no ``_FillValue`` on coordinates), so every file is CF-clean.
    It is then CF-encoded by xarray's encoder and written with netCDF4 directly,
    slab by slab, with SIGINT/SIGTERM/SIGHUP deferred to the slab boundaries
    (see the module docstring).  An interrupted write removes its temporary file.

    Parameters
    ----------
    ds : xarray.Dataset
        The Dataset.
    path : str or path-like
        The netCDF file.
    name : str, default "out"
        The parameter name used in error messages.

    Returns
    -------
    pathlib.Path
        The final path.

    Raises
    ------
    OSError
        One line, when the write fails (disk full, ...).
    """
    import netCDF4

    from .cf import finalize

    p = validate_output_path(path, None, name)
    ds = finalize(ds)
    variables, attrs = _encoded_variables(ds)
    need = sum(int(v.nbytes) for v in ds.variables.values())  # not the encoded ones: no second encoding pass
    parent = p.parent if str(p.parent) else Path(".")
    free = None
    with contextlib.suppress(OSError):
        free = shutil.disk_usage(parent).free
    if free is not None and need > free:
        raise OSError(f"could not write the netCDF file {str(p)!r}: it needs about {format_size(need)} "
                      f"and the device has {format_size(free)} free; nothing was written")
    with atomic_path(p, name) as tmp:
        with _SignalGuard(defer=True) as guard:
            try:
                nc = netCDF4.Dataset(tmp, "w", format="NETCDF4")
            except (OSError, RuntimeError) as exc:
                raise _write_failed(exc, p, tmp) from None
            try:
                _write_encoded(nc, ds, variables, attrs, guard)
            except (OSError, RuntimeError) as exc:
                with contextlib.suppress(Exception):
                    nc.close()
                raise _write_failed(exc, p, tmp) from None
            except BaseException:
                with contextlib.suppress(Exception):
                    nc.close()
                raise
            try:
                nc.close()
            except (OSError, RuntimeError) as exc:
                raise _write_failed(exc, p, tmp) from None
    return p


def read_netcdf(path):
    """Read a netCDF file written by dhfield into memory.

    SIGINT, SIGTERM and SIGHUP are deferred until the file is closed (xarray's
    file locks would deadlock if an interrupt landed inside them).

    Parameters
    ----------
    path : str or path-like
        The netCDF file.

    Returns
    -------
    xarray.Dataset
        Its contents, loaded.

    Raises
    ------
    ValueError
        If the file does not exist or cannot be read as netCDF.
    """
    import xarray as xr

    p = Path(path)
    if not p.is_file():
        raise ValueError(f"input file does not exist or is not a file; got {str(p)!r}")
    with _SignalGuard(defer=True):
        try:
            with xr.open_dataset(p, engine="netcdf4") as ds:
                return ds.load()
        except Exception as exc:  # noqa: BLE001 - any backend failure is an unreadable file
            raise ValueError(f"input file is not a readable netCDF file: {str(p)!r} "
                             f"({' '.join(str(exc).split())})") from None
