"""The ``lightrocks`` command line: exit codes, output formats, listing, formatting, textX.

Exit codes: 0 clean, 1 findings, 2 wrong use of the command line.
"""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
from importlib.metadata import version
from pathlib import Path

import pytest

from lightrocks.app.cli import main
from lightrocks.workbench.check import all_cocos

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
TURNSTILE = EXAMPLES / "plain" / "Turnstile.lr"


@pytest.fixture
def broken(tmp_path: Path) -> Path:
    """A copy of the plain Turnstile whose transition targets a misspelled state."""
    folder = tmp_path / "plain"
    folder.mkdir()
    text = TURNSTILE.read_text(encoding="utf-8")
    assert "Maintenance -> Operating resume;" in text
    text = text.replace("Maintenance -> Operating resume;", "Maintenance -> Operatng resume;")
    (folder / "Turnstile.lr").write_text(text, encoding="utf-8")
    return folder


def run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    status = main(list(argv))
    captured = capsys.readouterr()
    return status, captured.out, captured.err


# -- exit codes ---------------------------------------------------------------------------------


def test_check_examples_is_clean(capsys: pytest.CaptureFixture[str]) -> None:
    status, out, err = run(capsys, "check", str(EXAMPLES))
    assert status == 0, out + err
    assert out.strip().endswith("0 error(s), 0 warning(s)")


def test_check_broken_model_exits_1(broken: Path, capsys: pytest.CaptureFixture[str]) -> None:
    status, out, _ = run(capsys, "check", str(broken))
    assert status == 1
    assert re.search(r"Turnstile\.lr:\d+:\d+: error LR0110: unknown state or condition", out)
    assert "did you mean 'Operating'?" in out


def test_check_missing_path_exits_2(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    status, out, err = run(capsys, "check", str(tmp_path / "nowhere"))
    assert status == 2
    assert "no such file or folder" in err
    assert "Traceback" not in out + err


def test_check_missing_model_path_exits_2(capsys: pytest.CaptureFixture[str]) -> None:
    status, _, err = run(capsys, "check", str(TURNSTILE), "--path", "/no/such/root")
    assert status == 2
    assert "no such file or folder" in err


@pytest.mark.parametrize(
    "argv",
    [
        ["check", str(TURNSTILE), "--no-such-option"],
        ["check"],
        ["check", str(TURNSTILE), "--format", "xml"],
        ["frobnicate"],
        [],
    ],
    ids=["unknown-option", "no-paths", "unknown-format", "unknown-command", "nothing"],
)
def test_usage_errors_exit_2(argv: list[str], capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exit_info:
        main(argv)
    assert exit_info.value.code == 2
    captured = capsys.readouterr()
    assert "usage: lightrocks" in captured.err
    assert "Traceback" not in captured.err


def test_usage_error_exits_2_as_a_process() -> None:
    result = subprocess.run(
        [
            sys.executable,
            "-m",
            "lightrocks.app.cli",
            "check",
            "--no-such-option",
            str(TURNSTILE),
        ],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert result.returncode == 2
    assert "Traceback" not in result.stderr


def test_version(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exit_info:
        main(["--version"])
    assert exit_info.value.code == 0
    assert capsys.readouterr().out.strip() == version("lightrocks")


# -- output formats -----------------------------------------------------------------------------


def test_json_format(broken: Path, capsys: pytest.CaptureFixture[str]) -> None:
    status, out, _ = run(capsys, "check", str(broken), "--format", "json")
    assert status == 1
    items = json.loads(out)
    assert items
    for item in items:
        assert {"file", "line", "column", "code", "severity", "message", "hint"} <= set(item)
        assert re.fullmatch(r"LR\d{4}", item["code"])
        assert item["line"] >= 1 and item["column"] >= 1
    assert any(i["code"] == "LR0110" and i["hint"] == "did you mean 'Operating'?" for i in items)


def test_json_format_clean_is_an_empty_list(capsys: pytest.CaptureFixture[str]) -> None:
    status, out, _ = run(capsys, "check", str(EXAMPLES), "--format", "json")
    assert status == 0
    assert json.loads(out) == []


def test_sarif_format(broken: Path, capsys: pytest.CaptureFixture[str]) -> None:
    status, out, _ = run(capsys, "check", str(broken), "--format", "sarif")
    assert status == 1
    document = json.loads(out)
    assert document["version"] == "2.1.0"
    assert "sarif" in document["$schema"] and "2.1.0" in document["$schema"]
    run0 = document["runs"][0]
    driver = run0["tool"]["driver"]
    assert driver["name"] == "lightrocks"
    rules = {rule["id"] for rule in driver["rules"]}
    results = run0["results"]
    assert results
    for result in results:
        assert result["ruleId"] in rules
        assert result["level"] in ("error", "warning", "note")
        assert result["message"]["text"]
        location = result["locations"][0]["physicalLocation"]
        assert location["artifactLocation"]["uri"].endswith("Turnstile.lr")
        assert location["region"]["startLine"] >= 1
        assert location["region"]["startColumn"] >= 1
    assert "LR0110" in {r["ruleId"] for r in results}
    assert all(rule["shortDescription"]["text"] for rule in driver["rules"])


def test_github_format(broken: Path, capsys: pytest.CaptureFixture[str]) -> None:
    status, out, _ = run(capsys, "check", str(broken), "--format", "github")
    assert status == 1
    lines = out.strip().splitlines()
    assert lines
    pattern = re.compile(
        r"^::(error|warning|notice) file=[^,]+Turnstile\.lr,line=\d+,col=\d+,title=LR\d{4}::.+"
    )
    for line in lines:
        assert pattern.match(line), line
    assert any(line.startswith("::error ") and "title=LR0110" in line for line in lines)


# -- list -----------------------------------------------------------------------------------------


def test_list_cocos_lists_every_code(capsys: pytest.CaptureFixture[str]) -> None:
    status, out, _ = run(capsys, "list", "cocos")
    assert status == 0
    listed = re.findall(r"^(LR\d{4})\s+(error|warning|info)\s+\S", out, re.MULTILINE)
    codes = [c.code for c in all_cocos()]
    assert [code for code, _ in listed] == codes
    assert {"LR0101", "LR0213", "LR0307", "LR0404"} <= set(codes)


def test_list_languages(capsys: pytest.CaptureFixture[str]) -> None:
    status, out, _ = run(capsys, "list", "languages")
    assert status == 0
    assert ".lr" in out and ".lrd" in out


# -- fmt ------------------------------------------------------------------------------------------


def _printer_ready() -> bool:
    try:
        from lightrocks.languages.lightrocks.printer import format_statechart_text  # noqa: F401
    except ImportError:
        return False
    return True


@pytest.mark.skipif(
    not _printer_ready(), reason="languages.lightrocks.printer.format_statechart_text not there yet"
)
def test_fmt_check_examples_is_clean(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    copy = tmp_path / "examples"
    shutil.copytree(EXAMPLES, copy)
    status, out, err = run(capsys, "fmt", "--check", str(copy))
    assert status == 0, out + err
    assert "would reformat" not in out
    assert [p.read_bytes() for p in sorted(copy.rglob("*")) if p.is_file()] == [
        p.read_bytes() for p in sorted(EXAMPLES.rglob("*")) if p.is_file()
    ]


def test_fmt_syntax_error_exits_1_and_changes_nothing(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    model = tmp_path / "plain" / "Turnstile.lr"
    model.parent.mkdir()
    text = TURNSTILE.read_text(encoding="utf-8").replace("final state Off;", "final state Off")
    model.write_text(text, encoding="utf-8")
    before = sorted(p.name for p in model.parent.iterdir())
    status, out, err = run(capsys, "fmt", str(model))
    assert status == 1
    assert re.search(r"Turnstile\.lr:\d+:\d+: error LR0001: syntax error", out)
    assert "Traceback" not in out + err
    assert model.read_text(encoding="utf-8") == text
    assert sorted(p.name for p in model.parent.iterdir()) == before


def test_fmt_missing_path_exits_2(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    status, _, err = run(capsys, "fmt", str(tmp_path / "nowhere.lr"))
    assert status == 2
    assert "no such file or folder" in err


# -- textX registration ---------------------------------------------------------------------------


def test_textx_registry_knows_lr_files() -> None:
    from textx import language_for_file, metamodel_for_language

    assert language_for_file("Turnstile.lr").name == "lightrocks"
    model = metamodel_for_language("lightrocks").model_from_file(str(TURNSTILE))
    assert model is not None


def test_textx_cli_checks_lr_files() -> None:
    textx = Path(sys.executable).with_name("textx")
    listing = subprocess.run(
        [str(textx), "list-languages"], capture_output=True, text=True, timeout=120
    )
    assert listing.returncode == 0, listing.stderr
    assert "lightrocks (*.lr)" in listing.stdout + listing.stderr  # textx lists on stderr
    result = subprocess.run(
        [str(textx), "check", str(TURNSTILE)], capture_output=True, text=True, timeout=120
    )
    assert result.returncode == 0, result.stdout + result.stderr
    assert "OK" in result.stdout + result.stderr
