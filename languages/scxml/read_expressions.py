"""SCXML conditions and values back to LightRocks expressions.

``cond`` and ``expr`` are Python (python-statemachine's data model), parsed with
:func:`ast.parse` and never evaluated; the translation undoes the target's
(:mod:`generators.scxml.expressions`): ``abs``, ``min`` and ``max`` written out as
arithmetic are recognised, and the parts of a condition that are the generator's own
(``In()`` of an outcome, history variables, the exclusions of other regions) are dropped.
A condition may also use what python-statemachine rewrites (``true``, ``&&``, ``===`` …).
"""

from __future__ import annotations

import ast as py
import re

from lightrocks.languages.scxml.read_context import EXPRESSION, ReadContext, Refused
from lightrocks.languages.scxml.xml_tree import Element
from lightrocks.metamodel import ast

_COND_WORDS = {"true": "True", "false": "False", "null": "None", "&&": "and", "||": "or"}
_COND_PATTERN = re.compile(r"\b(?:true|false|null)\b|===|!==|&&|\|\|")
_OPERATORS = {
    py.Add: "+", py.Sub: "-", py.Mult: "*", py.Div: "/", py.Mod: "%",
    py.Eq: "==", py.NotEq: "!=", py.Lt: "<", py.LtE: "<=", py.Gt: ">", py.GtE: ">=",
}  # fmt: skip


class ExpressionReader:
    """The expressions of one document; its ``<data>`` ids name the parameters."""

    def __init__(self, context: ReadContext) -> None:
        self.context = context

    def guard(self, transition: Element) -> ast.Expression | None:
        """The guard of ``transition`` (see :meth:`completion_guard`)."""
        return self._condition(transition, completion=False)[0]

    def completion_guard(self, transition: Element) -> tuple[ast.Expression | None, list[str]]:
        """The guard of a completion and the ids of the finals its ``In()`` names; the
        generator's own parts of a condition (history variables, the exclusions of other
        regions) are dropped, and ``lr:guard`` is the guard as the model wrote it where the
        condition had to read it before the exit actions."""
        return self._condition(transition, completion=True)

    def _condition(
        self, transition: Element, completion: bool
    ) -> tuple[ast.Expression | None, list[str]]:
        text = transition.get("cond")
        finals: list[str] = []
        if not text:
            return None, finals
        tree = _parse(_normalized(text), transition)
        parts = self._parts(tree)
        kept = []
        for part in parts:
            ins = _in_states(part)
            if ins is not None and completion and not finals:
                finals = ins
                continue
            if self.context.generated and (self._flag(part) or _suppressor(part)):
                continue
            kept.append(part)
        if transition.lr("guard"):
            guard = self.expression(transition.lr("guard"), transition)
        elif len(kept) == len(parts) and len(parts) > 1:
            guard = self.translated(tree, transition)
        elif kept:
            guard = self.translated(kept[0], transition)
            for part in kept[1:]:
                guard = ast.Binary("&&", guard, self.translated(part, transition))
        else:
            guard = None
        return guard, finals

    def _parts(self, tree: py.expr) -> list[py.expr]:
        """The conjuncts of a condition, the generator's own ones (``In()``, history
        variables, exclusions of other regions) taken out of the conjunctions it nests them
        in; a guard of the model stays whole."""
        if not (isinstance(tree, py.BoolOp) and isinstance(tree.op, py.And)):
            return [tree]
        found: list[py.expr] = []
        for value in tree.values:
            inner = self._parts(value)
            if len(inner) > 1 and any(self._own(p) for p in inner):
                found += inner
            else:
                found.append(value)
        return found

    def _own(self, part: py.expr) -> bool:
        return _in_states(part) is not None or (
            self.context.generated and (self._flag(part) or _suppressor(part))
        )

    def _flag(self, part: py.expr) -> bool:
        inner = (
            part.operand if isinstance(part, py.UnaryOp) and isinstance(part.op, py.Not) else part
        )
        return isinstance(inner, py.Name) and inner.id in self.context.flags

    def expression(self, text: str, element: Element) -> ast.Expression:
        return self.translated(_parse(text, element), element)

    def translated(self, node: py.expr, element: Element) -> ast.Expression:
        special = _function(node)
        if special is not None:
            name, arguments = special
            return ast.Call(
                ast.Name(name),
                tuple(ast.Argument(self.translated(a, element)) for a in arguments),
            )
        match node:
            case py.BoolOp(op=op, values=values):
                operator = "&&" if isinstance(op, py.And) else "||"
                result = self.translated(values[0], element)
                for value in values[1:]:
                    result = ast.Binary(operator, result, self.translated(value, element))
                return result
            case py.UnaryOp(op=py.Not(), operand=operand):
                return ast.Unary("!", self.translated(operand, element))
            case py.UnaryOp(op=py.USub() | py.UAdd() as op, operand=operand):
                sign = "-" if isinstance(op, py.USub) else "+"
                return ast.Unary(sign, self.translated(operand, element))
            case py.BinOp(op=op, left=left, right=right) if type(op) in _OPERATORS:
                return ast.Binary(
                    _OPERATORS[type(op)],
                    self.translated(left, element),
                    self.translated(right, element),
                )
            case py.Compare(left=left, ops=ops, comparators=comparators):
                if not all(type(o) in _OPERATORS for o in ops):
                    raise Refused(element, "a comparison LightRocks does not have (in, is)",
                                  EXPRESSION)  # fmt: skip
                terms, before = [], left
                for op, after in zip(ops, comparators, strict=True):
                    terms.append(
                        ast.Binary(
                            _OPERATORS[type(op)],
                            self.translated(before, element),
                            self.translated(after, element),
                        )
                    )
                    before = after
                result = terms[0]
                for term in terms[1:]:
                    result = ast.Binary("&&", result, term)
                return result
            case py.Constant(value=bool() as value):
                return ast.BooleanLiteral(value)
            case py.Constant(value=int() as value):
                return ast.Quantity(float(value), "", str(value))
            case py.Constant(value=float() as value) if value == value and abs(value) != float(
                "inf"
            ):
                return ast.Quantity(value, "", repr(value))
            case py.Constant(value=str() as value):
                return ast.StringLiteral(value)
            case py.Name(id=name) if name in self.context.variables:
                return ast.Name(self.context.variables[name])
            case py.Name(id=name):
                raise Refused(element, f"'{name}' is no <data> of the document", EXPRESSION)
        raise Refused(
            element,
            f"'{py.unparse(node)}' has no LightRocks counterpart (names, numbers, Booleans, "
            "strings, and, or, not, comparisons, + - * / %, abs, min, max)",
            EXPRESSION,
        )

    def invariant(self, transition: Element) -> ast.Invariant:
        text = transition.get("cond") or ""
        tree = _parse(_normalized(text), transition)
        if isinstance(tree, py.UnaryOp) and isinstance(tree.op, py.Not):
            return ast.Invariant(self.translated(tree.operand, transition))
        raise Refused(transition, "an invariant check that is not 'not (…)'")


def _normalized(text: str) -> str:
    """What python-statemachine makes of a condition: ``true``, ``false``, ``null``,
    ``&&``, ``||``, ``===`` and ``!==`` as Python."""
    replace = {**_COND_WORDS, "===": "==", "!==": "!="}
    return _COND_PATTERN.sub(lambda m: replace[m.group(0)], text)


def _parse(text: str, element: Element) -> py.expr:
    try:
        return py.parse(text.strip(), mode="eval").body
    except SyntaxError as error:
        raise Refused(element, f"'{text}' is no Python expression: {error.msg}",
                      EXPRESSION) from None  # fmt: skip


def _in_states(node: py.expr) -> list[str] | None:
    """The states ``In('a')`` or ``(In('a') or In('b'))`` names."""
    if isinstance(node, py.BoolOp) and isinstance(node.op, py.Or):
        found = [_in_states(v) for v in node.values]
        if all(f is not None and len(f) == 1 for f in found):
            return [f[0] for f in found]  # type: ignore[index]
        return None
    if (
        isinstance(node, py.Call)
        and isinstance(node.func, py.Name)
        and node.func.id == "In"
        and len(node.args) == 1
        and isinstance(node.args[0], py.Constant)
        and isinstance(node.args[0].value, str)
    ):
        return [node.args[0].value]
    return None


def _suppressor(node: py.expr) -> bool:
    """``not (In('X') [and …])``: the target's exclusion of another region's transition."""
    if not (isinstance(node, py.UnaryOp) and isinstance(node.op, py.Not)):
        return False
    inner = node.operand
    if isinstance(inner, py.BoolOp) and isinstance(inner.op, py.And):
        inner = inner.values[0]
    return _in_states(inner) is not None


def _same(a: py.expr, b: py.expr) -> bool:
    return py.dump(a) == py.dump(b)


def _compare(node: py.expr, op: type, left: py.expr, right: py.expr | int) -> bool:
    if not (isinstance(node, py.Compare) and len(node.ops) == 1 and type(node.ops[0]) is op):
        return False
    other = node.comparators[0]
    if isinstance(right, int):
        matches = isinstance(other, py.Constant) and other.value == right
    else:
        matches = _same(other, right)
    return _same(node.left, left) and matches


def _function(node: py.expr) -> tuple[str, list[py.expr]] | None:
    """``abs``, ``min``, ``max`` as the target writes them with comparisons."""
    if isinstance(node, py.BinOp) and isinstance(node.op, py.Mult):
        x, sign = node.left, node.right
        if (
            isinstance(sign, py.BinOp)
            and isinstance(sign.op, py.Sub)
            and _compare(sign.left, py.Gt, x, 0)
            and _compare(sign.right, py.Lt, x, 0)
        ):
            return "abs", [x]
    if isinstance(node, py.BinOp) and isinstance(node.op, py.Add):
        first, second = node.left, node.right
        if all(isinstance(p, py.BinOp) and isinstance(p.op, py.Mult) for p in (first, second)):
            a, b = first.left, second.left
            for name, ops in (("min", (py.LtE, py.Lt)), ("max", (py.GtE, py.Gt))):
                if _compare(first.right, ops[0], a, b) and _compare(second.right, ops[1], b, a):
                    return name, [a, b]
    return None
