"""A command whose part is not installed says which: an extra's package names the extra that
brings it, a part of LightRocks itself a broken installation (exit 1, no traceback)."""

from __future__ import annotations

from importlib.util import find_spec
from pathlib import Path

import pytest

from lightrocks.app import cli
from lightrocks.app.commands import common

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
TASK = [str(EXAMPLES / "screwing/tasks/ScrewTask.lr"), "--path", str(EXAMPLES), "--adapter=dryrun"]


@pytest.fixture
def absent(monkeypatch: pytest.MonkeyPatch):
    """``absent(*modules)``: those modules are not installed, as far as commands look."""

    def hide(*modules: str) -> None:
        def spec(name: str):
            return None if name in modules else find_spec(name)

        monkeypatch.setattr(common, "find_spec", spec)

    return hide


def test_the_studio_names_the_extra_its_web_server_comes_in(absent, capsys) -> None:
    absent("starlette")
    assert cli.main(["studio", str(EXAMPLES)]) == cli.EXIT_USAGE
    err = capsys.readouterr().err
    assert "the studio needs starlette: pip install 'lightrocks[monitor]'" in err


def test_a_studio_without_its_page_is_a_broken_installation(absent, capsys) -> None:
    absent("lightrocks.app.studio.page", "starlette")
    assert cli.main(["studio", str(EXAMPLES)]) == cli.EXIT_FINDINGS
    err = capsys.readouterr().err
    assert "the studio is missing from this installation of lightrocks" in err
    assert "lightrocks.app.studio.page not found" in err and "pip install" not in err


def test_the_monitor_names_what_it_lacks(absent, capsys) -> None:
    absent("websockets", "uvicorn")
    assert cli.main(["run", *TASK, "--monitor", "0"]) == cli.EXIT_USAGE
    err = capsys.readouterr().err
    assert "the monitor needs uvicorn, websockets: pip install 'lightrocks[monitor]'" in err


def test_a_module_of_lightrocks_missing_at_import_is_named(monkeypatch, capsys) -> None:
    def lost(args) -> int:
        name = "lightrocks.app.gone"
        raise ModuleNotFoundError(f"No module named '{name}'", name=name)

    configure, _ = common.COMMANDS["list"]
    monkeypatch.setitem(common.COMMANDS, "list", (configure, lost))
    assert cli.main(["list", "languages"]) == cli.EXIT_FINDINGS
    err = capsys.readouterr().err
    assert "lightrocks.app.gone is missing from this installation" in err
    assert "Traceback" not in err
