"""Parameter sweeps over a scenario: the design of experiments, one co-simulation per point on
Dask workers, reduced outputs in one table, plots (docs/sweep.md)."""
