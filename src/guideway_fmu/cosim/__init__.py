"""The co-simulation master: scenarios (read, built, written), algorithms, observers, the run."""
from .algorithms import ALGORITHMS, Algorithm
from .master import Result, SimulationError, simulate
from .observers import Observer
from .system import Builder, ScenarioError, System, dump, load

__all__ = ["ALGORITHMS", "Algorithm", "Builder", "Observer", "Result", "ScenarioError",
           "SimulationError", "System", "dump", "load", "simulate"]
