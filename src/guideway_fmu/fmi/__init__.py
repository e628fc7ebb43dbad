"""FMU files themselves, below both the build (fmu_build/) and the master (cosim/): ``archive``
(an FMU's zip entries checked, rewritten, its start values baked in)."""
