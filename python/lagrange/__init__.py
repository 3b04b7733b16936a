"""lagrange from Python: models, equations, simulations and forward dynamics (docs/python.md).

A thin binding of the library the ``lagrange`` command uses: the same reader, derivation,
compiled tapes and integrators, so a run gives the numbers the command writes to its CSV.
"""

from ._lagrange import (  # noqa: F401  (the package's public API)
    AnalysisError,
    Equations,
    Model,
    ModelError,
    Run,
    SimulationError,
    Stepper,
    load,
    loads,
)
from .study import sweep  # noqa: F401

__all__ = ["AnalysisError", "Equations", "Model", "ModelError", "Run", "SimulationError", "Stepper",
           "load", "loads", "sweep"]
