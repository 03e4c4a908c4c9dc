"""Progress of a BEM pull-off solve, one line per state, and its time limit (``dhfield solve``).

:class:`SolveProgress` is handed every state the solve computes, on every grid
(:func:`dhfield.bem.branch.state_reporter`), and writes one line per state: the grid, the
branch and phase, the state's load in the result's units (W* of Eq. 34 for nondimensional
input, newtons for SI input), the elapsed time and an ETA.  Where a time limit is set it
stops the solve after the state that crosses it, raising :class:`SolveTimeLimit` with what
was reached.

The ETA
-------
A state costs about the same per cell on every grid, so the seconds per cell of the states
solved so far, times the cells of the answer's grid, times the states still expected on it,
is the time left; on the finer grids a state needs more iterations, so the seconds per cell are
at least those of the last state on the finest grid solved so far.  A route solves a typical number of states on the answer's grid
(:data:`EXPECTED_STATES`: 3-4 on the located route, a handful on the bracket search); past
that number the ETA is that of one more state.  A route that refines its answer's grid (the
Newton route, while its stated error is above its target) says so on a line of its own
(:meth:`SolveProgress.set_answer_grid`, through :func:`dhfield.bem.branch.answer_grid_changed`),
and the ETA counts the new grid from then on.  It is an estimate, written ``~``.
"""
from __future__ import annotations

import math
import sys
import time

__all__ = ["EXPECTED_STATES", "PROGRESS_PREFIX", "SolveTimeLimit", "SolveProgress"]

#: Typical number of states a route solves on the answer's grid [-]: 'located', 3 lattice samples and
#: at most one parabola vertex; 'bracket', the start, the bracket and its refinements; 'predicted',
#: lattice samples around GVG's pull-off; 'newton', the first state, two around it, the bracket and the vertex; 'march', uniform unloading steps to the jump; the continuation
#: of displacement control and the spring's branch sample the whole branch.
EXPECTED_STATES = {"newton": 5, "located": 4, "bracket": 6, "predicted": 6, "march": 30, "displacement": 30, "spring": 30}
#: Start of every progress line, so that a reader can tell them from the result's messages.
PROGRESS_PREFIX = "dhfield: progress: "


class SolveTimeLimit(BaseException):
    """The solve ran past its time limit and was stopped (a BaseException: no solver catches it).

    Parameters
    ----------
    reached : str
        What was reached: states, elapsed time and the lowest load on the answer's grid.
    """

    def __init__(self, reached):
        super().__init__(reached)
        self.reached = reached


class SolveProgress:
    """The reporter of :func:`dhfield.bem.branch.state_reporter`: one line per state on a stream.

    Parameters
    ----------
    load_scale : float
        Multiplies a state's load (the problem's units, R = E* = Delta gamma = 1) into the
        result's unit: sin(theta_skew)/(2 pi) for W* (Eq. 34), times the load unit
        2 pi R Delta gamma/sin(theta_skew) for newtons.
    unit : {'W*', 'N'}
        The result's unit.
    answer_grid : (int, int)
        Cells (nx, ny) of the grid the answer is computed on [-].
    route : str
        A key of :data:`EXPECTED_STATES` [-].
    max_seconds : float, optional
        Stop after the first state that ends past this elapsed time [s]; None: no limit.
    stream : file, optional
        Where the lines go; default ``sys.stderr``.
    header : str, optional
        A line written before the first state's (what is being solved); none before a solve that
        fails before its first state (bad input).
    """

    def __init__(self, load_scale, unit, answer_grid, route, max_seconds=None, stream=None, header=""):
        self.load_scale = float(load_scale)
        self.unit = unit
        self.answer_cells = int(answer_grid[0]) * int(answer_grid[1])
        self.answer_grid = (int(answer_grid[0]), int(answer_grid[1]))
        self.expected = EXPECTED_STATES.get(route, EXPECTED_STATES["bracket"])
        self.max_seconds = None if max_seconds is None else float(max_seconds)
        self.stream = sys.stderr if stream is None else stream
        self.header = header
        self.t0 = self._last = time.perf_counter()
        self.states = 0
        self.answer_states = 0
        self.cells_done = 0
        self.finest = (0, 0.0)        # (cells, seconds per cell) of the last state on the finest grid so far
        self.lowest = math.inf        # the lowest load on the answer's grid, in the result's unit
        self.lowest_any = math.inf    # on any grid

    def elapsed(self) -> float:
        """Return the seconds since the reporter was made.

        Returns
        -------
        float
            The elapsed wall time [s].
        """
        return time.perf_counter() - self.t0

    def _value(self, load) -> str:
        v = float(load) * self.load_scale
        return f"W* = {v:+.5f}" if self.unit == "W*" else f"W = {v:+.5g} N"

    def eta(self) -> float:
        """Estimate the seconds left (module docstring).

        Returns
        -------
        float
            The estimated time to the end of the solve [s]; NaN before the first state.
        """
        if self.cells_done == 0:
            return math.nan
        per_cell = max(self.elapsed() / self.cells_done, self.finest[1])
        left = max(self.expected - self.answer_states, 1 if self.answer_states >= self.expected else 0)
        return left * self.answer_cells * per_cell

    def __call__(self, label, k, st, phase):
        now = time.perf_counter()
        nx, ny = int(st.grid.nx), int(st.grid.ny)
        if nx * ny >= self.finest[0]:
            self.finest = (nx * ny, (now - self._last) / (nx * ny))
        self._last = now
        self.states += 1
        self.cells_done += nx * ny
        value = float(st.load) * self.load_scale
        self.lowest_any = min(self.lowest_any, value)
        if (nx, ny) == self.answer_grid:
            self.answer_states += 1
            self.lowest = min(self.lowest, value)
        eta = self.eta()
        flag = "" if st.converged else " (not converged)"
        if self.states == 1 and self.header:
            self.stream.write(f"{PROGRESS_PREFIX}{self.header}\n")
        self.stream.write(f"{PROGRESS_PREFIX}state {self.states} on {nx} x {ny} ({label}, {phase}): "
                          f"{self._value(st.load)}{flag}; elapsed {self.elapsed():.1f} s, "
                          f"ETA ~{eta:.1f} s\n")
        self.stream.flush()
        if self.max_seconds is not None and self.elapsed() > self.max_seconds:
            raise SolveTimeLimit(self.reached())

    def set_answer_grid(self, shape, reason=""):
        """Take ``shape`` as the answer's grid from now on (a route that refines), and say so.

        The ETA then counts the states expected on the new grid; the lowest load on the answer's
        grid is that of the new grid.

        Parameters
        ----------
        shape : (int, int)
            Cells (nx, ny) of the new answer's grid [-].
        reason : str, optional
            Why, appended to the line.
        """
        self.answer_grid = (int(shape[0]), int(shape[1]))
        self.answer_cells = self.answer_grid[0] * self.answer_grid[1]
        self.answer_states = 0
        self.lowest = math.inf
        why = f" ({reason})" if reason else ""
        self.stream.write(f"{PROGRESS_PREFIX}refining: the answer's grid is now {self.answer_grid[0]} x "
                          f"{self.answer_grid[1]}{why}; elapsed {self.elapsed():.1f} s, ETA ~{self.eta():.1f} s\n")
        self.stream.flush()

    def reached(self) -> str:
        """Say what was reached: the states solved, the time, the lowest load on the answer's grid.

        Returns
        -------
        str
            One clause, e.g. ``"12 states in 3.1 s; the lowest W* on the 256 x 256 grid -0.79261"``.
        """
        grid = f"{self.answer_grid[0]} x {self.answer_grid[1]}"
        if math.isfinite(self.lowest):
            low = f"the lowest {self._value(self.lowest / self.load_scale)} on the {grid} grid"
        elif math.isfinite(self.lowest_any):
            low = f"no state on the {grid} grid yet (the lowest on a coarser grid: " \
                  f"{self._value(self.lowest_any / self.load_scale)})"
        else:
            low = "no state solved yet"
        return f"{self.states} state{'' if self.states == 1 else 's'} in {self.elapsed():.1f} s; {low}"
