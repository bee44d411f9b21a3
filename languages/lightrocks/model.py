"""The resolved model of LightRocks components: extension applied, references resolved.

A :class:`Region` is the content of a statechart or of a composite state: parameters,
start/end conditions, states, transitions and actions. ``<<extends>>`` merges the base's
region under the derived one (same name or same source and stimulus overrides);
``<<import>>`` makes a state an instance of another component. Everything here is built
once per check and shared by the CoCos and the generators.

It is also the one place the language's derived facts are defined: the layers and which
layer may use which, where each stereotype takes effect, the built-in outcomes, an action's
command budget, the cell a statechart runs in, and what each element reads and writes
(:mod:`~lightrocks.languages.lightrocks.access`). CoCos, generators, the studio and the
language server ask it (``tests/languages/test_semantic_model.py`` fails on a second
definition).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

from lightrocks.languages.lightrocks.access import Accesses, assigned, names_of
from lightrocks.metamodel import ast
from lightrocks.metamodel.units import seconds
from lightrocks.runtime import DEFAULT_BUDGET
from lightrocks.workbench.diagnostics import Diagnostics, did_you_mean
from lightrocks.workbench.workspace import Loaded, Symbol, Workspace

# -- the language's facts -------------------------------------------------------------------

LAYERS = ("task", "skill", "action")
"""The layer stereotypes of a component, highest first."""
MAY_USE: dict[str, tuple[str, ...]] = {
    "task": ("task", "skill"),
    "skill": ("skill", "action"),
    "action": (),
}
"""The layers a component of each layer may import as child states."""
BUILTIN_OUTCOMES = ("error", "timeout", "preempted")
"""Outcomes every child state can end with besides its own: a fault, a spent budget, a
preemption."""
REFERENCE_STEREOTYPES = ("import", "extends")
"""The stereotypes whose value names another statechart."""
COMPONENT_STEREOTYPES = (*LAYERS, *REFERENCE_STEREOTYPES)
"""The stereotypes that make a statechart a LightRocks component rather than a plain one."""


@dataclass(frozen=True)
class StereotypeRule:
    """Where a known stereotype takes effect (``statechart``, ``state``, ``device``,
    ``cell``), and the hint when it stands anywhere else."""

    places: frozenset[str]
    belongs: str = "remove it"


STEREOTYPES: dict[str, StereotypeRule] = {
    **{layer: StereotypeRule(frozenset({"statechart"})) for layer in LAYERS},
    "extends": StereotypeRule(frozenset({"statechart", "state"})),
    "import": StereotypeRule(frozenset({"state"}), "<<import>> belongs on a state"),
    "timeout": StereotypeRule(
        frozenset({"statechart", "device"}), "a time budget belongs on a statechart or a device"
    ),
    "concurrent": StereotypeRule(frozenset({"device"}), "<<concurrent>> belongs on a device"),
    "scene": StereotypeRule(frozenset({"cell"}), "a scene belongs on a cell"),
}
"""Every known stereotype: ``timeout`` on a statechart is an action's command budget, and
bounds a skill, task or plain statechart as a whole."""


def may_use(layer: str | None, child: str | None) -> bool:
    """A component of ``layer`` may import one of ``child``; a plain statechart (no layer)
    imports plain ones."""
    if layer is None:
        return child is None
    return child in MAY_USE.get(layer, ())


def takes_effect(stereotype: str, place: str) -> bool:
    """``<<stereotype>>`` changes something where it is written on a ``place``."""
    rule = STEREOTYPES.get(stereotype)
    return rule is not None and place in rule.places


@dataclass(frozen=True)
class Budget:
    """An action's command budget in seconds and the ``<<timeout>>`` it comes from (None:
    the default)."""

    seconds: float
    stereotype: ast.Stereotype | None = None


def visible_cells(workspace: Workspace, loaded: Loaded) -> list[Symbol]:
    """The cells a file sees, in the order of its scope: their devices and objects are the
    environment of its statecharts."""
    return [s for s in workspace.scope(loaded).values() if isinstance(s.node, ast.Cell)]


def running_cell(workspace: Workspace, loaded: Loaded) -> Symbol | None:
    """The cell a file's statechart runs in: the first it sees by qualified name."""
    return min(visible_cells(workspace, loaded), key=lambda s: s.qualified_name, default=None)


def _duration(stereotype: ast.Stereotype | None) -> float | None:
    """A ``<<timeout>>`` in seconds; None for none, or for one LR0501 refuses."""
    return seconds(stereotype.value) if stereotype is not None else None


# -- the resolved model ---------------------------------------------------------------------


@dataclass
class StateInfo:
    state: ast.State
    imported: Component | None = None
    region: Region | None = None

    @property
    def name(self) -> str:
        return self.state.name

    @property
    def outcomes(self) -> tuple[str, ...] | None:
        """Outcomes this state can end with, or None for a simple state left by events."""
        if self.imported is not None:
            return self.imported.region.outcomes
        if self.region is not None and self.region.outcomes:
            return self.region.outcomes
        return None


@dataclass
class Region:
    name: str
    position: ast.Position
    loaded: Loaded
    parameters: dict[str, ast.Parameter] = field(default_factory=dict)
    conditions: dict[str, ast.Condition] = field(default_factory=dict)
    states: dict[str, StateInfo] = field(default_factory=dict)
    transitions: list[ast.Transition] = field(default_factory=list)
    pseudostates: dict[str, ast.Pseudostate] = field(default_factory=dict)
    internal: list[ast.InternalTransition] = field(default_factory=list)
    events: dict[str, ast.Event] | None = None  # declared events (top region only)
    actions: list[ast.Action] = field(default_factory=list)
    invariants: list[ast.Invariant] = field(default_factory=list)
    properties: list[ast.Property] = field(default_factory=list)
    """What every run guarantees (``lightrocks verify``), inherited ones first."""
    extensions: list[object] = field(default_factory=list)
    """Elements of language extensions (workbench.extensions), inherited ones first."""
    parent: Region | None = None
    orthogonal: bool = False  # its states are regions, active together

    @property
    def start_conditions(self) -> list[ast.Condition]:
        return [c for c in self.conditions.values() if c.kind == "start"]

    @property
    def end_conditions(self) -> list[ast.Condition]:
        return [c for c in self.conditions.values() if c.kind == "end"]

    @property
    def outcomes(self) -> tuple[str, ...]:
        """End conditions and final states; when all regions of an orthogonal state are
        final it completes with the final state of its first region."""
        ends = tuple(c.name for c in self.end_conditions)
        if self.orthogonal:
            first = next(iter(self.states.values()), None)
            inner = first.region if first is not None else None
            return ends + (inner.outcomes if inner is not None else ())
        return ends + tuple(s.name for s in self.states.values() if s.state.is_final)

    def regions(self) -> list[Region]:
        """This region and every composite-state region inside it, depth first."""
        found = [self]
        for info in self.states.values():
            if info.region is not None:
                found += info.region.regions()
        return found


@dataclass(frozen=True)
class Touch:
    """A variable an element of a region writes, or one its guards, conditions and invariants
    test, named as the region's statechart names it."""

    path: str
    writes: bool
    node: object
    """The statement that writes it or the expression that tests it, as written."""
    at: ast.Position
    """Where in the region: the node's position, or the state importing the child it is in."""
    child: str = ""
    """The importing state of the region the node is in ("" for the region's own)."""


@dataclass
class Component:
    """One statechart with its extension resolved."""

    qualified_name: str
    unit: ast.StatechartUnit
    loaded: Loaded
    region: Region
    base: Component | None = None

    @property
    def statechart(self) -> ast.Statechart:
        return self.unit.statechart

    @property
    def name(self) -> str:
        return self.statechart.name

    @cached_property
    def access(self) -> Accesses:
        """What each element of this statechart reads and writes
        (:mod:`~lightrocks.languages.lightrocks.access`), computed once per element."""
        return Accesses()

    @cached_property
    def assigned(self) -> frozenset[str]:
        """The parameters (a plain statechart's variables) some assignment of the chart
        writes: they are not constant."""
        return assigned(self.statechart)

    def touches(self, region: Region) -> tuple[Touch, ...]:
        """What ``region`` of this statechart, the states inside it and the statecharts they
        import write, and what their guards, conditions and invariants test: a child's
        ``Object`` parameters become the names bound to them; its other parameters are its
        own copies (and an ``Object`` parameter bound to no name is no object known here),
        so what it does with them touches nothing of this statechart."""
        found = self._touches.get(id(region))
        if found is None:
            found = self._touches[id(region)] = tuple(self._touching(region))
        return found

    @cached_property
    def _touches(self) -> dict[int, tuple[Touch, ...]]:
        return {}

    def _touching(self, region: Region) -> list[Touch]:
        found: list[Touch] = []
        for inner in region.regions():
            for node, writes in _touching_nodes(inner):
                done = self.access(node)
                paths = done.writes if writes else done.reads
                found += [Touch(p, writes, node, node.position) for p in sorted(paths)]
            for info in inner.states.values():
                child = info.imported
                if child is None:
                    continue
                bound = _bound_objects(child, info.state)
                for touch in child.touches(child.region):
                    path = _renamed(touch.path, child.region.parameters, bound)
                    if path is not None:
                        found.append(
                            Touch(path, touch.writes, touch.node, info.state.position, info.name)
                        )
        return found

    @cached_property
    def layers(self) -> list[ast.Stereotype]:
        return [s for s in self.statechart.stereotypes if s.name in LAYERS]

    @property
    def layer(self) -> str | None:
        layers = self.layers
        if layers:
            return layers[0].name
        return self.base.layer if self.base is not None else None

    @property
    def budget(self) -> ast.Stereotype | None:
        """The ``<<timeout>>`` of this statechart or of the one it extends: an action's
        command budget, the time a skill, task or plain statechart may take as a whole."""
        found = ast.stereotype(self.statechart.stereotypes, "timeout")
        if found is None and self.base is not None:
            return self.base.budget
        return found

    @property
    def time_budget(self) -> float | None:
        """:attr:`budget` in seconds; None without one (or with one LR0501 refuses)."""
        return _duration(self.budget)

    def command_budget(self, device: ast.Device | None) -> Budget:
        """An action's command budget: its own ``<<timeout>>`` (or the one of the action it
        extends), else its device's, else :data:`DEFAULT_BUDGET`."""
        own = self.time_budget
        if own is not None:
            return Budget(own, self.budget)
        written = ast.stereotype(device.stereotypes, "timeout") if device is not None else None
        found = _duration(written)
        if found is not None:
            return Budget(found, written)
        return Budget(DEFAULT_BUDGET)


class ModelSet:
    """All components of a workspace, built on demand and cached by qualified name."""

    def __init__(self, workspace: Workspace, diagnostics: Diagnostics) -> None:
        self.workspace = workspace
        self.diagnostics = diagnostics
        self._components: dict[str, Component | None] = {}
        self._building: set[str] = set()
        self._references: list[tuple[str, str, str, ast.Position]] = []

    @property
    def components(self) -> list[Component]:
        """The components CoCos report on (see ``Workspace.checked_units``)."""
        self._build_all()
        targets = self.workspace.targets
        return [
            c
            for c in self._components.values()
            if c is not None and (targets is None or c.loaded.path in targets)
        ]

    @property
    def references(self) -> list[tuple[str, str, str, ast.Position]]:
        """Every ``<<import>>``/``<<extends>>`` edge: (source, target, kind, where)."""
        self._build_all()
        return self._references

    def _build_all(self) -> None:
        """Build every checked statechart; building records its references."""
        for loaded in self.workspace.checked_units():
            if isinstance(loaded.unit, ast.StatechartUnit):
                self.component(_qualified(loaded.unit))

    def component(self, qualified_name: str) -> Component | None:
        if qualified_name in self._components:
            return self._components[qualified_name]
        if qualified_name in self._building:
            return None  # a cycle: reported by the cycle CoCo, broken here
        symbol = self.workspace.lookup(qualified_name)
        if symbol is None or not isinstance(symbol.node, ast.Statechart):
            return None
        self._building.add(qualified_name)
        unit = symbol.loaded.unit
        base = self._referenced(symbol.loaded, unit.statechart.stereotypes, "extends")
        region = self._region(
            unit.statechart.name,
            unit.statechart.position,
            unit.statechart.elements,
            symbol.loaded,
            base.region if base else None,
            None,
            qualified_name,
        )
        component = Component(qualified_name, unit, symbol.loaded, region, base)
        self._building.discard(qualified_name)
        self._components[qualified_name] = component
        return component

    def resolve_statechart(self, loaded: Loaded, name: str) -> Component | None:
        symbol = self.workspace.resolve(loaded, name)
        if symbol is None or not isinstance(symbol.node, ast.Statechart):
            return None
        return self.component(symbol.qualified_name)

    def _referenced(
        self, loaded: Loaded, stereotypes: tuple[ast.Stereotype, ...], kind: str, owner: str = ""
    ) -> Component | None:
        reference = ast.stereotype(stereotypes, kind)
        if reference is None:
            return None
        if not reference.value:
            self.diagnostics.error(
                reference.position, "LR0104", f"<<{kind}>> needs a statechart name"
            )
            return None
        symbol = self.workspace.resolve(loaded, reference.value)
        if symbol is None or not isinstance(symbol.node, ast.Statechart):
            candidates = [
                n
                for n, s in self.workspace.scope(loaded).items()
                if isinstance(s.node, ast.Statechart)
            ]
            self.diagnostics.error(
                reference.position,
                "LR0104",
                f"<<{kind}>> target '{reference.value}' does not resolve to a statechart",
                did_you_mean(reference.value.rpartition(".")[2], candidates),
            )
            return None
        source = owner or _qualified(loaded.unit)
        self._references.append((source, symbol.qualified_name, kind, reference.position))
        return self.component(symbol.qualified_name)

    def _region(
        self,
        name: str,
        position: ast.Position,
        elements: tuple,
        loaded: Loaded,
        base: Region | None,
        parent: Region | None,
        owner: str,
    ) -> Region:
        region = Region(name, position, loaded, parent=parent)
        inherited: dict[tuple[str, str], int] = {}
        if base is not None:
            inherited = {(t.source, t.stimulus): i for i, t in enumerate(base.transitions)}
            region.parameters.update(base.parameters)
            region.conditions.update(base.conditions)
            region.states.update(base.states)
            region.transitions.extend(base.transitions)
            region.pseudostates.update(base.pseudostates)
            region.internal.extend(base.internal)
            region.invariants.extend(base.invariants)
            region.properties.extend(base.properties)
            region.extensions.extend(base.extensions)
            region.orthogonal = base.orthogonal
            if base.events is not None:
                region.events = dict(base.events)
        own_actions: list[ast.Action] = []
        for element in _flatten(elements):
            if isinstance(element, ast.Parameter):
                region.parameters[element.name] = element
            elif isinstance(element, ast.Condition):
                region.conditions[element.name] = element
            elif isinstance(element, ast.State):
                region.states[element.name] = self._state(element, loaded, region, owner)
            elif isinstance(element, ast.Region):
                region.orthogonal = True
                state = ast.State(element.name, body=element.elements, position=element.position)
                region.states[element.name] = self._state(state, loaded, region, owner)
            elif isinstance(element, ast.Transition):
                index = inherited.pop((element.source, element.stimulus), None)
                if index is None:
                    region.transitions.append(element)
                else:  # same source and stimulus as an inherited one: it overrides it
                    region.transitions[index] = element
            elif isinstance(element, ast.Pseudostate):
                region.pseudostates[element.name] = element
            elif isinstance(element, ast.InternalTransition):
                region.internal.append(element)
            elif isinstance(element, ast.EventBlock):
                region.events = region.events or {}
                region.events.update((e.name, e) for e in element.events)
            elif isinstance(element, ast.Action):
                own_actions.append(element)
            elif isinstance(element, ast.Invariant):
                region.invariants.append(element)
            elif isinstance(element, ast.Property):
                region.properties.append(element)
            else:
                region.extensions.append(element)
        overridden = {a.kind for a in own_actions}
        inherited = [a for a in (base.actions if base else []) if a.kind not in overridden]
        region.actions = inherited + own_actions
        return region

    def _state(self, state: ast.State, loaded: Loaded, parent: Region, owner: str) -> StateInfo:
        info = StateInfo(state)
        info.imported = self._referenced(loaded, state.stereotypes, "import", owner)
        base = self._referenced(loaded, state.stereotypes, "extends", owner)
        if state.body is not None or base is not None:
            info.region = self._region(
                state.name,
                state.position,
                state.body or (),
                loaded,
                base.region if base else None,
                parent,
                owner,
            )
        return info


def _touching_nodes(region: Region) -> list[tuple[object, bool]]:
    """The region's own statements (True: they write) and tests (False: they read)."""
    found: list[tuple[object, bool]] = []
    for transition in [*region.transitions, *region.internal]:
        found += [(transition.guard, False)] if transition.guard is not None else []
        found += [(s, True) for s in transition.action or ()]
    found += [(c.expression, False) for c in region.conditions.values() if c.expression]
    found += [(i.expression, False) for i in region.invariants]
    found += [(i.state.invariant, False) for i in region.states.values() if i.state.invariant]
    found += [(s, True) for a in region.actions for s in a.statements]
    return found


def _bound_objects(child: Component, state: ast.State) -> dict[str, str]:
    """The child's parameters bound to a name or attribute path by the importing state."""
    names = list(child.region.parameters)
    bound: dict[str, str] = {}
    for index, argument in enumerate(state.arguments):
        key = argument.name or (names[index] if index < len(names) else "")
        chain = names_of(argument.value)
        if chain is not None:
            bound[key] = ".".join(chain)
    return bound


def _renamed(path: str, parameters: dict[str, ast.Parameter], bound: dict[str, str]) -> str | None:
    """A child's path in the importing statechart's names; None for one of its own."""
    head, dot, rest = path.partition(".")
    if head not in parameters:
        return path
    if parameters[head].type != "Object" or head not in bound:
        return None
    return bound[head] + dot + rest


def _flatten(elements: tuple) -> list:
    flat: list = []
    for element in elements:
        if isinstance(element, ast.ParameterBlock):
            flat.extend(element.parameters)
        else:
            flat.append(element)
    return flat


def _qualified(unit: ast.StatechartUnit) -> str:
    name = unit.statechart.name
    return f"{unit.package}.{name}" if unit.package else name
