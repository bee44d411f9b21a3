"""Static types of LightRocks expressions, with dimensions for quantities.

``UNKNOWN`` stands for anything that could not be typed (an unresolved name, say): it is
compatible with every type so that one mistake yields one finding, not a cascade.
"""

from __future__ import annotations

from dataclasses import dataclass

from lightrocks.metamodel import ast
from lightrocks.metamodel.units import ANGLE, LENGTH, ONE, Dimension, UnitError, lookup
from lightrocks.workbench.languages import implicit_packages
from lightrocks.workbench.workspace import Loaded, Symbol, Workspace


@dataclass(frozen=True)
class Type:
    name: str

    def __str__(self) -> str:
        return self.name


@dataclass(frozen=True)
class QuantityT(Type):
    dimension: Dimension = ONE


@dataclass(frozen=True)
class VectorT(Type):
    elements: tuple[Type, ...] = ()


@dataclass(frozen=True)
class StructT(Type):
    fields: tuple[tuple[str, Type], ...] = ()

    def field(self, name: str) -> Type | None:
        return dict(self.fields).get(name)


@dataclass(frozen=True)
class DeviceT(Type):
    device: ast.Device | None = None


@dataclass(frozen=True)
class ObjectT(Type):
    """A scene object; ``attributes`` is None for a parameter bound to any object."""

    attributes: tuple[tuple[str, Type], ...] | None = None


@dataclass(frozen=True)
class CommandT(Type):
    device: ast.Device | None = None
    command: ast.Command | None = None


@dataclass(frozen=True)
class FunctionT(Type):
    pass


UNKNOWN = Type("?")
BOOLEAN = Type("Boolean")
STRING = Type("String")
FRAME = Type("Frame")
NUMBER = QuantityT("Real", ONE)
INTEGER = QuantityT("Integer", ONE)
LENGTH_T = QuantityT("Length", LENGTH)
ANGLE_T = QuantityT("Angle", ANGLE)
ANY_OBJECT = ObjectT("Object")

BUILTIN_TYPES: dict[str, Type] = {
    "Boolean": BOOLEAN,
    "String": STRING,
    "Frame": FRAME,
    "Object": ANY_OBJECT,
}

FRAME_MEMBERS: dict[str, Type] = {"x": LENGTH_T, "y": LENGTH_T, "z": LENGTH_T}

BUILTIN_FUNCTIONS = ("abs", "min", "max", "rotX", "rotY", "rotZ", "transl")


def quantity_of(literal: ast.Quantity) -> Type:
    """``3`` is an Integer; ``3.0``, ``0.5`` and ``1e3`` are Reals; ``3 mm`` a quantity."""
    if literal.integral:
        return INTEGER
    try:
        dimension = lookup(literal.unit).dimension
    except UnitError:
        return UNKNOWN
    return QuantityT(literal.unit or "Real", dimension)


def common_number(left: QuantityT, right: QuantityT) -> QuantityT:
    """The type of ``+ - * %``, ``min`` and ``max`` on two dimensionless numbers, as in Java
    and in both targets: Integer for two Integers, Real when a Real takes part. (``/``
    always divides as Real: Python's true division, REAL on the PLC.)"""
    return INTEGER if left == INTEGER and right == INTEGER else NUMBER


def compatible(expected: Type, actual: Type, literal_zero: bool = False) -> bool:
    """Whether a value of ``actual`` may stand where ``expected`` is declared."""
    if expected is UNKNOWN or actual is UNKNOWN:
        return True
    if isinstance(expected, QuantityT) and isinstance(actual, QuantityT):
        return expected.dimension == actual.dimension or literal_zero
    if isinstance(expected, VectorT) and isinstance(actual, VectorT):
        return len(expected.elements) == len(actual.elements) and all(
            compatible(e, a) for e, a in zip(expected.elements, actual.elements, strict=True)
        )
    if isinstance(expected, ObjectT) and isinstance(actual, ObjectT):
        return True
    if isinstance(expected, StructT) and isinstance(actual, StructT):
        return expected.name == actual.name
    return expected == actual


def narrows(expected: Type, actual: Type) -> bool:
    """Whether a value of ``actual`` would lose its fraction where ``expected`` is declared:
    a Real where an Integer is, also as a vector element. An Integer widens to a Real."""
    if isinstance(expected, VectorT) and isinstance(actual, VectorT):
        pairs = zip(expected.elements, actual.elements, strict=False)
        return any(narrows(e, a) for e, a in pairs)
    return expected == INTEGER and isinstance(actual, QuantityT) and actual != INTEGER


def describe(t: Type) -> str:
    if isinstance(t, QuantityT) and not t.dimension.dimensionless:
        return f"{t.name} [{t.dimension}]"
    if isinstance(t, VectorT) and t.name == "vector":
        return "[" + ", ".join(describe(e) for e in t.elements) + "]"
    return t.name


class Types:
    """Resolves type names of the domain language into :class:`Type` values."""

    def __init__(self, workspace: Workspace) -> None:
        self.workspace = workspace
        self._cache: dict[str, Type] = {}
        self._named: dict[Dimension, QuantityT] | None = None

    def resolve(self, loaded: Loaded, name: str) -> Type | None:
        if name in BUILTIN_TYPES:
            return BUILTIN_TYPES[name]
        symbol = self.workspace.resolve(loaded, name)
        return None if symbol is None else self._type_of(symbol)

    def quantity(self, dimension: Dimension) -> QuantityT:
        """The value type of a computed quantity: named after the implicit library's quantity
        type of that dimension (``Length`` for metres), else ``quantity``."""
        if self._named is None:
            self._named = {}
            for package in implicit_packages():
                for symbol in self.workspace.load_package(package).values():
                    kind = self._type_of(symbol)
                    if isinstance(kind, QuantityT):
                        self._named.setdefault(kind.dimension, kind)
        return self._named.get(dimension) or QuantityT("quantity", dimension)

    def _type_of(self, symbol: Symbol) -> Type:
        if symbol.qualified_name not in self._cache:
            self._cache[symbol.qualified_name] = UNKNOWN  # guards recursive structures
            self._cache[symbol.qualified_name] = self._build(symbol.loaded, symbol.node)
        return self._cache[symbol.qualified_name]

    def _build(self, loaded: Loaded, node: object) -> Type:
        if isinstance(node, ast.QuantityType):
            try:
                return QuantityT(node.name, lookup(node.unit).dimension)
            except UnitError:
                return UNKNOWN
        if isinstance(node, ast.VectorType):
            if node.units:
                elements = tuple(_unit_type(u) for u in node.units)
            else:
                element = self.resolve(loaded, node.element_type) or UNKNOWN
                elements = (element,) * node.size
            return VectorT(node.name, elements)
        if isinstance(node, ast.StructureType):
            fields = tuple((f.name, self.resolve(loaded, f.type) or UNKNOWN) for f in node.fields)
            return StructT(node.name, fields)
        if isinstance(node, ast.Device):
            return DeviceT(node.name, node)
        return UNKNOWN


def _unit_type(unit: str) -> Type:
    try:
        return QuantityT(unit, lookup(unit).dimension)
    except UnitError:
        return UNKNOWN
