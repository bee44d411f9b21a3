"""A check run: load the given models and what they import, then run every CoCo."""

from __future__ import annotations

import gc
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from lightrocks.workbench.cocos import CoCo
from lightrocks.workbench.diagnostics import Diagnostics
from lightrocks.workbench.extensions import language_extensions
from lightrocks.workbench.languages import extensions, languages
from lightrocks.workbench.modelpath import ModelPath, model_files, root_for
from lightrocks.workbench.workspace import Loaded, Workspace


@dataclass
class CheckContext:
    """What CoCos see: the workspace, the findings so far, and a cache for shared analyses."""

    workspace: Workspace
    diagnostics: Diagnostics
    cache: dict[str, Any] = field(default_factory=dict)


def all_cocos() -> list[CoCo]:
    """Every CoCo of every registered language and language extension, ordered by code."""
    found = [c for lang in (*languages(), *language_extensions()) for c in lang.cocos]
    unique = {id(c): c for c in found}
    return sorted(unique.values(), key=lambda c: c.code)


def load(
    paths: Iterable[Path],
    model_path: Iterable[Path] = (),
    texts: Mapping[Path, str] | None = None,
    only_given: bool = False,
    unchanged: Mapping[Path, Loaded] | None = None,
) -> CheckContext:
    """Parse the models below ``paths`` and everything they import.

    ``texts`` maps resolved paths to contents that replace the files on disk (editor buffers).
    With ``only_given``, CoCos report on the files below ``paths`` alone; what they import
    is loaded for its declarations. ``unchanged`` holds files loaded earlier and known not
    to have changed since: they are taken as they are instead of being read again.
    """
    paths = list(paths)
    diagnostics = Diagnostics()
    roots = [*model_path, *(p for p in paths if p.is_dir())]
    workspace = Workspace(ModelPath(roots), diagnostics, texts, unchanged)
    files = [f for p in paths for f in model_files(p, extensions())]
    if only_given:
        workspace.targets = dict.fromkeys(file.resolve() for file in files)
    for file in files:
        loaded = workspace.load(file)
        if loaded is not None:
            workspace.model_path.add_root(root_for(file, loaded.package))
    for loaded in workspace.checked_units():
        workspace.scope(loaded)
    return CheckContext(workspace, diagnostics)


def check(
    paths: Iterable[Path],
    model_path: Iterable[Path] = (),
    texts: Mapping[Path, str] | None = None,
    only_given: bool = False,
    unchanged: Mapping[Path, Loaded] | None = None,
) -> CheckContext:
    """Load and run every CoCo; all findings end up in ``context.diagnostics``."""
    context = load(paths, model_path, texts, only_given, unchanged)
    gc.freeze()  # the loaded models live to the end: keep the collector from rescanning them
    try:
        for coco in all_cocos():
            context.diagnostics.extend(coco.run(context))
    finally:
        gc.unfreeze()
    return context
