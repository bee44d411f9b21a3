"""The kernel learns libraries and implicit packages from the registered languages: a
language that brings a library puts it on every model path, and the packages it names are
seen by every file without an import."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest

from lightrocks.languages.domain import LANGUAGE as DOMAIN
from lightrocks.languages.domain import LIBRARY
from lightrocks.workbench import languages as registry
from lightrocks.workbench.check import check
from lightrocks.workbench.modelpath import ModelPath, in_library

CHART = """package app;

statechart Reach {
  parameters {
    Span span = 0 mm;
  }

  initial state Idle;
}
"""


@pytest.fixture
def kit(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A language registered beside the others whose library holds package ``kit``."""
    library = tmp_path / "kit-library"
    (library / "kit").mkdir(parents=True)
    (library / "kit" / "Units.lrd").write_text("package kit;\n\nquantity Span [m];\n")
    kit = dataclasses.replace(
        DOMAIN, name="kit", extensions=(), cocos=(), library=library, implicit_packages=("kit",)
    )
    registered = registry.languages()
    monkeypatch.setattr(registry, "languages", lambda: (*registered, kit))
    registry.libraries.cache_clear()
    registry.implicit_packages.cache_clear()
    yield library.resolve()
    registry.libraries.cache_clear()
    registry.implicit_packages.cache_clear()


def test_the_domain_language_declares_the_library_and_its_implicit_package() -> None:
    assert registry.libraries() == (LIBRARY,)
    assert registry.implicit_packages() == ("lightrocks",)


def test_a_registered_library_follows_the_users_roots(kit: Path, tmp_path: Path) -> None:
    model_path = ModelPath([tmp_path / "models"])
    assert model_path.roots == [(tmp_path / "models").resolve(), LIBRARY, kit]
    model_path.add_root(tmp_path / "more")
    assert model_path.roots[1:] == [(tmp_path / "more").resolve(), LIBRARY, kit]
    assert in_library(kit / "kit" / "Units.lrd") and not in_library(tmp_path / "A.lr")


def test_an_implicit_package_is_seen_without_an_import(kit: Path, tmp_path: Path) -> None:
    chart = tmp_path / "models" / "app" / "Reach.lr"
    chart.parent.mkdir(parents=True)
    chart.write_text(CHART)
    findings = check([chart], [tmp_path / "models"]).diagnostics.items
    assert [f for f in findings if "Span" in f.message] == []
