"""The grammar hooks: filled by an extension's rules where they stand, matching nothing
when unfilled, and refused when an extension names a hook that does not exist."""

from __future__ import annotations

import pytest
from textx import TextXSyntaxError

from lightrocks.languages.lightrocks.syntax import FRAGMENTS, GRAMMAR, parse_statechart
from lightrocks.metamodel.grammar import (
    HOOKS,
    GrammarExtension,
    GrammarExtensionError,
    SyntaxProblem,
    build_metamodel,
)

MARK = "Mark: 'mark' name=ID ';';"
TOP_ONLY = GrammarExtension(MARK, (("ChartExtension", ("Mark",)),))
EVERYWHERE = GrammarExtension(MARK, (("ElementExtension", ("Mark",)),))
AT_TOP = "statechart X { mark m; initial state S; }"
IN_STATE = "statechart X { initial state S { mark m; } }"


def test_a_chart_hook_takes_the_element_in_the_statechart_body_only() -> None:
    metamodel = build_metamodel(GRAMMAR, FRAGMENTS, (TOP_ONLY,))
    assert metamodel.model_from_str(AT_TOP).statechart.elements[0].name == "m"
    with pytest.raises(TextXSyntaxError):
        metamodel.model_from_str(IN_STATE)


def test_an_element_hook_takes_it_in_every_body() -> None:
    metamodel = build_metamodel(GRAMMAR, FRAGMENTS, (EVERYWHERE,))
    assert metamodel.model_from_str(IN_STATE).statechart.elements[0].body.elements[0].name == "m"
    assert metamodel.model_from_str(AT_TOP).statechart.elements[0].name == "m"


def test_unfilled_hooks_match_nothing_and_stay_out_of_messages() -> None:
    with pytest.raises(SyntaxProblem) as problem:
        parse_statechart(AT_TOP, "X.lr")
    assert not any(hook in problem.value.message for hook in HOOKS)
    assert "(?!)" not in problem.value.message


def test_an_unknown_hook_is_refused() -> None:
    wrong = GrammarExtension(MARK, (("StateExtension", ("Mark",)),))
    with pytest.raises(GrammarExtensionError, match="no grammar hook 'StateExtension'"):
        build_metamodel(GRAMMAR, FRAGMENTS, (wrong,))


TWICE = "Twice: 'twice' '(' value=Expression ')';"
BEEP = "Beep: 'beep' name=ID ';';"
STATEMENTS_AND_EXPRESSIONS = GrammarExtension(
    f"{TWICE}\n{BEEP}",
    (("ExpressionExtension", ("Twice",)), ("StatementExtension", ("Beep",))),
)
USES = """statechart X {
  parameters { Integer twin = 1; Integer beep = 0; }
  initial state S;
  state T;
  S -> T [twice(twin + 1) > twin] go / { beep loud; beep = twin; twin = twice(twin); };
}"""


def test_expression_and_statement_hooks_take_new_syntax_beside_the_built_in() -> None:
    metamodel = build_metamodel(GRAMMAR, FRAGMENTS, (STATEMENTS_AND_EXPRESSIONS,))
    transition = metamodel.model_from_str(USES).statechart.elements[-1]
    guard = transition.guard.operands[0].operand.primary
    assert type(guard).__name__ == "Twice"
    kinds = [type(s).__name__ for s in transition.action.statements]
    assert kinds == ["Beep", "Assignment", "Assignment"]  # a name may still be 'beep'
    assigned = transition.action.statements[2].value.operands[0].operand.primary
    assert type(assigned).__name__ == "Twice"


def test_without_the_extension_its_syntax_is_an_error() -> None:
    with pytest.raises(SyntaxProblem):
        parse_statechart(USES, "X.lr")
