"""Building the FMU files: ``build`` (pythonfmu, a private copy of the code per FMU, the
modelDescription completed, fmus/README.md), ``cache`` (each FMU built once per code, the
commands' default FMU folder), ``exit_patch`` (pythonfmu 0.7's binary made safe at
process exit), ``host_env`` (the environment a C host needs) and ``c_host.c`` (a minimal C host
that checks it).
"""
