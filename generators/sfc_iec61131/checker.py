"""A structural checker for the textual SFC subset this generator writes.

It tokenizes the text (comments and strings skipped, no evaluation), reads the declarations
and SFC elements of every POU, and reports each rule it finds broken:

``initial-step``   exactly one INITIAL_STEP per network
``unique-name``    names of a POU (variables, steps, actions, transitions) differ ignoring case
``type-name``      no name of a POU is spelled like a type or POU (MatIEC reads it as that type)
``macro-name``     no step or action is spelled like a member its POU reads: MatIEC's C makes
                   every step and action a macro of its block, which rewrites ``x.member``
``reserved-name``  no declared name is an IEC keyword or standard function/function block
``undefined-step`` every FROM/TO step exists; ``undefined-action`` every action used exists
``priority``       every branch of a selective divergence has a distinct PRIORITY
``timed-qualifier`` L, D, SD, DS and SL carry a time
``empty-action``   no action without statements
``empty-body``     no FUNCTION or FUNCTION_BLOCK without statements (MatIEC loops on one)
``string-literal`` string literals hold printable ASCII only; anything else is a ``$`` escape,
                   as are comment delimiters; at most 254 characters (MatIEC's STRING)
``simultaneous``   simultaneous divergences and convergences balance (same branch counts)
"""

from __future__ import annotations

import re
from collections import Counter
from dataclasses import dataclass, field
from itertools import pairwise

from lightrocks.generators.sfc_iec61131.expressions import STRING_LENGTH
from lightrocks.generators.sfc_iec61131.reserved import is_reserved

TOKEN = re.compile(
    r"\(\*.*?\*\)|//[^\n]*|'(?:\$.|[^'])*'|T#[\w.]+|[A-Za-z_]\w*|\d[\w.#]*|:=|\.\.|\S",
    re.DOTALL,
)
POUS = {
    "FUNCTION_BLOCK": "END_FUNCTION_BLOCK",
    "PROGRAM": "END_PROGRAM",
    "FUNCTION": "END_FUNCTION",
}
VAR_SECTIONS = {"VAR", "VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT", "VAR_EXTERNAL", "VAR_TEMP"}
TIMED = {"L", "D", "SD", "DS", "SL"}


@dataclass(frozen=True)
class Problem:
    line: int
    rule: str
    message: str

    def __str__(self) -> str:
        return f"line {self.line}: [{self.rule}] {self.message}"


@dataclass
class Token:
    text: str
    line: int

    @property
    def upper(self) -> str:
        return self.text.upper()


@dataclass
class Pou:
    kind: str
    name: Token
    names: list[Token] = field(default_factory=list)
    steps: dict[str, Token] = field(default_factory=dict)
    initial: list[Token] = field(default_factory=list)
    actions: dict[str, Token] = field(default_factory=dict)
    members: dict[str, Token] = field(default_factory=dict)
    statements: int = 0  # statements of the body outside SFC elements
    uses: list[tuple[Token, Token | None, bool]] = field(default_factory=list)
    transitions: list[tuple[Token, list[Token], list[Token], Token | None]] = field(
        default_factory=list
    )


def tokenize(text: str) -> list[Token]:
    """The words of ``text`` without comments, each with its line; lines are counted from
    the previous token on, so long units cost linear time."""
    tokens = []
    line, counted = 1, 0
    for match in TOKEN.finditer(text):
        line += text.count("\n", counted, match.start())
        counted = match.start()
        word = match.group()
        if not word.startswith(("(*", "//")):
            tokens.append(Token(word, line))
    return tokens


class Reader:
    def __init__(self, tokens: list[Token]) -> None:
        self.tokens = tokens
        self.at = 0

    def peek(self, ahead: int = 0) -> Token:
        index = self.at + ahead
        return self.tokens[index] if index < len(self.tokens) else Token("", 0)

    def next(self) -> Token:
        token = self.peek()
        self.at += 1
        return token

    def until(self, *ends: str) -> list[Token]:
        taken = []
        while self.peek().text and self.peek().upper not in ends:
            taken.append(self.next())
        return taken

    def steps(self) -> list[Token]:
        """One step name or a parenthesized list of them."""
        if self.peek().text != "(":
            return [self.next()]
        self.next()
        names = [t for t in self.until(")") if t.text != ","]
        self.next()
        return names


def parse(text: str) -> tuple[list[Pou], list[Token]]:
    """The POUs with their SFC elements, and the declared type names."""
    reader = Reader(tokenize(text))
    pous: list[Pou] = []
    types: list[Token] = []
    while reader.peek().text:
        word = reader.next().upper
        if word == "TYPE":
            types += _type_names(reader.until("END_TYPE"))
        elif word in POUS:
            pous.append(_pou(reader, word))
    return pous, types


def _type_names(body: list[Token]) -> list[Token]:
    """Names declared at the top of a TYPE block (not the fields of its STRUCTs)."""
    names, depth = [], 0
    for index, token in enumerate(body[:-1]):
        if token.upper == "STRUCT":
            depth += 1
        elif token.upper == "END_STRUCT":
            depth -= 1
        elif (
            depth == 0
            and body[index + 1].text == ":"
            and (index == 0 or body[index - 1].text == ";")
        ):
            names.append(token)
    return names


def _pou(reader: Reader, kind: str) -> Pou:
    end = POUS[kind]
    pou = Pou(kind, reader.next())
    start = reader.at
    while reader.peek().text and reader.peek().upper != end:
        word = reader.next().upper
        if word in VAR_SECTIONS:
            declaration = reader.until("END_VAR")
            first = True
            for token in declaration:
                if first and re.fullmatch(r"[A-Za-z_]\w*", token.text):
                    pou.names.append(token)
                first = token.text in (";", ",")
        elif word in ("STEP", "INITIAL_STEP"):
            name = reader.next()
            pou.steps[name.upper] = name
            pou.names.append(name)
            if word == "INITIAL_STEP":
                pou.initial.append(name)
            body = reader.until("END_STEP")
            _associations(pou, body)
        elif word == "TRANSITION":
            _transition(pou, reader)
        elif word == "ACTION":
            name = reader.next()
            pou.actions[name.upper] = name
            pou.names.append(name)
            body = [t for t in reader.until("END_ACTION")[1:] if t.text != ";"]
            if not body:
                pou.uses.append((name, None, False))  # recorded as an empty body
        elif word == ";":
            pou.statements += 1
    for before, token in pairwise(reader.tokens[start : reader.at]):
        if before.text == "." and re.fullmatch(r"[A-Za-z_]\w*", token.text):
            pou.members.setdefault(token.upper, token)
    reader.next()
    return pou


def _associations(pou: Pou, body: list[Token]) -> None:
    """``name(Q);`` or ``name(Q, T#5s);`` entries of a step."""
    for index, token in enumerate(body):
        if token.text == "(" and index > 0:
            qualifier = body[index + 1] if index + 1 < len(body) else None
            timed = index + 2 < len(body) and body[index + 2].text == ","
            pou.uses.append((body[index - 1], qualifier, timed))


def _transition(pou: Pou, reader: Reader) -> None:
    name = reader.next() if reader.peek().upper != "FROM" else Token("", reader.peek().line)
    priority = None
    if reader.peek().text == "(":
        reader.until(":=")
        reader.next()
        priority = reader.next()
        reader.until("FROM")
    reader.next()  # FROM
    sources = reader.steps()
    reader.next()  # TO
    targets = reader.steps()
    reader.until("END_TRANSITION")
    if name.text:
        pou.names.append(name)
    pou.transitions.append((name, sources, targets, priority))


def check_sfc(text: str) -> list[Problem]:
    """Every broken rule of every POU in ``text``, in line order."""
    pous, types = parse(text)
    problems: list[Problem] = []
    for declared in [*types, *(p.name for p in pous)]:
        if is_reserved(declared.text):
            problems.append(
                Problem(declared.line, "reserved-name", f"'{declared.text}' is reserved")
            )
    declared = {t.upper: t for t in [*types, *(p.name for p in pous)]}
    for pou in pous:
        problems += _check_pou(pou)
        problems += _check_spellings(pou, declared)
        if not pou.statements and not pou.steps and pou.kind != "PROGRAM":
            problems.append(Problem(pou.name.line, "empty-body", f"{pou.name.text} has no body"))
    for token in tokenize(text):
        if token.text.startswith("'"):
            problems += _check_string(token)
    return sorted(problems, key=lambda p: (p.line, p.rule))


def _check_string(token: Token) -> list[Problem]:
    """Printable ASCII only, no comment delimiter (MatIEC's ``-p`` pass reads one inside a
    string), and no more characters than a STRING holds (MatIEC hangs on more)."""
    inner = token.text[1:-1]
    if not re.fullmatch(r"[ -~]*", inner):
        return [Problem(token.line, "string-literal", "a string holds a character to escape")]
    if "(*" in inner or "*)" in inner:
        return [Problem(token.line, "string-literal", "a string holds a comment delimiter")]
    length = len(re.findall(r"\$[0-9A-Fa-f]{2}|\$.|.", inner))
    if length > STRING_LENGTH:
        return [Problem(token.line, "string-literal", f"a string of {length} characters")]
    return []


def _check_spellings(pou: Pou, declared: dict[str, Token]) -> list[Problem]:
    """Names that MatIEC would read as a type, or whose step macro rewrites a member."""
    problems = []
    for name in pou.names:
        if name.upper in declared:
            what = declared[name.upper]
            problems.append(
                Problem(
                    name.line,
                    "type-name",
                    f"'{name.text}' is spelled like the type '{what.text}' of line {what.line}",
                )
            )
    for name in [*pou.steps.values(), *pou.actions.values()]:
        if name.upper in pou.members:
            member = pou.members[name.upper]
            problems.append(
                Problem(
                    name.line,
                    "macro-name",
                    f"step or action '{name.text}' is spelled like the member "
                    f"'.{member.text}' of line {member.line}",
                )
            )
    return problems


def _check_pou(pou: Pou) -> list[Problem]:
    problems: list[Problem] = []
    where = pou.name.text
    if pou.steps and len(pou.initial) != 1:
        problems.append(
            Problem(pou.name.line, "initial-step", f"{where} has {len(pou.initial)} INITIAL_STEPs")
        )
    seen: dict[str, Token] = {}
    for name in pou.names:
        if is_reserved(name.text):
            problems.append(Problem(name.line, "reserved-name", f"'{name.text}' is reserved"))
        if name.upper in seen:
            first = seen[name.upper]
            problems.append(
                Problem(name.line, "unique-name", f"'{name.text}' clashes with line {first.line}")
            )
        seen.setdefault(name.upper, name)
    variables = {n.upper for n in pou.names}
    for action, qualifier, timed in pou.uses:
        if qualifier is None:
            problems.append(Problem(action.line, "empty-action", f"action {action.text} is empty"))
            continue
        if action.upper not in pou.actions and action.upper not in variables:
            problems.append(
                Problem(action.line, "undefined-action", f"action {action.text} is not defined")
            )
        if qualifier.upper in TIMED and not timed:
            problems.append(
                Problem(qualifier.line, "timed-qualifier", f"{qualifier.text} needs a time")
            )
    by_source: dict[tuple[str, ...], list] = {}
    for name, sources, targets, priority in pou.transitions:
        for step in [*sources, *targets]:
            if step.upper not in pou.steps:
                problems.append(
                    Problem(step.line, "undefined-step", f"step {step.text} is not defined")
                )
        by_source.setdefault(tuple(s.upper for s in sources), []).append((name, priority))
    for branches in by_source.values():
        if len(branches) < 2:
            continue
        priorities = [p.text for _, p in branches if p is not None]
        if len(priorities) != len(branches) or len(set(priorities)) != len(priorities):
            name = branches[0][0]
            problems.append(
                Problem(name.line, "priority", "selective divergence without distinct PRIORITY")
            )
    divergences = Counter(len(t) for _, _, t, _ in pou.transitions if len(t) > 1)
    convergences = Counter(len(s) for _, s, _, _ in pou.transitions if len(s) > 1)
    if divergences != convergences:
        problems.append(
            Problem(pou.name.line, "simultaneous", f"{where}: simultaneous branches do not balance")
        )
    return problems
