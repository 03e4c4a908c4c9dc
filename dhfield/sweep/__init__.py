"""Sweeps: studies over grids of model inputs, on dask, resumable.

* :mod:`dhfield.sweep.config` -- :class:`SweepConfig`, read from TOML or flags and
  validated before any work starts.
* :mod:`dhfield.sweep.tasks` -- what is computed at a grid point (numpy only).
* :mod:`dhfield.sweep.engine` -- :func:`run_sweep`: chunked analytic maps through
  ``xarray.apply_ufunc(dask="parallelized")``, BEM cases as dask tasks, on a serial,
  local-process or dask.distributed scheduler.
* :mod:`dhfield.sweep.store` -- the per-case store that makes a sweep resumable.

Example::

    from dhfield.sweep import config_from_mapping, run_sweep
    cfg = config_from_mapping({"axes": {"beta0": [0.8, 0.9, 1.0], "mu": {"geomspace": [0.1, 10, 50]}},
                               "sweep": {"models": ["dh-elliptic", "md"]}})
    ds = run_sweep(cfg, out="s.nc").dataset      # ds.W_star: (model, beta0, mu)
"""
from .config import QUANTITIES, SweepConfig, config_from_mapping, load_config
from .engine import SweepResult, connect, map_cases, run_sweep
from .store import CaseStore, output_paths

__all__ = ["SweepConfig", "QUANTITIES", "config_from_mapping", "load_config", "run_sweep", "SweepResult",
           "connect", "map_cases", "CaseStore", "output_paths"]
