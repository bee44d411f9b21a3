"""The blocks of one IEC 61131-3 compilation unit, as the SFC and PLCopen targets write them.

The unit builder (:mod:`.unit`) fills these records from the resolved components; the
``.st`` templates and the PLCopen document read them, so both exports mean the same.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from lightrocks.languages.lightrocks.model import Component


@dataclass
class Variable:
    name: str
    type: str
    initial: str = ""
    comment: str = ""


@dataclass
class Step:
    name: str
    initial: bool = False
    actions: list[tuple[str, str]] = field(default_factory=list)  # (action, qualifier)


@dataclass
class Transition:
    name: str
    source: str
    target: str
    condition: str
    priority: int | None = None
    sources: list[str] = field(default_factory=list)  # a simultaneous convergence
    targets: list[str] = field(default_factory=list)  # a simultaneous divergence


@dataclass
class Action:
    name: str
    body: list[str]


@dataclass
class Block:
    """A FUNCTION_BLOCK: a device interface (``body``) or a component's SFC network."""

    name: str
    comment: str
    inputs: list[Variable] = field(default_factory=list)
    outputs: list[Variable] = field(default_factory=list)
    in_outs: list[Variable] = field(default_factory=list)
    externals: list[Variable] = field(default_factory=list)
    locals: list[Variable] = field(default_factory=list)
    body: list[str] = field(default_factory=list)
    steps: list[Step] = field(default_factory=list)
    transitions: list[Transition] = field(default_factory=list)
    actions: list[Action] = field(default_factory=list)
    # for callers: LightRocks name -> ST name
    parameters: dict[str, str] = field(default_factory=dict)
    outcomes: dict[str, str] = field(default_factory=dict)
    commands: dict[str, tuple[str, dict[str, str], str]] = field(default_factory=dict)
    members: dict[str, str] = field(default_factory=dict)
    # what a step stands for: ST step -> (state path in the block, outcome taken or "")
    states: dict[str, tuple[str, str]] = field(default_factory=dict)
    instances: dict[str, str] = field(default_factory=dict)  # instance -> hosting state path
    events: dict[str, str] = field(default_factory=dict)  # LightRocks event -> input
    regions: list[str] = field(default_factory=list)  # state paths of orthogonal regions


@dataclass
class TypeDeclaration:
    name: str
    alias: str = ""
    fields: list[Variable] = field(default_factory=list)


@dataclass
class Unit:
    """Everything one ``.st`` file holds."""

    top: Component
    types: list[TypeDeclaration]
    devices: list[Block]
    blocks: list[Block]
    globals: list[Variable]
    object_fields: list[Variable]
    program: Block
    instance: str
    configuration: str
    resource: str
    task: str
    cell: dict[str, str] = field(default_factory=dict)  # device or object -> its global
