"""Native FMUs: each component's Python definition translated to C, compiled, no Python inside.

Mechanism (one for every FMU): the physics and the component methods are written once, in the
Python edition; :mod:`.translate` reads their syntax trees and writes C for the subset the
physics uses (numbers, tuples, objects and dicts of known shape, calls inlined, loops,
branches, raise with the Python message), typed by example: a component built at its start
values fixes the shape of everything it holds. A SymPy or CasADi route would need the physics
rewritten as expressions (and loses its branches, substep loops and error messages); a C core
called from Python would make the readable edition C. The FMI layer (:file:`fmi2_slave.c`) is
written once for every native FMU; :mod:`.component` writes a component's unit and
:mod:`.build` compiles and packs it.
"""

#: a native FMU's modelDescription generationTool: this, then its code hash (native/build.py
#: writes it, fmu_build.build.built_edition reads it)
GENERATION_TOOL = "guideway-fmu native edition"

#: the components whose native edition is built and tested against the Python edition
COMPONENTS = ("HorizontalRig", "FrictionCoulomb", "FrictionStribeck", "FrictionDahl",
              "ContactDryHertz", "VerticalDynamics", "FeedKinematics", "ContactEHL",
              "FrictionPositionDependent", "FrictionBallToBall", "FrictionPreloadLoss",
              "MillingForce", "FeedUnitErrors", "BallCarriage5DOF")

#: components that stay Python-only by design, and why (the others are not translated yet:
#: docs/native.md quotes the translator's refusal for each)
PYTHON_ONLY = {
    "FrictionMixedEHL": "its Greenwood-Tripp functions are SciPy's parabolic cylinder functions "
                        "(series and asymptotic expansions chosen by range), which C's library "
                        "lacks: unlike the elliptic integrals (a few lines of the arithmetic-"
                        "geometric mean), a C edition would be a second special-function library",
    "ForceTable": "it reads a CSV file named by a parameter when the model is built",
    "Wear": "it integrates the wear along the running distance with SciPy's adaptive solve_ivp "
            "(RK45 with error control): a C edition would need that integrator written a second "
            "time",
}
