"""The Python side of the tapered roller bearing element: operating-point sweeps and duty
cycles on Dask (`trb-sweep`, sweeps/README.md).

Modules: `spec` (sweep files: validation, cases, ids), `variables` (the FMU's variable table
from the `trb` program), `runner` (one case on a worker: `trb simulate`), `store` (Parquet
parts and results, resuming), `sweep` (the Dask client loop), `aggregate` (Palmgren-Miner
life, time-weighted means), `plots` (maps), `cli` (the console script); `rotordynamics`
(the FMU stiffness as ROSS bearings: examples/rotordynamics, imports ROSS lazily).
"""
