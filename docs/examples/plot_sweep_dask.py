"""
A sweep on a dask cluster, and its map
======================================

:func:`dhfield.sweep.run_sweep` computes a quantity over a grid of (β0, μ) as dask tasks,
stores every case as it finishes (an interrupted run resumes), and writes one consolidated
netCDF file.  Here a small pull-off map of two models runs on a local dask cluster (threads
in this process, to keep the example light; ``tcp://host:port`` or a ``distributed.Client``
of a real cluster works the same), and :mod:`dhfield.io.sweep_maps` draws it.
"""
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
from distributed import Client, LocalCluster

from dhfield.io import sweep_maps as plotting
from dhfield import sweep

config = sweep.config_from_mapping({
    "sweep": {"quantities": ["pull_off"], "models": ["dh-elliptic", "md"]},
    "axes": {"beta0": {"linspace": [0.5, 1.0, 11]}, "mu": {"geomspace": [0.1, 10, 40]}},
})
out = Path(tempfile.mkdtemp()) / "map.nc"
with LocalCluster(n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None) as cluster, \
        Client(cluster) as client:
    result = sweep.run_sweep(config, out=out, scheduler=client, progress=False)
ds = result.dataset
print(f"{len(result.computed)} cases computed, {len(result.reused)} reused, {len(result.failed)} failed; "
      f"written to {result.path.name}")
print(ds["W_star"].sizes)

fig, axes = plt.subplots(1, 2, figsize=(10, 4), layout="constrained")
plotting.pull_off_map(ds, "dh-elliptic", axes[0])
plotting.error_map(ds, "dh-elliptic", "md", axes[1])
plt.show()
