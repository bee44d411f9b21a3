"""Types of the Java expressions of guards and invariants, as far as the chart shows them.

A UML/P statechart takes its variables and methods from the class it describes; the
workbench does not see that class (MontiCore reads it from a symbol path). So a name is of
unknown type (MontiCore's *obscure* type) unless it is a literal's, an operator's or a type
of ``java.lang`` used where a value belongs. CoCos judge a type only when it is known, as
MontiCore's ``InvariantValid`` and ``TransitionPreconditionsAreBoolean`` skip obscure types.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping

from lightrocks.languages.umlp import nodes as n

UNKNOWN = "?"
TYPE_REFERENCE = "type"  # a name of a Java type, used as a value

JAVA_LANG_TYPES = frozenset(
    {
        "Boolean",
        "Byte",
        "Character",
        "Double",
        "Float",
        "Integer",
        "Long",
        "Math",
        "Number",
        "Object",
        "Short",
        "String",
        "StringBuilder",
        "System",
        "Thread",
        "Void",
    }
)
"""Types every Java file sees without an import: a bare one of these is no value."""

_NUMERIC = ("double", "float", "long", "int", "short", "byte", "char")
_COMPARISONS = ("<", ">", "<=", ">=", "==", "!=")

Unresolved = Callable[[n.JName], None]


def number_type(text: str) -> str:
    """The type of a number literal as Java reads it."""
    lowered = text.lower()
    if lowered.startswith("0x"):
        return "long" if lowered.endswith("l") else "int"
    if lowered.endswith("l"):
        return "long"
    if lowered.endswith("f"):
        return "float"
    if lowered.endswith("d") or any(c in lowered for c in ".e"):
        return "double"
    return "int"


def _promoted(left: str, right: str) -> str:
    """Binary numeric promotion: the wider of two numeric types, at least int."""
    for kind in ("double", "float", "long"):
        if kind in (left, right):
            return kind
    return "int"


def type_of(
    node: n.JExpression,
    unresolved: Unresolved | None = None,
    names: Mapping[str, str] | None = None,
) -> str:
    """The Java type of ``node`` (``boolean``, ``int``, ``String``, …), :data:`UNKNOWN`
    where it depends on names the chart does not declare, :data:`TYPE_REFERENCE` for a
    type used as a value. ``unresolved`` is told of every name whose type is unknown;
    ``names`` gives types of names where they are known (the conversion's guesses)."""

    def infer(expression: n.JExpression) -> str:
        return type_of(expression, unresolved, names)

    match node:
        case n.JLiteral(kind="number", text=text):
            return number_type(text)
        case n.JLiteral(kind="string"):
            return "String"
        case n.JLiteral(kind="null"):
            return "null"
        case n.JLiteral(kind=kind):
            return kind  # boolean, char
        case n.JName(name=name):
            if names is not None and name in names:
                return names[name]
            if name in JAVA_LANG_TYPES:
                return TYPE_REFERENCE
            if unresolved is not None:
                unresolved(node)
            return UNKNOWN
        case n.JFieldAccess(target=target) | n.JArrayAccess(target=target):
            _root(target, unresolved)
            return UNKNOWN
        case n.JCall(target=target, arguments=arguments):
            _root(target, unresolved)
            for argument in arguments:
                infer(argument)
            return UNKNOWN
        case n.JBracket(expression=inner):
            return infer(inner)
        case n.JPostfix(operand=operand):
            return _numeric_or_unknown(infer(operand))
        case n.JPrefix(operator=operator, operand=operand):
            kind = infer(operand)
            if operator == "!":
                return "boolean" if kind in ("boolean", UNKNOWN) else UNKNOWN
            return _numeric_or_unknown(kind)
        case n.JBinary(operator=operator, left=left, right=right):
            return _binary(operator, infer(left), infer(right))
        case n.JConditional(condition=condition, then=then, otherwise=otherwise):
            infer(condition)
            first, second = infer(then), infer(otherwise)
            if first == second:
                return first
            if first in _NUMERIC and second in _NUMERIC:
                return _promoted(first, second)
            return UNKNOWN
        case n.JAssignment(target=target, value=value):
            infer(value)
            return infer(target)
    return UNKNOWN


def _root(target: n.JExpression, unresolved: Unresolved | None) -> None:
    """Report the first name of ``a.b.c`` or ``a[0]`` unless it names a ``java.lang`` type
    (``System.out``); the members of an unknown thing are unknown without a finding."""
    while isinstance(target, n.JFieldAccess | n.JArrayAccess | n.JCall):
        if isinstance(target, n.JArrayAccess | n.JCall):
            arguments = (target.index,) if isinstance(target, n.JArrayAccess) else target.arguments
            for argument in arguments:
                type_of(argument, unresolved)
        target = target.target
    if isinstance(target, n.JName):
        if target.name not in JAVA_LANG_TYPES and unresolved is not None:
            unresolved(target)
    else:
        type_of(target, unresolved)


def _numeric_or_unknown(kind: str) -> str:
    if kind in ("byte", "short", "char"):
        return "int"
    return kind if kind in _NUMERIC else UNKNOWN


def _binary(operator: str, left: str, right: str) -> str:
    if operator in ("&&", "||"):
        return "boolean"
    if operator in _COMPARISONS:
        return "boolean"
    if UNKNOWN in (left, right) or TYPE_REFERENCE in (left, right):
        return UNKNOWN
    if operator == "+" and "String" in (left, right):
        return "String"
    if operator in ("&", "|", "^") and left == right == "boolean":
        return "boolean"
    if left in _NUMERIC and right in _NUMERIC:
        if operator in ("<<", ">>", ">>>"):
            return _numeric_or_unknown(left)
        return _promoted(left, right)
    return UNKNOWN


def is_boolean(kind: str) -> bool:
    return kind in ("boolean", "Boolean")


def is_known(kind: str) -> bool:
    return kind not in (UNKNOWN, TYPE_REFERENCE)


def type_references(node: n.JExpression) -> list[n.JName]:
    """Names of ``java.lang`` types that stand where a value belongs (``[String]``,
    ``String == x``), not as the target of a member access (``System.out``)."""
    found: list[n.JName] = []

    def visit(expression: object) -> None:
        match expression:
            case n.JName(name=name) if name in JAVA_LANG_TYPES:
                found.append(expression)
            case n.JFieldAccess() | n.JArrayAccess() | n.JCall():
                target = expression
                while isinstance(target, n.JFieldAccess | n.JArrayAccess | n.JCall):
                    if isinstance(target, n.JArrayAccess):
                        visit(target.index)
                    elif isinstance(target, n.JCall):
                        for argument in target.arguments:
                            visit(argument)
                    target = target.target
                if not isinstance(target, n.JName):
                    visit(target)
            case n.JBracket(expression=inner):
                visit(inner)
            case n.JPostfix(operand=operand) | n.JPrefix(operand=operand):
                visit(operand)
            case n.JBinary(left=left, right=right):
                visit(left)
                visit(right)
            case n.JConditional(condition=c, then=t, otherwise=o):
                visit(c)
                visit(t)
                visit(o)
            case n.JAssignment(target=t, value=v):
                visit(t)
                visit(v)

    visit(node)
    return found
