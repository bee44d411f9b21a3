"""Generator options: declared by each target (name, type, default, doc), read once from
``--option NAME=VALUE`` against that declaration, listed by ``lightrocks list generators``;
an unknown option or a bad value is a clear error with exit code 1 and nothing written."""

from __future__ import annotations

from pathlib import Path

import pytest
from generation import EXAMPLES, SCREW_IN, SCREW_TASK

from lightrocks.app.cli import main
from lightrocks.app.specs import generate_spec
from lightrocks.workbench.generators import (
    OptionError,
    declared_options,
    generator_names,
    load_generator,
    parse_options,
)


@pytest.mark.parametrize("target", generator_names())
def test_every_option_is_documented_and_its_default_reads_back(target: str) -> None:
    generator = load_generator(target)
    for option in declared_options(generator):
        assert option.name.isidentifier() and option.kind and option.doc, option
        assert option.read(str(option.default)) == option.default


def test_defaults_fill_what_is_not_given() -> None:
    assert parse_options(load_generator("dot"), {}) == {"depth": 0, "render": "", "levels": ""}
    assert parse_options(load_generator("sfc"), {"interval_ms": "4"}) == {"interval_ms": 4}
    assert parse_options(load_generator("python"), {}) == {}


@pytest.mark.parametrize(
    ("target", "given"),
    [("dot", {"render": ""}), ("dot", {"levels": ""}), ("dot", {"depth": "12"})],
    ids=["render-off", "levels-off", "depth"],
)
def test_accepted_words_stay_accepted(target: str, given: dict[str, str]) -> None:
    parse_options(load_generator(target), given)


@pytest.mark.parametrize(
    ("target", "given", "message"),
    [
        ("dot", {"depth": "-1"}, "option depth='-1' is not a whole number >= 0"),
        ("dot", {"depth": "²"}, "option depth='²' is not a whole number >= 0"),
        ("dot", {"render": "gif"}, "option render='gif': choose one of svg, png"),
        ("dot", {"levels": "no"}, "option levels='no': the only value is 'yes'"),
        ("sfc", {"interval_ms": "0"}, "option interval_ms='0' is not a whole number > 0"),
        ("plcopen", {"interval_ms": "1.5"}, "option interval_ms='1.5' is not a whole number > 0"),
        ("dot", {"dpeth": "1"}, "target 'dot' has no option 'dpeth'; its options: depth, render"),
        ("python", {"depth": "1"}, "target 'python' has no option 'depth'; it takes no options"),
    ],
)
def test_unknown_options_and_bad_values(target: str, given: dict[str, str], message: str) -> None:
    with pytest.raises(OptionError) as raised:
        parse_options(load_generator(target), given)
    assert str(raised.value).startswith(message)


def test_the_spec_holds_the_values_read() -> None:
    spec = generate_spec([SCREW_IN], [EXAMPLES], "dot", {"depth": "2", "render": "svg"})
    assert spec.options == {"depth": 2, "render": "svg", "levels": ""}


def _generate(tmp_path: Path, target: str, *options: str) -> int:
    out = tmp_path / "out"
    args = [str(SCREW_TASK), "--path", str(EXAMPLES), "--target", target, "-o", str(out)]
    return main(["generate", *args, *(part for o in options for part in ("--option", o))])


@pytest.mark.parametrize(
    ("target", "option", "message"),
    [
        ("sfc", "intervall_ms=4", "target 'sfc' has no option 'intervall_ms'"),
        ("python", "render=svg", "target 'python' has no option 'render'; it takes no options"),
        ("dot", "depth=two", "option depth='two' is not a whole number >= 0"),
    ],
)
def test_the_command_line_refuses_with_exit_1_and_writes_nothing(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], target: str, option: str, message: str
) -> None:
    assert _generate(tmp_path, target, option) == 1
    captured = capsys.readouterr()
    assert f"lightrocks: error: {message}" in captured.err
    assert "Traceback" not in captured.err + captured.out
    assert not (tmp_path / "out").exists()


def test_an_option_is_refused_before_the_models_are_checked(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    broken = tmp_path / "Broken.lr"
    broken.write_text("statechart Broken { state }\n")
    args = [str(broken), "--target", "sfc", "-o", str(tmp_path / "out")]
    assert main(["generate", *args, "--option", "interval_ms=fast"]) == 1
    captured = capsys.readouterr()
    assert "option interval_ms='fast'" in captured.err
    assert "LR0001" not in captured.out


def test_list_generators_shows_the_options(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["list", "generators"]) == 0
    listed = capsys.readouterr().out
    assert "    --option depth: whole number >= 0, default 0; also draw the content" in listed
    assert "    --option render: svg|png; also draw each .dot file" in listed
    assert "    --option interval_ms: whole number > 0, default 1; the task cycle" in listed
