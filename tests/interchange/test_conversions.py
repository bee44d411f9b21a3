"""Conversions are an extension point: descriptors registered through the
``lightrocks.conversions`` entry points, loaded by name, listed by ``lightrocks list
conversions``, and the only way ``lightrocks convert`` finds one."""

from __future__ import annotations

from importlib.metadata import EntryPoint
from pathlib import Path

import pytest

from lightrocks.app.cli import main
from lightrocks.workbench import conversions as registry
from lightrocks.workbench.conversions import (
    GROUP,
    Conversion,
    ConversionError,
    Converted,
    conversions,
    load_conversion,
)


def _upper(path: Path, text: str, shown: str) -> Converted:
    return Converted(f"{path.stem}.lr", text.upper())


UPPER = Conversion(".txt", "lr", "shouting text, for the test", _upper)
HERE = __name__


def test_the_shipped_conversions_are_registered() -> None:
    found = {c.name: (c.source, c.target) for c in conversions()}
    assert found == {
        "sc-to-lr": (".sc", "lr"),
        "lr-to-sc": (".lr", "sc"),
        "scxml-to-lr": (".scxml", "lr"),
    }
    assert all(c.description for c in conversions())


def test_list_conversions(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["list", "conversions"]) == 0
    out = capsys.readouterr().out
    assert "sc-to-lr  .sc -> .lr  UML/P statecharts (MontiCore) to LightRocks" in out
    assert "scxml-to-lr  .scxml -> .lr  SCXML (W3C)" in out


@pytest.fixture
def registered(monkeypatch: pytest.MonkeyPatch):
    """``registered(name, value)``: one more entry in the ``lightrocks.conversions`` group."""
    shipped = registry.entry_points(group=GROUP)

    def register(name: str, value: str) -> None:
        extra = [EntryPoint(name, value, GROUP)]
        monkeypatch.setattr(registry, "entry_points", lambda group: [*shipped, *extra])

    return register


def test_a_registered_conversion_is_used_by_convert(
    registered, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    registered("txt-to-lr", f"{HERE}:UPPER")
    source = tmp_path / "Note.txt"
    source.write_text("statechart a {}\n")
    assert main(["convert", str(source), "--to", "lr"]) == 0
    assert (tmp_path / "Note.lr").read_text() == "STATECHART A {}\n"
    assert main(["list", "conversions"]) == 0
    assert "txt-to-lr  .txt -> .lr  shouting text, for the test" in capsys.readouterr().out


@pytest.mark.parametrize(
    ("value", "message"),
    [
        (f"{HERE}:NOTHING", "conversion 'txt-to-lr' cannot be loaded"),
        ("lightrocks.no_such_module:X", "conversion 'txt-to-lr' cannot be loaded"),
        ("lightrocks.languages.umlp.interchange:SC_TO_LR", "is not a txt-to-lr Conversion"),
    ],
    ids=["missing-name", "missing-module", "name-disagrees"],
)
def test_a_broken_registration_is_a_usage_error(
    registered, tmp_path: Path, capsys: pytest.CaptureFixture[str], value: str, message: str
) -> None:
    registered("txt-to-lr", value)
    with pytest.raises(ConversionError, match=message):
        load_conversion(".txt", "lr")
    source = tmp_path / "Note.txt"
    source.write_text("x\n")
    assert main(["convert", str(source), "--to", "lr"]) == 2
    captured = capsys.readouterr()
    assert message in captured.err and "Traceback" not in captured.err
    assert not (tmp_path / "Note.lr").exists()
    assert main(["list", "conversions"]) == 2
    assert message in capsys.readouterr().err


def test_a_file_without_suffix_names_what_is_known(tmp_path: Path) -> None:
    with pytest.raises(ConversionError) as raised:
        load_conversion("", "lr")
    assert str(raised.value) == (
        "no conversion from a file without suffix to .lr; "
        "known: .lr -> .sc, .sc -> .lr, .scxml -> .lr"
    )
