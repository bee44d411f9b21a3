"""Text read from a trace, a model or a scene reaches the terminal neutralised: an escape
sequence in a trace field is shown, never obeyed, by ``plot``, ``replay`` and the run's
summary, and matplotlib's warnings about missing glyphs never echo a control character."""

from __future__ import annotations

import contextlib
import io
import json
import unicodedata
import warnings
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from lightrocks.app import display
from lightrocks.app.cli import main
from lightrocks.app.run import RunResult

pytest.importorskip("matplotlib", reason="plot needs matplotlib (the 'plot' extra)")

TITLE = "\x1b]0;PWNED\x07\x1b[2J"
"""Sets the terminal's title and clears the screen when printed raw."""

OBEYED = ("Cc", "Cf", "Cs", "Zl", "Zp")
"""Controls, format characters (bidi overrides), lone surrogates, line or paragraph separators."""
CONTROLS = st.characters(categories=OBEYED)
HOSTILE = st.lists(st.one_of(CONTROLS, st.characters()), min_size=1, max_size=12).map("".join)


def acts_on_a_terminal(text: str) -> bool:
    """Whether ``text`` holds a character a terminal would obey (line breaks aside)."""
    return any(unicodedata.category(c) in OBEYED for c in text.replace("\n", ""))


def trace_with(path: Path, word: str) -> Path:
    sample = {
        "time": 0.2,
        "kind": "sample",
        "robot.tcp": [0.0, 0.0, 0.1],
        "robot.wrench": {"force": [0.0, 0.0, 1.0], "torque": [0.0, 0.0, 0.0]},
    }
    records = [
        {"time": 0.0, "kind": "enter", "state": f"T{word}", "layer": "task"},
        {"time": 0.1, "kind": "enter", "state": f"T{word}/S{word}", "layer": "skill"},
        sample,
        {"time": 0.3, "kind": "exit", "state": f"T{word}/S{word}"},
        {"time": 0.4, "kind": "finished", "outcome": word},
    ]
    path.write_text("".join(json.dumps(r) + "\n" for r in records), encoding="utf-8")
    return path


def test_plot_shows_the_outcome_escaped(tmp_path: Path, capsys) -> None:
    trace = trace_with(tmp_path / "run.jsonl", TITLE)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        assert main(["plot", str(trace), "-o", str(tmp_path / "run.png")]) == 0
    out = capsys.readouterr()
    assert "\\x1b]0;PWNED\\x07" in out.out
    assert not acts_on_a_terminal(out.out + out.err)
    assert not any(acts_on_a_terminal(str(w.message)) for w in caught)


@settings(max_examples=12)
@given(word=HOSTILE)
def test_no_trace_field_drives_the_terminal_of_plot(tmp_path_factory, word: str) -> None:
    folder = tmp_path_factory.mktemp("plot")
    trace = trace_with(folder / "run.jsonl", word)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            assert main(["plot", str(trace), "-o", str(folder / "run.png")]) == 0
    assert not acts_on_a_terminal(out.getvalue() + err.getvalue())
    assert not any(acts_on_a_terminal(str(w.message)) for w in caught)


@settings(max_examples=30)
@given(word=HOSTILE)
def test_no_field_drives_the_terminal_of_a_run_summary(word: str) -> None:
    result = RunResult(
        seed=0,
        outcome=word,
        success=False,
        time=1.0,
        skills=[(f"T/{word}", 0.5)],
        measurements={f"m{word}": word, "depth": 0.1},
        fault=word,
        active=(f"T/{word}",),
        video=word,
    )
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        display.show(f"T{word}", result)
        display.show_seeds(f"T{word}", word, [result])
    assert not acts_on_a_terminal(out.getvalue())
