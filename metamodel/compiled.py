"""Arpeggio parser models compiled into closures: the same parse trees, a fraction of the time.

textX turns a grammar into an Arpeggio parser model, a graph of parsing expressions that
Arpeggio interprets: every expression pays for debugging hooks, memoization checks, rule
bookkeeping and a ``NoMatch`` exception on every failed alternative. For a large model that
interpretation was three quarters of a check. This module compiles the same graph once into
one closure per expression, each taking the text and a position and returning the result
and the next position, or ``None`` where the expression does not match. The closures build
exactly the parse tree Arpeggio builds (the same node classes, rules, positions, values and
flags; quirks included), so everything downstream reads it unchanged.

Only the successful parse is compiled. A text the closures reject is parsed again by
Arpeggio, which raises its usual error with the expected rules; a parser model that uses a
feature this module does not compile (per-rule whitespace, line-end repetitions, lexical
rules, memoization, ...) is not compiled at all (:func:`compile_parser` returns ``None``).
"""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import Any

from arpeggio import (
    And,
    EndOfFile,
    NonTerminal,
    Not,
    OneOrMore,
    Optional,
    OrderedChoice,
    Parser,
    ParsingExpression,
    RegExMatch,
    Sequence,
    StrMatch,
    Terminal,
    ZeroOrMore,
)

Result = tuple[Any, int] | None
"""What a compiled expression returns: Arpeggio's result value and the next position, or
``None`` where it does not match."""

Compiled = Callable[[str, int], Result]

_SUPPORTED = (Sequence, OrderedChoice, Optional, ZeroOrMore, OneOrMore, And, Not)
_MATCHES = (StrMatch, RegExMatch, EndOfFile)
_SCOPED_FLAGS = {re.IGNORECASE: "i", re.MULTILINE: "m", re.DOTALL: "s", re.VERBOSE: "x"}


def compile_parser(parser: Parser) -> Callable[[str], NonTerminal | None] | None:
    """A function from a text to the parse tree ``parser`` would build for it (``None``
    where the text does not match), or ``None`` if the parser model cannot be compiled."""
    skip = _skipper(parser)
    if skip is None or not _compilable(parser):
        return None
    root = _Compiler(skip).compile(parser.parser_model, in_sequence=False)

    def parse(text: str) -> NonTerminal | None:
        result = root(text, 0)
        return None if result is None else result[0]

    return parse


def _compilable(parser: Parser) -> bool:
    """Whether every expression and every parser setting is one this module reproduces."""
    settings = (parser.memoization, parser.reduce_tree, parser.ignore_case, parser.eolterm)
    if any(settings) or parser.debug:
        return False
    seen: set[int] = set()
    pending: list[ParsingExpression] = [parser.parser_model]
    while pending:
        node = pending.pop()
        if id(node) in seen:
            continue
        seen.add(id(node))
        if type(node) not in _SUPPORTED + _MATCHES or node.suppress:
            return False
        if getattr(node, "ws", None) is not None or getattr(node, "skipws", None) is not None:
            return False
        if getattr(node, "eolterm", False) or getattr(node, "ignore_case", False):
            return False
        pending.extend(node.nodes)
        if getattr(node, "sep", None) is not None:
            pending.append(node.sep)
    return True


def _skipper(parser: Parser) -> Callable[[str, int], re.Match] | None:
    """A match of the whitespace and comments at a position, as Arpeggio skips them before
    every match: whitespace, then comment after comment, each followed by whitespace. One
    regular expression does it, in constant memory; ``None`` if the comment rule is not one
    regex."""
    spaces = "".join(re.escape(char) for char in parser.ws)
    alternatives = [f"[{spaces}]++"] if parser.skipws and spaces else []
    comment = parser.comments_model
    if comment is not None:
        if type(comment) is not RegExMatch or comment.suppress:
            return None
        flags = comment.regex.flags & ~re.UNICODE
        letters = "".join(letter for flag, letter in _SCOPED_FLAGS.items() if flags & flag)
        if flags & ~sum(_SCOPED_FLAGS):
            return None
        scoped = f"(?{letters}:{comment.regex.pattern})" if letters else comment.regex.pattern
        alternatives.append(f"(?:{scoped})")
    if not alternatives:
        return re.compile("").match
    # Possessive: nothing follows to backtrack for, and a repetition that may backtrack
    # keeps state for every time it repeats (about 115 bytes for each space of a long run).
    return re.compile(f"(?:{'|'.join(alternatives)})*+").match


def _terminal(rule: Any, position: int, value: str, suppress: bool, extra: Any) -> Terminal:
    """A terminal as Arpeggio makes it, without the checks of its constructor."""
    node = Terminal.__new__(Terminal)
    node.rule = rule
    node.rule_name = rule.rule_name
    node.position = position
    node.error = False
    node.comments = None
    node.value = value
    node.suppress = suppress
    node.extra_info = extra
    return node


def _flat(items: list, into: list) -> list:
    """Arpeggio's ``flatten``: nested plain lists opened, nodes kept."""
    for item in items:
        if type(item) is list:
            _flat(item, into)
        else:
            into.append(item)
    return into


def _nonterminal(rule: Any, value: list) -> NonTerminal:
    """The node a root rule makes of its result list (Arpeggio's ``NonTerminal``)."""
    nodes = _flat(value, [])
    node = NonTerminal.__new__(NonTerminal)
    list.extend(node, nodes)
    node.rule = rule
    node.rule_name = rule.rule_name
    node.position = nodes[0].position if nodes else 0
    node.error = False
    node.comments = None
    node._filtered = False
    return node


class _Compiler:
    """Compiles expressions once each; a rule that refers back to itself goes through the
    table of compiled expressions."""

    def __init__(self, skip: Callable[[str, int], re.Match]) -> None:
        self._skip = skip
        self._done: dict[tuple[int, bool], Compiled | None] = {}

    def compile(self, node: ParsingExpression, in_sequence: bool) -> Compiled:
        # Only a string match depends on where it is used: inside a plain sequence
        # Arpeggio marks its terminal as suppressed.
        key = (id(node), in_sequence and type(node) is StrMatch)
        if key in self._done:
            done = self._done[key]
            if done is None:  # still being compiled: a recursive rule
                table = self._done
                return lambda text, pos: table[key](text, pos)
            return done
        self._done[key] = None
        compiled = self._compile(node, key[1])
        self._done[key] = compiled
        return compiled

    def _children(self, node: ParsingExpression) -> list[Compiled]:
        return [self.compile(child, type(node) is Sequence) for child in node.nodes]

    def _compile(self, node: ParsingExpression, suppressed: bool) -> Compiled:
        kind = type(node)
        if kind is StrMatch:
            return self._string(node, suppressed)
        if kind is RegExMatch:
            return self._regex(node)
        if kind is EndOfFile:
            return self._end()
        if kind in (And, Not):
            return self._lookahead(self._children(node), positive=kind is And)
        # A root rule turns a non-empty result into a node of its own.
        rule = node if node.root else None
        if kind is Sequence:
            return self._sequence(self._children(node), rule)
        if kind is OrderedChoice:
            return self._choice(self._children(node), rule)
        if kind is Optional:
            return self._optional(self._children(node)[0], rule)
        separator = None if node.sep is None else self.compile(node.sep, False)
        return self._repetition(self._children(node)[0], separator, kind is OneOrMore, rule)

    def _string(self, rule: StrMatch, suppressed: bool) -> Compiled:
        skip, expected, length = self._skip, rule.to_match, len(rule.to_match)

        def string(text: str, pos: int) -> Result:
            pos = skip(text, pos).end()
            if text.startswith(expected, pos):
                return _terminal(rule, pos, expected, suppressed, None), pos + length
            return None

        return string

    def _regex(self, rule: RegExMatch) -> Compiled:
        skip, match = self._skip, rule.regex.match

        def regex(text: str, pos: int) -> Result:
            pos = skip(text, pos).end()
            found = match(text, pos)
            if found is None:
                return None
            matched = found.group()
            if not matched:
                return None, pos
            return _terminal(rule, pos, matched, False, found), pos + len(matched)

        return regex

    def _end(self) -> Compiled:
        skip = self._skip

        def end(text: str, pos: int) -> Result:
            pos = skip(text, pos).end()
            if pos != len(text):
                return None
            return _terminal(EndOfFile(), pos, "", True, None), pos

        return end

    @staticmethod
    def _sequence(parts: list[Compiled], rule: Any) -> Compiled:
        def sequence(text: str, pos: int) -> Result:
            results: list = []
            for part in parts:
                result = part(text, pos)
                if result is None:
                    return None
                value, pos = result
                if value:
                    # A list's items are taken one level up: the same once flattened.
                    if type(value) is list:
                        results.extend(value)
                    else:
                        results.append(value)
            if not results:
                return None, pos
            return (results if rule is None else _nonterminal(rule, results)), pos

        return sequence

    @staticmethod
    def _choice(alternatives: list[Compiled], rule: Any) -> Compiled:
        def choice(text: str, pos: int) -> Result:
            for alternative in alternatives:
                result = alternative(text, pos)
                if result is not None:
                    if result[0] is not None:
                        value = [result[0]]
                        return (value if rule is None else _nonterminal(rule, value)), result[1]
                    pos = result[1]  # matched nothing: Arpeggio goes on from there
            return None

        return choice

    @staticmethod
    def _optional(part: Compiled, rule: Any) -> Compiled:
        def optional(text: str, pos: int) -> Result:
            result = part(text, pos)
            if result is None:
                return None, pos
            if result[0] is None:
                return result
            value = [result[0]]
            return (value if rule is None else _nonterminal(rule, value)), result[1]

        return optional

    @staticmethod
    def _repetition(
        part: Compiled, separator: Compiled | None, at_least_one: bool, rule: Any
    ) -> Compiled:
        def repetition(text: str, pos: int) -> Result:
            results: list = []
            previous = None
            while True:
                start = pos
                if separator is not None and previous:
                    found = separator(text, pos)
                    if found is None:
                        pos = start
                        break
                    if found[0]:
                        # Kept even when no item follows, as Arpeggio keeps it.
                        results.append(found[0])
                    pos = found[1]
                result = part(text, pos)
                if result is None:
                    if at_least_one and previous is None:
                        return None
                    pos = start
                    break
                previous, pos = result
                if not previous:
                    break
                results.append(previous)
            if rule is None or not results:
                return results, pos
            return _nonterminal(rule, results), pos

        return repetition

    @staticmethod
    def _lookahead(parts: list[Compiled], positive: bool) -> Compiled:
        def lookahead(text: str, pos: int) -> Result:
            for part in parts:
                if part(text, pos) is None:
                    return None if positive else (None, pos)
            return (None, pos) if positive else None

        return lookahead
