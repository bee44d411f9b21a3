"""The run cache is not trusted code: it lives in the user's cache folder, is keyed by the
LightRocks version and the generator's inputs, and an entry that does not match its manifest
is rebuilt, never imported."""

from __future__ import annotations

import sys
import threading
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

from lightrocks.app import cache, cachedir
from lightrocks.app.loading import component_class, generated_package
from lightrocks.workbench.check import check

from .fault_runs import DEADLINE, cli, within, write_models

CHART = """package t;

statechart Gate {
  parameters {
    Integer passed = 0;
  }

  initial state Closed;
  final state Open;

  Closed -> Open go / { passed = passed + 1; };
}
"""


@pytest.fixture
def model(tmp_path: Path) -> Path:
    write_models(tmp_path / "models", {"Gate": CHART})
    return tmp_path / "models" / "t" / "Gate.lr"


def load(model: Path, root: Path) -> type:
    """Import the chart's class afresh from the cache (as a new process would)."""
    for name in [m for m in sys.modules if m.startswith("lightrocks_")]:
        del sys.modules[name]
    context = check([model])
    return component_class(generated_package(context, [model], root), "t.Gate")


def runs(cls: type) -> bool:
    chart = cls().start()
    chart.send("go")
    return chart.outcome == "Open" and chart.passed == 1


def the_entry(root: Path) -> Path:
    (entry,) = [p for p in root.iterdir() if not p.name.startswith(".")]
    return entry


def test_cache_root_is_the_users_cache_folder(monkeypatch, tmp_path):
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert cachedir.cache_root() == tmp_path / "xdg" / "lightrocks"
    monkeypatch.delenv("XDG_CACHE_HOME")
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    monkeypatch.setenv("LOCALAPPDATA", str(tmp_path / "local"))
    assert cachedir.cache_root().parent in {
        tmp_path / "home" / ".cache",
        tmp_path / "home" / "Library" / "Caches",
        tmp_path / "local",
    }


def test_run_ignores_a_cache_planted_in_the_working_directory(tmp_path: Path, model: Path):
    planted = tmp_path / ".lightrocks-cache"
    marker = tmp_path / "planted-code-ran"
    for key in ("0" * 16, "f" * 16):
        (planted / key).mkdir(parents=True)
        (planted / key / "__init__.py").write_text(f"open({str(marker)!r}, 'w')\n")
    done = cli("run", str(model), "--events", "go", cwd=tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    assert not marker.exists()
    assert list((tmp_path / "cache" / "lightrocks").glob("*/manifest.json"))


def test_key_follows_version_and_inputs(monkeypatch):
    inputs = [("t/Gate.lr", CHART.encode())]
    key = cache.cache_key("python", inputs)
    assert cache.cache_key("python", [("t/Gate.lr", CHART.encode() + b" ")]) != key
    assert cache.cache_key("python", [("u/Gate.lr", CHART.encode())]) != key
    assert cache.cache_key("ecore", inputs) != key
    monkeypatch.setattr(cache, "version", lambda name: "999.0")
    assert cache.cache_key("python", inputs) != key


@pytest.mark.parametrize(
    "tamper",
    [
        pytest.param(
            lambda e, m: (e / "t" / "Gate.py").write_text(f"open({m!r}, 'w')\n"), id="edited"
        ),
        pytest.param(
            lambda e, m: (e / "evil.py").write_text(f"open({m!r}, 'w')\n"), id="extra-file"
        ),
        pytest.param(lambda e, m: (e / "t" / "Gate.py").unlink(), id="missing-file"),
        pytest.param(lambda e, m: (e / "manifest.json").write_text("{"), id="bad-manifest"),
        pytest.param(lambda e, m: (e / "manifest.json").unlink(), id="half-written"),
        pytest.param(
            lambda e, m: (
                (e / "__pycache__").mkdir() or (e / "__pycache__" / "x.pyc").write_bytes(b"")
            ),
            id="bytecode",
        ),
    ],
)
def test_corrupt_entry_is_rebuilt_not_imported(tmp_path: Path, model: Path, tamper):
    root = tmp_path / "cache"
    assert runs(load(model, root))
    entry = the_entry(root)
    marker = tmp_path / "tampered-code-ran"
    tamper(entry, str(marker))
    assert not cache.verified(entry)
    assert runs(load(model, root))
    assert not marker.exists()
    assert cache.verified(the_entry(root))


def test_entries_are_imported_without_writing_bytecode(tmp_path: Path, model: Path):
    root = tmp_path / "cache"
    assert runs(load(model, root))
    assert runs(load(model, root))
    assert not list(the_entry(root).rglob("__pycache__"))
    assert cache.verified(the_entry(root))


def test_leftover_staging_folder_and_partial_entry_do_not_poison_the_cache(tmp_path, model):
    root = tmp_path / "cache"
    assert runs(load(model, root))
    entry = the_entry(root)
    (root / ".lightrocks-killed").mkdir()  # a staging folder of a killed run
    (root / ".lightrocks-killed" / "__init__.py").write_text("")
    for path in entry.rglob("*.*"):  # as if killed after the first file
        if path != entry / "__init__.py":
            path.unlink()
    assert runs(load(model, root))


def test_processes_building_the_same_entry_at_once_all_get_a_good_one(tmp_path: Path):
    root, builders = tmp_path / "cache", 4
    together = threading.Barrier(builders)

    def generate() -> dict[str, str]:
        together.wait(DEADLINE)  # everyone has found the entry missing
        return {"__init__.py": "", "t/Gate.py": "X = 1\n"}

    found = within(
        lambda: list(
            ThreadPoolExecutor(builders).map(
                lambda _: cache.entry(root, "k" * 32, generate), range(builders)
            )
        )
    )
    assert found == [root / ("k" * 32)] * builders
    assert cache.verified(root / ("k" * 32))
    assert [p.name for p in root.iterdir()] == ["k" * 32]  # no staging folder left


def test_threads_loading_one_model_at_once_never_see_it_half_imported(tmp_path, model):
    root, loaders = tmp_path / "cache", 8
    context = check([model])
    for _ in range(5):  # the import races the others' lookups; a few rounds show a lost race
        for name in [m for m in sys.modules if m.startswith("lightrocks_")]:
            del sys.modules[name]
        together = threading.Barrier(loaders)

        def load_at_once(_: int, together: threading.Barrier = together) -> type:
            together.wait(DEADLINE)
            return component_class(generated_package(context, [model], root), "t.Gate")

        classes = within(
            lambda: list(ThreadPoolExecutor(loaders).map(load_at_once, range(loaders)))
        )
        assert len(set(classes)) == 1
        assert runs(classes[0])
