"""Array backends of the BEM (dhfield.bem.backend): the same discrete sums on another array library.

The ``numpy`` backend runs the code path of the ``cupy`` (GPU) backend on the CPU: the operator
evaluated with ``scipy.fft`` instead of pyfftw plans, the solver's working arrays taken from the
operator's array module.  Here it is checked against the pyfftw operator and solver (the default,
verified against closed forms elsewhere) and against a direct double sum of Love's coefficients.
CuPy is not installed on the CI machines: its backend is checked where a GPU is
(``python -m verification.bench_backend --backend cupy``); here only its refusal without CuPy.
"""
from __future__ import annotations

import builtins

import numpy as np
import pytest

from dhfield.bem import DugdaleLaw, Grid, love_influence, quadrant, solve_adhesive, unfold_quadrant
from dhfield.bem import backend as bk
from dhfield.bem.operator import ArrayHalfSpaceOperator, HalfSpaceOperator, get_operator
from dhfield.bem.solver import AdhesiveProblem, solve_problem

#: Two FFT libraries evaluating the same sum: round-off only (measured <= 8e-16 relative, N <= 2048).
RTOL_OPERATOR = 1e-12
#: A converged adhesive state on both backends: the solver stops at tol = 1e-8 (complementarity and
#: zone-fraction change), and the two FFT libraries' round-off moves the stopping point (measured
#: |dW|/|W| <= 8e-10 here, outer iterations 69 vs 75); 1e-6 still fails a wrong operator (~1e-2).
RTOL_STATE = 1e-6


@pytest.mark.parametrize("shape", [(16, 16), (24, 40), (64, 12)])
@pytest.mark.parametrize("symmetric", [False, True])
def test_numpy_backend_operator_is_the_pyfftw_operator(shape, symmetric):
    g = Grid(shape[0], shape[1], 0.1, 0.07)
    ref = HalfSpaceOperator(g, 2.0, symmetric=symmetric)
    op = ArrayHalfSpaceOperator(g, 2.0, symmetric=symmetric, backend="numpy")
    p = np.random.default_rng(7).standard_normal(ref.input_shape)
    u_ref = ref(p)
    u = op(p)
    out = np.empty_like(u)
    assert op(p, out=out) is out
    scale = np.abs(u_ref).max()
    assert np.abs(u - u_ref).max() <= RTOL_OPERATOR * scale
    assert np.array_equal(out, u)


def test_numpy_backend_operator_is_the_direct_love_sum():
    grid = Grid.centered(20, 1.0, ny=12, half_width_y=0.6)
    q = np.random.default_rng(3).standard_normal((10, 6))
    p = unfold_quadrant(q)
    x, y = grid.mesh()
    direct = np.array([[np.sum(love_influence(x[i, j] - x, y[i, j] - y, grid.dx / 2, grid.dy / 2) * p)
                        for j in range(grid.ny)] for i in range(grid.nx)])
    sym = get_operator(grid, symmetric=True, backend="numpy")(quadrant(p))
    full = get_operator(grid, backend="numpy")(p)
    scale = np.abs(direct).max()
    assert np.abs(unfold_quadrant(sym) - direct).max() <= 10 * RTOL_OPERATOR * scale
    assert np.abs(full - direct).max() <= 10 * RTOL_OPERATOR * scale


@pytest.mark.parametrize("symmetric", [True, False])
def test_adhesive_state_is_the_same_on_both_backends(symmetric):
    grid = Grid.centered(64, 2.0)
    x, y = grid.mesh()
    z = 0.5 * (x * x + y * y)                                 # the sphere, R = 1 (paper units)
    law = DugdaleLaw(2.0, 0.5)                                # mu = 2: sigma0 = 2, h0 = 1/2 (dgamma = 1)
    ref = solve_adhesive(z, grid, -0.1, law, tol=1e-8, symmetric=symmetric)          # pyfftw (default)
    prob = AdhesiveProblem(z, grid, law, symmetric, None, 1.0, backend="numpy")
    assert isinstance(prob.op, ArrayHalfSpaceOperator)
    st = solve_problem(prob, -0.1, None, 1e-8, 20000)
    assert ref.converged and st.converged
    assert ref.contact.sum() > 1000 and (ref.cohesive > 0).sum() > 300     # contact and a cohesive zone
    assert isinstance(st.pressure, np.ndarray) and st.pressure.shape == grid.shape
    assert st.load == pytest.approx(ref.load, rel=RTOL_STATE)
    assert np.array_equal(st.contact, ref.contact)


def test_environment_selects_the_backend(monkeypatch):
    g = Grid(16, 16, 0.1, 0.1)
    monkeypatch.setenv("DHFIELD_BEM_BACKEND", "numpy")
    assert bk.default_backend() == "numpy"
    assert isinstance(get_operator(g), ArrayHalfSpaceOperator)
    monkeypatch.setenv("DHFIELD_BEM_BACKEND", " ")
    assert bk.default_backend() == "fftw"
    assert isinstance(get_operator(g), HalfSpaceOperator)
    monkeypatch.delenv("DHFIELD_BEM_BACKEND")
    assert bk.default_backend() == "fftw"
    monkeypatch.setenv("DHFIELD_BEM_BACKEND", "opencl")
    with pytest.raises(ValueError, match="DHFIELD_BEM_BACKEND"):
        bk.default_backend()


@pytest.mark.parametrize("bad", ["cuda", "", 3, None])
def test_bad_backend_names_the_parameter(bad):
    with pytest.raises(ValueError, match="backend must be one of fftw, numpy, cupy"):
        bk.check_backend(bad)
    with pytest.raises(ValueError, match="backend"):
        get_operator(Grid(16, 16, 0.1, 0.1), backend=bad if bad is not None else 1.5)


def test_fftw_is_not_an_array_backend():
    with pytest.raises(ValueError, match="'numpy' or 'cupy'"):
        ArrayHalfSpaceOperator(Grid(16, 16, 0.1, 0.1), backend="fftw")


def test_cupy_without_cupy_is_a_clear_error(monkeypatch):
    real_import = builtins.__import__

    def no_cupy(name, *args, **kwargs):
        if name.split(".")[0] in ("cupy", "cupyx"):
            raise ImportError(f"No module named {name!r}")
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_cupy)
    monkeypatch.setattr("importlib.import_module", lambda name: no_cupy(name))
    with pytest.raises(ValueError, match="backend 'cupy' needs CuPy"):
        bk.array_module("cupy")


def test_host_helpers_leave_numpy_arrays_alone():
    a = np.arange(6.0).reshape(2, 3)
    assert bk.to_host(a) is a
    assert bk.namespace_of(a) is np
    assert bk.namespace_of(1.5) is np
    assert isinstance(bk.to_host([1.0, 2.0]), np.ndarray)
