"""The pythonfmu edition of the FMUs: one slave class per FMU, grouped like ``physics/``
(``roller_guide``, ``ball_guides``, ``wear``, ``rigs``), each a declaration of its variables plus a
call into its physics. Beside the groups, the machinery every FMU shares: ``base`` (the slave base
class: registration, checks, outputs, state), ``runtime`` (the pythonfmu runtime an FMU runs
on), ``units`` and ``registry`` (finds every FMU class). Building the .fmu files is
:mod:`guideway_fmu.fmu_build`.
"""
