"""Building the FMU files: ``build`` (pythonfmu, a private copy of the code per FMU, the
modelDescription completed, fmus/README.md), ``cache`` (each FMU built once per code, the
commands' default FMU folder), the fixes of pythonfmu 0.7's Linux binary (``exit_patch``: safe
at process exit; ``error_patch``: a Python exception is fmi2Error, the instance kept;
``uri_patch``: the resource URI decoded; ``elf``: what they read of the binary), ``host_env``
(the environment a C host needs) and ``c_host.c`` (a minimal C host that checks it).
"""

#: how an FMU runs: "python" (pythonfmu, in the host's Python) or "native" (compiled C,
#: fmu_build/native, where the component has a native edition); here, where the command line
#: reads it without loading the builders
EDITIONS = ("python", "native")
