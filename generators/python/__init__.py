"""The python generator: statecharts as Python modules on :mod:`runtime`."""

from lightrocks.generators.python.generator import GENERATOR, PythonGenerator

__all__ = ["GENERATOR", "PythonGenerator"]
