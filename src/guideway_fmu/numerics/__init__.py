"""Numerical tools shared by the master, the reference, sweeps, analyses and the diagnosis:
``spectrum`` (the one amplitude spectrum and its peaks)."""
