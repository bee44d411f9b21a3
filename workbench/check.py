"""A check run: load the given models and what they import, then run every CoCo.

Analyses that several CoCos share are passes (:mod:`lightrocks.workbench.passes`), computed
once per run. A check of a workspace whose reads all still hold is answered by the findings cache
(:mod:`lightrocks.workbench.checkcache`) instead of running again."""

from __future__ import annotations

import gc
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, TypeVar, cast

from lightrocks.workbench import checkcache
from lightrocks.workbench.cocos import CoCo, Code
from lightrocks.workbench.diagnostics import Diagnostics
from lightrocks.workbench.extensions import language_extensions
from lightrocks.workbench.languages import extensions, languages
from lightrocks.workbench.modelpath import ModelPath, model_files, root_for
from lightrocks.workbench.passes import Pass, report
from lightrocks.workbench.workspace import Loaded, Workspace

P = TypeVar("P", bound=Pass)


@dataclass
class CheckContext:
    """What CoCos see: the workspace, the findings so far, and the passes of this run."""

    workspace: Workspace
    diagnostics: Diagnostics
    _results: dict[type[Pass], Pass] = field(default_factory=dict, init=False, repr=False)

    def result(self, kind: type[P]) -> P:
        """The pass ``kind`` of this run, computed the first time it is asked for."""
        if kind not in self._results:
            self._results[kind] = kind(self)
        return cast(P, self._results[kind])


def all_cocos() -> list[Code]:
    """Every code a check reports, ordered by code: each CoCo and each code a pass declares,
    of every registered language and language extension."""
    codes = [code for check in _checks() for code in _codes(check)]
    return sorted(codes, key=lambda c: c.code)


def run_checks(context: CheckContext) -> None:
    """Run every CoCo and every pass that reports codes; their findings go to
    ``context.diagnostics``."""
    for check in _checks():
        if isinstance(check, CoCo):
            context.diagnostics.extend(check.run(context))
        else:
            context.diagnostics.extend(report(check, context))


def _checks() -> list[CoCo | type[Pass]]:
    """The CoCos and passes of every language and extension, ordered by (first) code."""
    registered = (*languages(), *language_extensions())
    found = [c for lang in registered for c in (*lang.cocos, *lang.passes)]
    unique = {id(c): c for c in found}
    return sorted(unique.values(), key=lambda c: min(code.code for code in _codes(c)))


def _codes(check: CoCo | type[Pass]) -> tuple[Code, ...]:
    return (check,) if isinstance(check, CoCo) else check.codes


def load(
    paths: Iterable[Path],
    model_path: Iterable[Path] = (),
    texts: Mapping[Path, str] | None = None,
    only_given: bool = False,
    unchanged: Mapping[Path, Loaded] | None = None,
    substituted: Mapping[Path, Any] | None = None,
) -> CheckContext:
    """Parse the models below ``paths`` and everything they import.

    ``texts`` maps resolved paths to contents that replace the files on disk (editor buffers).
    With ``only_given``, CoCos report on the files below ``paths`` alone; what they import
    is loaded for its declarations. ``unchanged`` holds files loaded earlier and known not
    to have changed since: they are taken as they are instead of being read again.
    ``substituted`` maps resolved paths to a text or a parsed unit that stands in for the
    file in this load only: neither the parse cache nor the findings cache keeps it.
    """
    paths = list(paths)
    diagnostics = Diagnostics()
    roots = [*model_path, *(p for p in paths if p.is_dir())]
    workspace = Workspace(ModelPath(roots), diagnostics, texts, unchanged, substituted)
    files = []
    for path in paths:
        found = model_files(path, extensions())
        workspace.reads.trees[str(path)] = [str(file) for file in found]
        files += found
    if only_given:
        workspace.targets = dict.fromkeys(file.resolve() for file in files)
    for file in files:
        loaded = workspace.load(file)
        if loaded is not None:
            workspace.model_path.add_root(root_for(loaded.path, loaded.package))
    for loaded in workspace.checked_units():
        workspace.scope(loaded)
    return CheckContext(workspace, diagnostics)


def check(
    paths: Iterable[Path],
    model_path: Iterable[Path] = (),
    texts: Mapping[Path, str] | None = None,
    only_given: bool = False,
    unchanged: Mapping[Path, Loaded] | None = None,
    substituted: Mapping[Path, Any] | None = None,
) -> CheckContext:
    """Load and run every CoCo; all findings end up in ``context.diagnostics``.

    The context of an earlier check with the same arguments is returned when everything
    that check read is unchanged; a check with ``substituted`` files (see :func:`load`) is
    always run, and never remembered."""
    paths, model_path, texts = list(paths), list(model_path), texts or {}
    entry = checkcache.key(paths, model_path, only_given)
    remembered = None if substituted else checkcache.recall(entry, texts)
    if remembered is not None:
        return remembered
    context = load(paths, model_path, texts, only_given, unchanged, substituted)
    gc.freeze()  # the loaded models live to the end: keep the collector from rescanning them
    try:
        run_checks(context)
    finally:
        gc.unfreeze()
    workspace = context.workspace
    workspace.reads.roots = [str(root) for root in workspace.model_path.roots]
    workspace.reads.extensions = list(extensions())
    checkcache.remember(entry, workspace.reads, context, context.diagnostics.items, texts)
    return context
