"""Model text reaches a terminal or a CI log as text: escape sequences are shown, not obeyed,
and a file name cannot add a workflow command."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from lightrocks.app.cli import main
from lightrocks.workbench.report import printable

TITLE = "\x1b]0;owned\x07"  # sets the terminal's title when printed raw
BROKEN = f"package t;\n\nstatechart S {{ {TITLE} }}\n"


@pytest.mark.parametrize("text", [TITLE, "a\nb\rc", "\u202eevil", "\x9b2J", "\u2028"])
def test_printable_leaves_no_control_or_format_character(text):
    shown = printable(text)
    assert shown.isprintable()
    assert printable("plain ÄÖ text: 12 mm") == "plain ÄÖ text: 12 mm"


def test_syntax_error_does_not_echo_escape_sequences(tmp_path: Path, capsys):
    model = tmp_path / "S.lr"
    model.write_text(BROKEN, encoding="utf-8")
    assert main(["check", str(model)]) == 1
    out = capsys.readouterr().out
    assert "\x1b" not in out and "\x07" not in out
    assert "\\x1b" in out


def test_file_name_with_escapes_is_shown_escaped(tmp_path: Path, capsys):
    model = tmp_path / f"S{TITLE}.lr"
    model.write_text("package t;\n\nstatechart   S{\ninitial state A;\n}\n", encoding="utf-8")
    main(["check", str(model)])
    main(["fmt", str(model)])
    captured = capsys.readouterr()
    for stream in (captured.out, captured.err):
        assert "\x1b" not in stream and "\x07" not in stream


def test_github_annotation_cannot_be_split_by_a_file_name(tmp_path: Path, capsys):
    name = "x\n::warning file=forged.lr::injected\n%0A,y:z.lr"
    model = tmp_path / name
    model.write_text(BROKEN, encoding="utf-8")
    assert main(["check", "--format", "github", str(model)]) == 1
    lines = capsys.readouterr().out.splitlines()
    assert len(lines) == 1
    assert lines[0].startswith("::error file=")
    assert "::warning" not in lines[0].split("::", 2)[1]  # the properties part
    properties = lines[0].split("::")[1]
    assert properties.count(",") == 3  # file, line, col, title: nothing forged
    assert "\x1b" not in lines[0]


def test_json_output_keeps_the_text_but_escaped(tmp_path: Path, capsys):
    model = tmp_path / "S.lr"
    model.write_text(BROKEN, encoding="utf-8")
    main(["check", "--format", "json", str(model)])
    out = capsys.readouterr().out
    assert "\x1b" not in out
    assert json.loads(out)[0]["file"] == str(model)
