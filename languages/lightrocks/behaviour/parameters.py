"""The values a parameter takes in the loaded models: its default where a use leaves it
unbound (or nobody imports the statechart), and each constant an ``<<import>>`` binds, also
through the parameters of the statecharts that bind it. A parameter that is assigned, or
bound to a value only known at run time, may take any value (``None``)."""

from __future__ import annotations

from lightrocks.languages.lightrocks.model import Component, ModelSet, Region
from lightrocks.metamodel import ast
from lightrocks.metamodel.constants import fold

Values = frozenset[float | bool] | None


class ParameterValues:
    def __init__(self, models: ModelSet) -> None:
        self.models = models
        self._known: dict[tuple[str, str], Values] = {}
        self._sites: dict[str, list[tuple[Component, Region, ast.State]]] | None = None

    def of(self, component: Component, name: str) -> Values:
        key = (component.qualified_name, name)
        if key not in self._known:
            self._known[key] = None  # a cycle of bindings stops here
            self._known[key] = self._values(component, name)
        return self._known[key]

    def _values(self, component: Component, name: str) -> Values:
        parameter = component.region.parameters.get(name)
        if parameter is None or name in component.assigned:
            return None
        found: set[float | bool] = set()
        sites = self.sites().get(component.qualified_name, [])
        names = list(component.region.parameters)
        unbound = not sites
        for user, region, state in sites:
            bound = _binding(state, name, names)
            if bound is None:
                unbound = True
                continue
            values = self._expression(user, region, bound)
            if values is None:
                return None
            found |= values
        if unbound:
            default = _constant(parameter.default)
            if default is None:
                return None
            found.add(default)
        return frozenset(found)

    def _expression(self, user: Component, region: Region, value: ast.Expression) -> Values:
        constant = _constant(value)
        if constant is not None:
            return frozenset({constant})
        if isinstance(value, ast.Name) and _declares(region, value.name):
            return self.of(user, value.name)
        return None

    def sites(self) -> dict[str, list[tuple[Component, Region, ast.State]]]:
        """Every state that imports a statechart, by the statechart's qualified name."""
        if self._sites is None:
            self._sites = {}
            for component in self.models.components:
                for region in component.region.regions():
                    for info in region.states.values():
                        if info.imported is not None:
                            entry = (component, region, info.state)
                            self._sites.setdefault(info.imported.qualified_name, []).append(entry)
        return self._sites


def _binding(state: ast.State, name: str, names: list[str]) -> ast.Expression | None:
    for index, argument in enumerate(state.arguments):
        bound = argument.name or (names[index] if index < len(names) else "")
        if bound == name:
            return argument.value
    return None


def _declares(region: Region | None, name: str) -> bool:
    while region is not None:
        if name in region.parameters:
            return True
        region = region.parent
    return False


def _constant(expression: ast.Expression | None) -> float | bool | None:
    value = fold(expression)
    if isinstance(value, bool):
        return value
    if isinstance(value, int | float):
        return value
    return None
