"""The floors of docs/architecture.md and what each may import, proven by walking every
import of every module.

A module may import only the layers below it; the workbench kernel is below the languages
and generators, the application (``lightrocks.app``, a floor of its own) above everything,
and the generated code's support (``runtime``, ``adapters``) never reaches the language
tooling.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
FOLDERS = ("metamodel", "languages", "workbench", "generators", "runtime", "adapters", "app")
KERNEL, APP = "workbench", "app"

ALLOWED: dict[str, set[str]] = {
    "metamodel": set(),
    "runtime": set(),
    "adapters": {"runtime"},
    KERNEL: {"metamodel"},
    "languages": {"metamodel", KERNEL, "runtime"},
    "generators": {"metamodel", KERNEL, "languages", "runtime"},
    APP: {"metamodel", KERNEL, "languages", "generators", "runtime", "adapters"},
}


def layer(dotted: str) -> str | None:
    """The layer of a ``lightrocks.…`` module name."""
    parts = dotted.split(".")
    if parts[0] != "lightrocks" or len(parts) < 2:
        return None
    return parts[1]


def imported(path: Path) -> list[tuple[int, str]]:
    """Every module named by an import statement anywhere in ``path`` (lazy ones too)."""
    found = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            found += [(node.lineno, alias.name) for alias in node.names]
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            found.append((node.lineno, node.module))
            found += [(node.lineno, f"{node.module}.{alias.name}") for alias in node.names]
    return found


MODULES = sorted(p for folder in FOLDERS for p in (ROOT / folder).rglob("*.py"))


def own_layer(path: Path) -> str:
    relative = path.relative_to(ROOT).with_suffix("")
    return layer("lightrocks." + ".".join(relative.parts))


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(ROOT)))
def test_imports_only_go_down(path: Path) -> None:
    mine = own_layer(path)
    for line, name in imported(path):
        theirs = layer(name)
        assert name.split(".")[0] not in FOLDERS, f"{path}:{line}: '{name}' outside 'lightrocks'"
        if theirs is None or theirs == mine:
            continue
        assert theirs in ALLOWED[mine], f"{path}:{line}: {mine} must not import {name}"


def test_the_kernel_imports_no_language_and_no_generator() -> None:
    kernel = [p for p in MODULES if own_layer(p) == KERNEL]
    assert {p.stem for p in kernel} >= {"languages", "modelpath", "workspace", "diagnostics"}
    for path in kernel:
        for line, name in imported(path):
            assert layer(name) not in {"languages", "generators", APP}, f"{path}:{line}: {name}"


def test_the_walker_sees_a_violation(tmp_path: Path) -> None:
    module = tmp_path / "m.py"
    module.write_text("def f():\n    from lightrocks.app.cli import main\n")
    assert (2, "lightrocks.app.cli") in imported(module)
    assert APP not in ALLOWED[KERNEL]
