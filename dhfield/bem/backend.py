"""Array backends of the BEM: where the working arrays of a solve live and who transforms them.

The adhesive solver (:mod:`dhfield.bem.solver`) works on the arrays of its operator's
backend; everything it returns (:class:`dhfield.bem.state.ContactState`) is on the host,
as numpy arrays, whatever the backend.

* ``"fftw"`` (default): numpy arrays, pyfftw plans (:class:`dhfield.bem.operator.HalfSpaceOperator`).
* ``"numpy"``: numpy arrays, ``scipy.fft`` transforms
  (:class:`dhfield.bem.operator.ArrayHalfSpaceOperator`): the same code path as ``"cupy"``
  on the CPU, so that the tests exercise it.
* ``"cupy"``: CuPy arrays on an NVIDIA GPU, ``cupyx.scipy.fft`` transforms.  CuPy is not a
  dependency of dhfield: it is imported on first use, and a missing CuPy is a ValueError naming
  the backend.  Meant for the heavy ground-truth studies (a machine with a GPU); the library,
  its tests and CI never need it.

The default is ``$DHFIELD_BEM_BACKEND`` if set and not blank, else ``"fftw"``, so a study
run by ``dhfield sweep`` (whose dask workers inherit the environment) can be moved to a GPU
without a flag on every route.  The backend changes how the discrete sums are evaluated, not
what they are: the results agree to rounding (tests/test_bem_backend.py).
"""
from __future__ import annotations

import importlib
import os

import numpy as np

__all__ = ["BACKENDS", "check_backend", "default_backend", "array_module", "namespace_of", "to_host"]

#: Accepted backend names (module docstring).
BACKENDS = ("fftw", "numpy", "cupy")


def check_backend(value, name: str = "backend") -> str:
    """Check a backend name.

    Parameters
    ----------
    value : str
        Backend name, one of :data:`BACKENDS`.
    name : str, default "backend"
        Name of the parameter, used in the error message.

    Returns
    -------
    str
        ``value``, lower case.

    Raises
    ------
    ValueError
        Naming ``name`` and the accepted names if ``value`` is not one of them.
    """
    if not isinstance(value, str) or value.strip().lower() not in BACKENDS:
        raise ValueError(f"{name} must be one of {', '.join(BACKENDS)}; got {value!r}")
    return value.strip().lower()


def default_backend() -> str:
    """Return the backend used when none is given.

    Returns
    -------
    str
        ``$DHFIELD_BEM_BACKEND`` if set and not blank, else ``"fftw"``.

    Raises
    ------
    ValueError
        Naming ``DHFIELD_BEM_BACKEND`` if it is set to an unknown name.
    """
    env = os.environ.get("DHFIELD_BEM_BACKEND")
    if env is None or env.strip() == "":
        return "fftw"
    return check_backend(env, "DHFIELD_BEM_BACKEND (environment)")


def array_module(backend: str):
    """Return the array module and the FFT module of a backend.

    Parameters
    ----------
    backend : str
        One of :data:`BACKENDS`.

    Returns
    -------
    xp : module
        ``numpy`` or ``cupy``.
    fft : module
        ``scipy.fft`` or ``cupyx.scipy.fft`` (both with ``rfft2``, ``irfft2`` and ``dctn``).

    Raises
    ------
    ValueError
        If ``backend`` is unknown, or is ``"cupy"`` and CuPy cannot be imported.
    """
    backend = check_backend(backend)
    if backend != "cupy":
        import scipy.fft

        return np, scipy.fft
    try:
        cupy = importlib.import_module("cupy")
        cufft = importlib.import_module("cupyx.scipy.fft")
    except ImportError as exc:
        raise ValueError(f"backend 'cupy' needs CuPy and a GPU ({exc}); use 'fftw' or 'numpy'") from None
    return cupy, cufft


def namespace_of(array):
    """Return the array module of an array: ``cupy`` for a CuPy array, else ``numpy``.

    Parameters
    ----------
    array : array_like
        Any array or scalar.

    Returns
    -------
    module
        The module whose functions create arrays of the same kind.
    """
    mod = type(array).__module__.split(".", 1)[0]
    return importlib.import_module("cupy") if mod == "cupy" else np


def to_host(array):
    """Return an array as a numpy array (a copy from the GPU for a CuPy array; else as is).

    Parameters
    ----------
    array : array_like
        A numpy or CuPy array, or anything :func:`numpy.asarray` takes.

    Returns
    -------
    ndarray
        The values on the host.
    """
    get = getattr(array, "get", None)
    if get is not None and type(array).__module__.split(".", 1)[0] == "cupy":
        return get()
    return np.asarray(array)
