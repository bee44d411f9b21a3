"""Which tracked attributes a configuration still needs: those its active statecharts read,
and those a statechart it may enter reads before it writes them. Forgetting every other
value (it becomes unknown) loses nothing the future depends on, and keeps the counters of a
finished skill from multiplying the configurations of the rest of the task.

A read is a pair (object, attribute); the object is a scene object, a parameter name (a
statechart's own variable, object ``""``), or ``None`` for an ``Object`` parameter whose
object is not known here: then that attribute of every object is kept. The names each
element reads and writes come from the semantic model (``Component.access``); only what
steers the flow counts here: guards, conditions, assigned values and the arguments of
imported states, not the arguments of a device command.
"""

from __future__ import annotations

from lightrocks.languages.lightrocks.access import Access
from lightrocks.languages.lightrocks.model import Component, Region
from lightrocks.metamodel import ast

Read = tuple[str | None, str]


class Liveness:
    def __init__(self) -> None:
        self._reads: dict[str, frozenset[Read]] = {}
        self._entry: dict[str, frozenset[Read]] = {}
        self._owns: dict[str, frozenset[Read]] = {}
        self._needed: dict[tuple, frozenset[Read]] = {}

    def reads(self, component: Component) -> frozenset[Read]:
        """What the statechart's own expressions read, in its own names."""
        if component.qualified_name not in self._reads:
            found: set[Read] = set()
            for region in component.region.regions():
                for expression in _read_expressions(region):
                    found |= _pairs(component.access(expression))
            self._reads[component.qualified_name] = frozenset(found)
        return self._reads[component.qualified_name]

    def live_at_entry(self, component: Component) -> frozenset[Read]:
        """What the statechart, or one it may enter, reads before writing it."""
        key = component.qualified_name
        if key not in self._entry:
            self._entry[key] = frozenset()  # a cycle of imports stops here
            found = set(self.reads(component))
            for region in component.region.regions():
                for info in region.states.values():
                    if info.imported is not None:
                        found |= _rename(self.live_at_entry(info.imported), info)
            self._entry[key] = frozenset(found - _written_first(component))
        return self._entry[key]

    def needed(
        self, active: list[tuple[Component, tuple[tuple[str, str], ...]]]
    ) -> frozenset[Read]:
        """What the active statecharts (each with the objects its parameters stand for)
        and the ones they may enter still read, in the names of the scene."""
        key = tuple((c.qualified_name, objects) for c, objects in active)
        if key not in self._needed:
            found: set[Read] = set()
            for component, objects in active:
                found |= self._scene_names(component, dict(objects))
            self._needed[key] = frozenset(found)
        return self._needed[key]

    def _scene_names(self, component: Component, objects: dict[str, str]) -> set[Read]:
        parameters = component.region.parameters
        found: set[Read] = set()
        for head, attribute in self._own(component):
            if head in objects:
                found.add((objects[head], attribute))
            elif head in parameters and parameters[head].type == "Object":
                found.add((None, attribute))
            else:
                found.add((head, attribute))
        return found

    def _own(self, component: Component) -> frozenset[Read]:
        """What a statechart and the ones it may enter read, in its own names."""
        key = component.qualified_name
        if key not in self._owns:
            found = set(self.reads(component))
            for region in component.region.regions():
                for info in region.states.values():
                    if info.imported is not None:
                        found |= _rename(self.live_at_entry(info.imported), info)
            self._owns[key] = frozenset(found)
        return self._owns[key]


def keeps(needed: frozenset[Read], path: str) -> bool:
    head, _, attribute = path.rpartition(".")
    return (head, attribute) in needed or (None, attribute) in needed


def _rename(reads: frozenset[Read], info) -> set[Read]:
    """A child's reads in the names of the state that imports it: its ``Object``
    parameters bound to a name become that name, unbound ones any object."""
    child = info.imported
    names = list(child.region.parameters)
    bound: dict[str, str] = {}
    for index, argument in enumerate(info.state.arguments):
        key = argument.name or (names[index] if index < len(names) else "")
        if isinstance(argument.value, ast.Name):
            bound[key] = argument.value.name
    parameters = child.region.parameters
    found: set[Read] = set()
    for head, attribute in reads:
        if head in bound:
            found.add((bound[head], attribute))
        elif head in parameters:
            found.add((None, attribute) if parameters[head].type == "Object" else ("", ""))
        else:
            found.add((head, attribute))
    return found


def _read_expressions(region: Region) -> list[ast.Expression]:
    found: list[ast.Expression] = []
    for transition in [*region.transitions, *region.internal]:
        found += [transition.guard] if transition.guard is not None else []
        found += [s.value for s in transition.action or () if isinstance(s, ast.Assignment)]
    found += [c.expression for c in region.conditions.values() if c.expression is not None]
    for action in region.actions:
        for statement in action.statements:
            if isinstance(statement, ast.Assignment):
                found.append(statement.value)
    for info in region.states.values():
        found += [a.value for a in info.state.arguments]
    return found


def _pairs(access: Access) -> set[Read]:
    """("", head) of every variable read, and (head, attribute) of every member path."""
    found: set[Read] = set()
    for path in access.reads:
        head, _, rest = path.partition(".")
        found.add(("", head))
        if rest:
            found.add((head, rest.partition(".")[0]))
    return found


def _written_first(component: Component) -> set[Read]:
    """Attributes every way into the statechart assigns before anything reads them."""
    region, access = component.region, component.access
    starts = region.start_conditions
    read_first: set[Read] = set()
    for condition in starts:
        read_first |= _pairs(access(condition))
    ways: list[set[Read]] = []
    for condition in starts:
        for transition in region.transitions:
            if transition.source == condition.name:
                read_first |= _pairs(access(transition.guard))
                ways.append(_assigned(component, transition.action or ()))
    entry: set[Read] = set()
    for action in region.actions:
        if action.kind == "entry":
            entry |= _assigned(component, action.statements)
    written = set.intersection(*ways) if ways else set()
    return (written | entry) - read_first


def _assigned(component: Component, statements: tuple[ast.Statement, ...]) -> set[Read]:
    """The attributes (object and attribute, no deeper) the statements write without reading
    them in the same statement."""
    found: set[Read] = set()
    for statement in statements:
        done = component.access(statement)
        for path in done.writes:
            head, _, attribute = path.partition(".")
            pair = (head, attribute)
            if attribute and "." not in attribute and pair not in _pairs(done):
                found.add(pair)
    return found
