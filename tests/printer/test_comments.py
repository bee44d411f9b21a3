"""Comments survive formatting: all of them, in order, where they were as far as possible."""

from __future__ import annotations

from pathlib import Path

from hypothesis import given, settings
from hypothesis import strategies as st

from lightrocks.languages.domain.printer import format_domain_text
from lightrocks.languages.domain.syntax import parse_domain
from lightrocks.languages.lightrocks.printer import format_statechart_text
from lightrocks.languages.lightrocks.syntax import parse_statechart
from lightrocks.metamodel.comments import Comments

MODELS = Path(__file__).parent / "models"


def comment_texts(text: str) -> list[str]:
    return [c.text for c in Comments(text).comments]


def check_statechart(text: str) -> str:
    """Format ``text`` and check the invariants every formatting must keep."""
    printed = format_statechart_text(text, "t.lr")
    assert comment_texts(printed) == comment_texts(text)
    assert parse_statechart(printed, "t.lr") == parse_statechart(text, "t.lr")
    assert format_statechart_text(printed, "t.lr") == printed
    return printed


def test_scanner_finds_comments_but_not_inside_strings() -> None:
    text = "a = \"// no /* no */\"; // yes\n/* one\n two */ b = '// no';"
    found = Comments(text).comments
    assert [c.text for c in found] == ["// yes", "/* one\n two */"]
    assert [(c.line, c.column, c.end_line, c.own_line) for c in found] == [
        (1, 23, 1, False),
        (2, 1, 3, True),
    ]


SOURCE = """\
// file header

package p; // after package
/* before import */ import q.*;

// before the statechart
<<skill>> statechart S { // after the head
  // before parameters
  parameters {
    Length a = 1 mm;   // after a
    // before the closing brace of parameters
  }
  exit / { x = 1; }    // after exit
  do / {
    // inside a one-statement block
    y = 2;
  }
  state A { /* after A's brace */
    A -> A;
  } // after A's closing brace

  // before the transition, after a blank line
  A -> A [x > /* in the guard */ 1];
  A -> A e(1,   // on an argument line
           2);
  // before the closing brace of the statechart
}
// at the end
/* really the end */
"""


def test_comments_are_placed_where_they_were() -> None:
    printed = check_statechart(SOURCE)
    assert (
        printed
        == """\
// file header

package p; // after package

/* before import */
import q.*;

// before the statechart
<<skill>> statechart S { // after the head
  // before parameters
  parameters {
    Length a = 1 mm; // after a
    // before the closing brace of parameters
  }

  exit / { x = 1; } // after exit
  do / {
    // inside a one-statement block
    y = 2;
  }

  state A { /* after A's brace */
    A -> A;
  } // after A's closing brace

  // before the transition, after a blank line
  A -> A [x > 1]; /* in the guard */
  A -> A e(1, 2); // on an argument line
  // before the closing brace of the statechart
}
// at the end
/* really the end */
"""
    )


def test_adjacent_trailing_comments_are_aligned() -> None:
    printed = check_statechart("statechart S {\n  state Long; // a\n  state B; // b\n}\n")
    assert "  state Long; // a\n  state B;    // b\n" in printed


def test_a_comment_on_a_later_line_of_an_element_follows_it() -> None:
    printed = check_statechart("statechart S {\n  A -> B [x >\n  // why\n  1];\n}\n")
    assert printed == "statechart S {\n  A -> B [x > 1];\n  // why\n}\n"


def test_domain_comments_are_kept() -> None:
    text = (MODELS / "Rich.lrd").read_text(encoding="utf-8")
    commented = text.replace("{\n", "{ // opened\n").replace(";\n", "; /* done */\n")
    commented = "// header\n" + commented + "// end\n"
    printed = format_domain_text(commented, "t.lrd")
    assert comment_texts(printed) == comment_texts(commented)
    assert parse_domain(printed, "t.lrd") == parse_domain(text, "t.lrd")
    assert format_domain_text(printed, "t.lrd") == printed


RICH = (MODELS / "Rich.lr").read_text(encoding="utf-8").splitlines()


@settings(max_examples=60, deadline=None)
@given(st.lists(st.sampled_from(["", "trailing", "own", "block"]), min_size=len(RICH)))
def test_comments_anywhere_between_lines_survive(choices: list[str]) -> None:
    lines = []
    for number, (line, choice) in enumerate(zip(RICH, choices, strict=False)):
        if choice == "own":
            lines.append(f"// own {number}")
        lines.append(f"{line} // trailing {number}" if choice == "trailing" else line)
        if choice == "block":
            lines.append(f"  /* block\n     {number} */")
    check_statechart("\n".join(lines) + "\n")
