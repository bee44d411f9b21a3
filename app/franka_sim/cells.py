"""Which scene a ``franka-sim`` argument names: a registered scene, or a cell file (``.lrd``)
whose cell carries ``<<scene="…">>``."""

from __future__ import annotations

from pathlib import Path

from lightrocks.adapters.scene_registry import scenes
from lightrocks.metamodel import ast
from lightrocks.workbench import report
from lightrocks.workbench.diagnostics import Diagnostics
from lightrocks.workbench.modelpath import ModelPath
from lightrocks.workbench.workspace import Workspace

CELL_SUFFIX = ".lrd"


class CellError(ValueError):
    """The argument is neither a registered scene nor a cell file with one scene."""


def scene_of(argument: str) -> str:
    """The registered scene that ``argument`` names, directly or through its cell file."""
    if argument in scenes():
        return argument
    path = Path(argument)
    if path.suffix != CELL_SUFFIX:
        raise CellError(
            f"{argument!r} is neither a scene ({', '.join(sorted(scenes()))}) "
            f"nor a cell file ({CELL_SUFFIX})"
        )
    if not path.is_file():
        raise CellError(f"no such cell file: {argument}")
    named = {_scene(cell) for cell in _cells(path)} - {None}
    if not named:
        raise CellError(f'{argument}: no cell with a <<scene="…">> stereotype')
    if len(named) > 1:
        raise CellError(f"{argument}: cells of several scenes ({', '.join(sorted(named))})")
    [name] = named
    if name not in scenes():
        raise CellError(f"{argument}: unknown scene {name!r}; known: {', '.join(sorted(scenes()))}")
    return name


def _cells(path: Path) -> list[ast.Cell]:
    diagnostics = Diagnostics()
    loaded = Workspace(ModelPath([path.parent]), diagnostics).load(path)
    if loaded is None:
        first = diagnostics.items()[0] if diagnostics.items() else None
        detail = report.printable(first.message) if first is not None else "does not load"
        raise CellError(f"{path}: {detail}")
    return [n for _, n in loaded.language.declarations(loaded.unit) if isinstance(n, ast.Cell)]


def _scene(cell: ast.Cell) -> str | None:
    return next((s.value for s in cell.stereotypes if s.name == "scene"), None)
