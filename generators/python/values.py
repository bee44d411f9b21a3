"""Model types and values as Python: annotations, the zero a value starts from, the kinds of
run parameters, safe ranges, and durations of stereotypes."""

from __future__ import annotations

from lightrocks.generators.python.views import tuple_code
from lightrocks.languages.domain.ranges import Range
from lightrocks.languages.domain.types import (
    BOOLEAN,
    FRAME,
    STRING,
    ObjectT,
    QuantityT,
    StructT,
    Type,
    VectorT,
)
from lightrocks.metamodel import ast


def python_type(t: Type | None) -> str:
    """The annotation of a value of model type ``t`` (SI floats, frames, tuples)."""
    if isinstance(t, QuantityT):
        return "int" if t.name == "Integer" else "float"
    if t == BOOLEAN:
        return "bool"
    if t == STRING:
        return "str"
    if t == FRAME:
        return "rt.Frame"
    if isinstance(t, ObjectT):
        return "rt.SceneObject"
    if isinstance(t, VectorT):
        return "tuple[" + ", ".join(python_type(e) for e in t.elements) + "]"
    if isinstance(t, StructT):
        if t.name == "Wrench":
            return "rt.Wrench"
        if {n for n, _ in t.fields} == {"x", "y", "z"}:
            return "rt.Vector3"
    return "Any"


def zero_value(t: Type | None) -> str | None:
    """What an attribute without default starts as: zero, false or empty, as a PLC
    variable starts; None for a type without such a value."""
    if isinstance(t, QuantityT):
        return "0" if t.name == "Integer" else "0.0"
    if t == BOOLEAN:
        return "False"
    if t == STRING:
        return "''"
    if t == FRAME:
        return "rt.Frame.Identity()"
    if isinstance(t, VectorT):
        elements = [zero_value(e) for e in t.elements]
        return None if None in elements else "(" + "".join(f"{e}, " for e in elements) + ")"
    return None


def value_type(t: Type | None) -> tuple:
    """What a run parameter of model type ``t`` accepts, as plain data for the generated
    class (``PARAMETER_TYPES``): kind, type name, and the dimension exponents of its
    numbers (one for a quantity, one per element for a vector)."""
    if isinstance(t, QuantityT):
        kind = "integer" if t.name == "Integer" else "quantity"
        return (kind, t.name, (t.dimension.exponents,))
    if isinstance(t, VectorT) and all(isinstance(e, QuantityT) for e in t.elements):
        return ("vector", t.name, tuple(e.dimension.exponents for e in t.elements))
    if t == BOOLEAN:
        return ("boolean", "Boolean", ())
    if t == STRING:
        return ("string", "String", ())
    return ("other", str(t), ())


def safe_range(safe: Range) -> str | None:
    """A declared safe range as generated code (``rt.SafeRange``); None when not constant."""
    bounds = safe.elements()
    if not bounds:
        return None
    shown = tuple_code(
        f"rt.Bound({lo!r}, {hi!r}, {unit!r}, {factor!r})" for lo, hi, unit, factor in bounds
    )
    return f"rt.SafeRange({safe.device!r}, {safe.command!r}, {safe.argument!r}, {shown})"


def stereotype_value(stereotypes: tuple[ast.Stereotype, ...], name: str) -> str | None:
    found = ast.stereotype(stereotypes, name)
    return found.value if found else None
