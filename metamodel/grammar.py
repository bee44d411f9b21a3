"""Composition of textX grammars from fragments, and parsing with positions.

A language's grammar is its own root fragment followed by the shared fragments of this
package (common rules, expressions, statecharts). The root fragment comes first because
textX takes the first rule as the root of the model.

textX cannot override a rule of an imported grammar, so the shared fragments leave named
hooks open instead (:data:`HOOKS`). A :class:`GrammarExtension` brings its own rules and
names which of them fill which hook; a hook nobody fills matches nothing.
"""

from __future__ import annotations

import gc
import re
import threading
from collections.abc import Iterable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from functools import cache
from pathlib import Path

from arpeggio import ParsingExpression, RegExMatch
from textx import TextXSyntaxError, metamodel_from_str

from lightrocks.metamodel.compiled import compile_parser
from lightrocks.metamodel.objects import ObjectBuilder, eligible

FRAGMENTS = Path(__file__).parent


class SyntaxProblem(Exception):
    """A text that does not match the grammar, located at line and column."""

    def __init__(self, message: str, line: int, column: int) -> None:
        super().__init__(f"{line}:{column}: {message}")
        self.message = message
        self.line = line
        self.column = column


HOOKS = ("ChartExtension", "ElementExtension", "StatementExtension", "ExpressionExtension")
"""Rules of the shared fragments that extensions fill (see statecharts.tx, expressions.tx)."""

_NOTHING = "/(?!)/"  # a pattern that never matches: the body of an unfilled hook


@dataclass(frozen=True)
class GrammarExtension:
    """textX rules of an extension and the hooks they fill: ``(("ElementExtension",
    ("Requirement",)),)`` makes ``Requirement`` one more alternative of that hook."""

    rules: str
    hooks: tuple[tuple[str, tuple[str, ...]], ...]


class GrammarExtensionError(Exception):
    """An extension names a hook that does not exist or leaves it without rules."""


def compose(root: Path, *fragments: str, extensions: Iterable[GrammarExtension] = ()) -> str:
    """Grammar text of ``root``, the named fragments of this package and the hook rules."""
    parts = [root.read_text(encoding="utf-8")]
    parts += [(FRAGMENTS / f"{name}.tx").read_text(encoding="utf-8") for name in fragments]
    filled: dict[str, list[str]] = {hook: [] for hook in HOOKS}
    for extension in extensions:
        for hook, rules in extension.hooks:
            if hook not in filled or not rules:
                raise GrammarExtensionError(f"no grammar hook '{hook}' or no rules for it")
            filled[hook] += rules
        parts.append(extension.rules)
    parts += [f"{hook}: {' | '.join(rules) or _NOTHING};" for hook, rules in filled.items()]
    return "\n".join(parts)


def build_metamodel(
    root: Path, fragments: tuple[str, ...], extensions: tuple[GrammarExtension, ...] = ()
):
    """A new textX metamodel of a composed grammar, its strings matched in constant memory
    (:func:`linear_strings`)."""
    text = compose(root, *fragments, extensions=extensions)
    metamodel = metamodel_from_str(text, autokwd=True, skipws=True)
    linear_strings(metamodel._parser_blueprint.parser_model)
    return metamodel


TEXTX_STRING = r'("(\\"|[^"])*")|(\'(\\\'|[^\'])*\')'
"""textX's ``STRING``: a quoted text in which a backslash before the quote keeps it open.
Python's ``re`` keeps backtracking state for every character that the repeated capturing
group matches: about 180 bytes per character (a 5 MB string literal took 900 MB)."""

LINEAR_STRING = r'"(?:\\"|[^"])*+"|"[\s\S]*\\"' + r"|'(?:\\'|[^'])*+'|'[\s\S]*\\'"
r"""The same matches as :data:`TEXTX_STRING` in constant memory. ``STRING`` first takes
every escaped quote and stops at the first quote without a backslash before it; the
possessive repetition does the same without keeping state to backtrack to. Where no such
quote follows (the file ends), ``STRING`` backtracks to its last escaped quote and ends
there, its backslash kept as a character: the second alternative, whose ``[\s\S]*`` is one
character class and backtracks without memory either. textX reads a match by its group
only where the pattern has exactly one: the original has four, this one none."""


def linear_strings(model: ParsingExpression) -> None:
    """Match textX's ``STRING`` rule in ``model`` with :data:`LINEAR_STRING` (the rule is
    shared by every grammar textX builds, so theirs change alike: the matches are equal)."""
    seen: set[int] = set()
    pending = [model]
    while pending:
        node = pending.pop()
        if id(node) in seen:
            continue
        seen.add(id(node))
        if isinstance(node, RegExMatch) and node.to_match_regex == TEXTX_STRING:
            node.to_match_regex = LINEAR_STRING
            node.compile()
        pending.extend(node.nodes)
        if getattr(node, "sep", None) is not None:
            pending.append(node.sep)


_building = threading.Lock()


@cache
def textx_metamodel(
    root: Path, fragments: tuple[str, ...], extensions: tuple[GrammarExtension, ...] = ()
):
    """The textX metamodel the parsers use, built once per process. textX reads grammars
    with one shared parser, so builds from several threads take turns."""
    with _building:
        return build_metamodel(root, fragments, extensions)


@cache
def _object_builder(metamodel) -> ObjectBuilder | None:
    return ObjectBuilder(metamodel) if eligible(metamodel) else None


@cache
def _compiled_parser(metamodel):
    return compile_parser(metamodel._parser_blueprint)


def parse(
    root: Path,
    fragments: tuple[str, ...],
    text: str,
    file: str,
    extensions: tuple[GrammarExtension, ...] = (),
):
    """Parse ``text`` into textX model objects; raise :class:`SyntaxProblem` with a readable
    message on mismatch. The objects come from :mod:`metamodel.objects` where the grammar
    allows it, else from textX's own builder; the parse tree comes from the compiled parser
    (:mod:`metamodel.compiled`), or from Arpeggio where that is not compiled or the text does
    not match, so that a syntax error is described as Arpeggio describes it."""
    metamodel = textx_metamodel(root, fragments, extensions)
    builder = _object_builder(metamodel)
    try:
        if builder is None:
            return metamodel.model_from_str(text, file_name=file)
        compiled = _compiled_parser(metamodel)
        tree = None if compiled is None else compiled(text)
        if tree is None:
            parser = metamodel._parser_blueprint.clone()
            parser.parse(text, file_name=file)
            tree = parser.parse_tree
        return builder.build(tree[0])
    except TextXSyntaxError as error:
        raise SyntaxProblem(_describe(error), error.line or 1, error.col or 1) from None


@contextmanager
def paused_gc() -> Iterator[None]:
    """Pause the cyclic garbage collector while building trees.

    Parsing and conversion allocate hundreds of thousands of acyclic objects; the collector
    would rescan the growing tree again and again, which made large models grow
    super-linearly (6.5 s instead of 3 s for 10,000 states).
    """
    collecting = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if collecting:
            gc.enable()


def _describe(error: TextXSyntaxError) -> str:
    rules = [r for r in error.expected_rules or [] if getattr(r, "to_match", None) != "(?!)"]
    expected = sorted({text for rule in rules for text in _rule_texts(rule)})
    found = error.context.split("*")[-1].strip().split()[:1] if error.context else []
    if expected:
        shown = ", ".join(expected[:6]) + (", …" if len(expected) > 6 else "")
        where = f" but found '{found[0]}'" if found else " but the file ends here"
        return f"syntax error: expected {shown}{where}"
    return f"syntax error: {error.message}"


def _rule_texts(rule: object) -> tuple[str, ...]:
    """How an expected rule is named in a message, in the words a user may type: a keyword
    or an operator as written, a rule by what it stands for (``a name``), a lookahead on a
    set of characters (such as ``SuffixStart``, which spares trying each suffix) by each
    character."""
    text = getattr(rule, "to_match", None)
    if isinstance(text, str) and not getattr(rule, "regex", None):
        return (f"'{text}'",)
    name = getattr(rule, "rule_name", "") or getattr(rule, "name", "")
    if name in _FRIENDLY:
        return (_FRIENDLY[name],)
    if isinstance(text, str) and _KEYWORD.fullmatch(text):  # textX matches keywords whole
        return (f"'{text}'",)
    literal = _literal(text) if isinstance(text, str) else None
    if literal:  # an operator such as '=' that must not be followed by another '='
        return (f"'{literal}'",)
    characters = _CHARACTER_SET.fullmatch(text) if isinstance(text, str) else None
    if characters:
        return tuple(f"'{c}'" for c in re.sub(r"\\(.)", r"\1", characters[1]))
    return (name or str(rule),)


def _literal(pattern: str) -> str | None:
    """The plain text a regular expression matches once its lookaheads and word boundaries
    are left out (``=(?!=)`` -> ``=``); None for a pattern that matches more than one text."""
    core = _LOOKAROUND.sub("", pattern)
    plain = re.sub(r"\\(.)", r"\1", core)
    if not plain or any(c in ".^$*+?{}[]|()\\" for c in re.sub(r"\\.", "", core)):
        return None
    return plain


_LOOKAROUND = re.compile(r"\(\?<?[!=](?:\\.|[^()\\])*\)|\\b")
"""Lookaheads and lookbehinds without nested groups, and word boundaries."""

_KEYWORD = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
"""What a keyword's rule matches: textX turns a keyword into a regular expression that
matches the word alone (``import\\b``), and keeps the word."""

_CHARACTER_SET = re.compile(r"\[((?:\\.|[^\]^\\])+)\]")
r"""A regular expression that is one set of plain characters, such as ``[.(\[]``."""


_FRIENDLY = {
    "ID": "a name",
    "STRING": "a string",
    "INT": "an integer",
    "Number": "a number",
    "UnitSymbol": "a unit",
    "Comment": "a comment",
    "BinaryOperator": "an operator",
    "UnaryOperator": "a unary operator",
    "BooleanValue": "true or false",
    "EOF": "the end of the file",
}
