"""Abstract syntax of UML/P statecharts as MontiCore writes them (``.sc``).

One frozen dataclass per production of MontiCore's ``UMLStatecharts`` grammar, named after
it (``SCState``, ``SCTransition``, …), and one per production of the Java expressions and
statements the grammar uses (prefixed ``J``). Source positions take no part in equality, so
a model printed and parsed again compares equal to the original; the Java parts keep what
the syntax tree of MontiCore keeps (brackets, literal texts), so they print back as written.

The Java parts are opaque to LightRocks: they are checked (types of guards and invariants),
printed and drawn, and translated to LightRocks expressions and statements where LightRocks
has the construct (:mod:`languages.umlp.java_to_lr`); a generator never runs them.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from lightrocks.metamodel.ast import NOWHERE, DomainUnit, Position

# --- Java types (MCBasicTypes) ------------------------------------------------------------


@dataclass(frozen=True)
class MCType:
    """A type: a qualified name with optional generic arguments and array dimensions; the
    wildcard ``?`` is an ``MCType`` named ``?``."""

    name: str
    arguments: tuple[MCType, ...] = ()
    dimensions: int = 0
    position: Position = field(default=NOWHERE, compare=False, repr=False)


VOID = MCType("void")


# --- Java expressions ---------------------------------------------------------------------


@dataclass(frozen=True)
class JLiteral:
    """A literal as written: ``kind`` is null, boolean, char, string or number."""

    kind: str
    text: str
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class JName:
    name: str
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class JFieldAccess:
    target: JExpression
    name: str
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class JCall:
    target: JExpression
    arguments: tuple[JExpression, ...]
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class JArrayAccess:
    target: JExpression
    index: JExpression
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class JPostfix:
    """``x++`` or ``x--``."""

    operator: str
    operand: JExpression
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class JPrefix:
    """``++x``, ``--x``, ``+x``, ``-x``, ``!x`` or ``~x``."""

    operator: str
    operand: JExpression
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class JBinary:
    operator: str
    left: JExpression
    right: JExpression
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class JConditional:
    condition: JExpression
    then: JExpression
    otherwise: JExpression
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class JAssignment:
    """``target op value`` for ``=``, ``+=``, ``-=`` and the other compound operators."""

    operator: str
    target: JExpression
    value: JExpression
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class JBracket:
    """``(expression)``: kept, as MontiCore keeps its BracketExpression."""

    expression: JExpression
    position: Position = field(default=NOWHERE, compare=False, repr=False)


JExpression = (
    JLiteral
    | JName
    | JFieldAccess
    | JCall
    | JArrayAccess
    | JPostfix
    | JPrefix
    | JBinary
    | JConditional
    | JAssignment
    | JBracket
)


# --- Java statements ----------------------------------------------------------------------


@dataclass(frozen=True)
class JBlock:
    statements: tuple[JStatement, ...]
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class JDeclarator:
    """``name[]… = init`` of a local variable; ``init`` an expression or a ``JArrayInit``."""

    name: str
    dimensions: int = 0
    init: JExpression | JArrayInit | None = None
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class JArrayInit:
    values: tuple[JExpression | JArrayInit, ...]
    trailing_comma: bool = False
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class JLocalVariable:
    """``final Type a = 1, b;`` (without the ``;`` when it initialises a for loop)."""

    modifiers: tuple[str, ...]
    type: MCType
    declarators: tuple[JDeclarator, ...]
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class JExpressionStatement:
    expression: JExpression
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class JIf:
    condition: JExpression
    then: JStatement
    otherwise: JStatement | None = None
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class JWhile:
    condition: JExpression
    body: JStatement
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class JDoWhile:
    body: JStatement
    condition: JExpression
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class JFor:
    """``for (init; condition; updates)``: ``init`` a local variable or expressions."""

    init: JLocalVariable | tuple[JExpression, ...] | None
    condition: JExpression | None
    updates: tuple[JExpression, ...]
    body: JStatement
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class JForEach:
    modifiers: tuple[str, ...]
    type: MCType
    name: str
    iterable: JExpression
    body: JStatement
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class JSwitchLabel:
    """``case value:`` or, with ``value`` None, ``default:``."""

    value: JExpression | None
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class JSwitchGroup:
    labels: tuple[JSwitchLabel, ...]
    statements: tuple[JStatement, ...]
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class JSwitch:
    value: JExpression
    groups: tuple[JSwitchGroup, ...]
    labels: tuple[JSwitchLabel, ...] = ()  # labels after the last group
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class JJump:
    """``break;`` or ``continue;``."""

    keyword: str
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class JReturn:
    value: JExpression | None = None
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class JEmpty:
    """``;``"""

    position: Position = field(default=NOWHERE, compare=False, repr=False)


JStatement = (
    JBlock
    | JLocalVariable
    | JExpressionStatement
    | JIf
    | JWhile
    | JDoWhile
    | JFor
    | JForEach
    | JSwitch
    | JJump
    | JReturn
    | JEmpty
)


# --- statecharts ----------------------------------------------------------------------------


@dataclass(frozen=True)
class StereoValue:
    """One value of a stereotype: ``name`` or ``name="content"`` (the literal as written)."""

    name: str
    content: str | None = None
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class SCEvent:
    """The stimulus of a transition: a qualified name, with ``arguments`` None when written
    without parentheses (``close``) and a tuple when with them (``close()``)."""

    name: str
    arguments: tuple[JExpression, ...] | None = None
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class SCActionBody:
    """An action (SCABody): one block statement and, in the modelling variant, a
    postcondition; both optional (``Closed -> Opened open(false) / ;``)."""

    statement: JStatement | None = None
    post: JExpression | None = None
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class SCAction:
    """``entry / …``, ``exit / …`` or ``do / …``."""

    kind: str
    body: SCActionBody
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class SCTransition:
    """``Source -> Target [pre] event / action [post];`` (``action`` None: no ``/``)."""

    source: str
    target: str
    pre: JExpression | None = None
    event: SCEvent | None = None
    action: SCActionBody | None = None
    stereotype: tuple[StereoValue, ...] = ()
    position: Position = field(default=NOWHERE, compare=False, repr=False)
    source_position: Position = field(default=NOWHERE, compare=False, repr=False)
    target_position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class SCInternTransition:
    """``-> [pre] event / action [post];`` inside a state."""

    pre: JExpression | None = None
    event: SCEvent | None = None
    action: SCActionBody | None = None
    stereotype: tuple[StereoValue, ...] = ()
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class SCCompleteness:
    """``(c)``: the list is complete; ``(...)``: it is not."""

    complete: bool
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class SCState:
    """``<<s>> initial final {ante} state Name [invariant] { … };``: ``ante`` None without
    an ante block, ``body`` None without braces."""

    name: str
    initial: bool = False
    final: bool = False
    stereotype: tuple[StereoValue, ...] = ()
    ante: tuple[JStatement, ...] | None = None
    invariant: JExpression | None = None
    body: tuple[SCElement, ...] | None = None
    position: Position = field(default=NOWHERE, compare=False, repr=False)
    name_position: Position = field(default=NOWHERE, compare=False, repr=False)
    body_position: Position = field(
        default=NOWHERE, compare=False, repr=False
    )  # the '{' of the body, for comments
    ante_position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class SCFuncEventParameter:
    type: MCType
    name: str
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class SCFuncEventDef:
    """``event ReturnType? name(Type p, …);`` (``return_type`` None when omitted)."""

    name: str
    return_type: MCType | None = None
    parameters: tuple[SCFuncEventParameter, ...] = ()
    position: Position = field(default=NOWHERE, compare=False, repr=False)


SCElement = SCState | SCTransition | SCInternTransition | SCAction | SCCompleteness | SCFuncEventDef


@dataclass(frozen=True)
class SCStatechart:
    """A named (``name`` not empty) or unnamed statechart, written ``statechart`` or
    ``automaton``."""

    name: str
    elements: tuple[SCElement, ...]
    stereotype: tuple[StereoValue, ...] = ()
    keyword: str = "statechart"
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class MCImportStatement:
    name: str
    star: bool = False
    position: Position = field(default=NOWHERE, compare=False, repr=False)


@dataclass(frozen=True)
class SCArtifact(DomainUnit):
    """One ``.sc`` file: an optional package, Java imports and one statechart.

    To the workbench a UML/P file is a unit that declares nothing: a ``DomainUnit`` whose
    ``imports`` (the models it imports) and ``declarations`` are empty, so the passes of
    the other languages over every loaded unit pass over it, and a ``.sc`` chart and the
    ``.lr`` chart converted from it can stand side by side. Its own content is in
    :attr:`statechart` and :attr:`type_imports` (the imports of Java types)."""

    statechart: SCStatechart | None = None
    type_imports: tuple[MCImportStatement, ...] = ()


def artifact(
    package: str,
    type_imports: tuple[MCImportStatement, ...],
    statechart: SCStatechart,
    file: str = "",
    package_position: Position = NOWHERE,
) -> SCArtifact:
    """A ``.sc`` unit."""
    return SCArtifact(
        package,
        (),
        (),
        file,
        package_position,
        statechart=statechart,
        type_imports=type_imports,
    )


def states(elements: tuple[SCElement, ...] | None) -> list[SCState]:
    """Every state among ``elements`` and below them, in source order (the state space of
    UML/P is flat: every state is visible from everywhere in its statechart)."""
    found: list[SCState] = []
    for element in elements or ():
        if isinstance(element, SCState):
            found.append(element)
            found += states(element.body)
    return found
