"""Memory estimates checked before large allocations.

The limit is the memory available now: ``MemAvailable`` of ``/proc/meminfo``,
lowered to the room left under a cgroup (v2) limit if the process runs in one;
elsewhere the free physical pages (``os.sysconf``).  Only a fraction
:data:`USABLE_FRACTION` of it may be claimed, leaving room for the interpreter,
the page cache and other processes.  If nothing can be measured no limit applies.
"""
from __future__ import annotations

import os

__all__ = ["available_memory", "memory_limit", "check_memory", "USABLE_FRACTION"]

#: Share of the available memory one computation may claim [-].
USABLE_FRACTION = 0.8


def _meminfo_available():
    try:
        with open("/proc/meminfo") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    try:
        return os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, AttributeError):
        return None


def _cgroup_room():
    try:
        with open("/proc/self/cgroup") as fh:
            rel = next((ln.split(":", 2)[2].strip() for ln in fh if ln.startswith("0::")), None)
        if rel is None:
            return None
        base = os.path.join("/sys/fs/cgroup", rel.lstrip("/"))
        with open(os.path.join(base, "memory.max")) as fh:
            limit = fh.read().strip()
        if limit == "max":
            return None
        with open(os.path.join(base, "memory.current")) as fh:
            current = int(fh.read().strip())
        return max(0, int(limit) - current)
    except (OSError, ValueError, StopIteration):
        return None


def available_memory():
    """Return the memory available to this process now.

    Returns
    -------
    int or None
        ``MemAvailable`` of ``/proc/meminfo`` (elsewhere the free physical pages), lowered to the
        room left under a cgroup (v2) memory limit if there is one [bytes]; None if neither can be
        read.
    """
    values = [v for v in (_meminfo_available(), _cgroup_room()) if v is not None]
    return min(values) if values else None


def memory_limit():
    """Return the most one computation may allocate.

    Returns
    -------
    int or None
        :data:`USABLE_FRACTION` of :func:`available_memory` [bytes]; None (no limit) if the
        available memory is unknown.
    """
    avail = available_memory()
    return None if avail is None else int(USABLE_FRACTION * avail)


def _gib(nbytes: float) -> str:
    return f"{nbytes / 2**30:.3g} GiB"


def check_memory(needed: float, what: str) -> None:
    """Refuse an allocation larger than :func:`memory_limit`.

    Parameters
    ----------
    needed : float
        Estimated memory the computation will allocate [bytes].
    what : str
        The input that sets the size, named in the message, e.g.
        ``"n=100000 (a 100000 x 100000 grid)"``.

    Raises
    ------
    ValueError
        If ``needed`` exceeds :func:`memory_limit`; the message names ``what``, the estimate and
        the limit [GiB].  Nothing is raised where the limit is unknown.
    """
    limit = memory_limit()
    if limit is not None and needed > limit:
        raise ValueError(f"{what} needs an estimated {_gib(needed)} of memory, more than the limit of "
                         f"{_gib(limit)} ({USABLE_FRACTION:.0%} of the {_gib(limit / USABLE_FRACTION)} available now)")
