"""Numerical tools shared by the master, the reference, sweeps, analyses and the diagnosis:
``spectrum`` (the one amplitude spectrum, its peaks, and the power spectrum)."""
