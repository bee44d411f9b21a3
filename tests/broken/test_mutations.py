"""Property: whatever one edit does to an example model, checking it never raises and every
finding has a code ``LR`` + 4 digits and a position with line and column from 1.

Edits: delete, duplicate or swap lines; delete or insert a character; truncate the file.
Every run works on a fresh copy of ``examples/`` in a temporary folder.
"""

from __future__ import annotations

import re
import shutil
import tempfile
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from lightrocks.workbench.check import check

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
MODELS = sorted(p.relative_to(EXAMPLES).as_posix() for p in EXAMPLES.rglob("*.lr*"))
CODE = re.compile(r"LR\d{4}")
INSERTED = st.sampled_from(
    [
        ";",
        "}",
        "{",
        "(",
        ")",
        "[",
        "]",
        "<",
        ">",
        "-",
        ".",
        "/",
        '"',
        "\n",
        " ",
        "x",
        "0",
        "µ",
        "\x00",
        "=",
        ",",
    ]
)


@st.composite
def mutations(draw: st.DrawFn) -> tuple[str, str]:
    """A model file of the examples and its mutated text."""
    relative = draw(st.sampled_from(MODELS))
    text = (EXAMPLES / relative).read_text(encoding="utf-8")
    lines = text.splitlines(keepends=True)
    kind = draw(
        st.sampled_from(
            [
                "delete-line",
                "duplicate-line",
                "swap-lines",
                "delete-char",
                "insert-char",
                "truncate",
            ]
        )
    )
    if kind in ("delete-line", "duplicate-line", "swap-lines"):
        i = draw(st.integers(0, len(lines) - 1))
        if kind == "delete-line":
            del lines[i]
        elif kind == "duplicate-line":
            lines.insert(i, lines[i])
        else:
            j = draw(st.integers(0, len(lines) - 1))
            lines[i], lines[j] = lines[j], lines[i]
        return relative, "".join(lines)
    offset = draw(st.integers(0, len(text)))
    if kind == "delete-char":
        return relative, text[:offset] + text[offset + 1 :]
    if kind == "insert-char":
        return relative, text[:offset] + draw(INSERTED) + text[offset:]
    return relative, text[:offset]


@settings(
    max_examples=100,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)
@given(mutations())
def test_mutated_examples_never_crash_the_checker(mutation: tuple[str, str]) -> None:
    relative, text = mutation
    with tempfile.TemporaryDirectory() as folder:
        root = Path(folder) / "examples"
        shutil.copytree(EXAMPLES, root)
        target = root / relative
        target.write_text(text, encoding="utf-8")
        context = check([target], [root])
        for finding in context.diagnostics.items:
            assert CODE.fullmatch(finding.code), finding
            assert finding.line >= 1 and finding.column >= 1, finding
            assert finding.file, finding
            assert finding.message, finding
