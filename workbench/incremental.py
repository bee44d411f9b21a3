"""Incremental checking: after an edit, re-check only the files the edit can affect.

A file depends on every file of the packages its names resolve through: the implicit
library, its own package and the packages of its imports. These dependencies form a graph;
an edit of one file affects that file and every file that reaches it in the graph. Only
those files are loaded and checked again (parsing is answered by the content-keyed parse
cache); the findings of all other files are kept from the previous run.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from functools import cache, partial
from pathlib import Path

import networkx as nx

from lightrocks.workbench.check import CheckContext, check
from lightrocks.workbench.diagnostics import Diagnostic
from lightrocks.workbench.languages import extensions
from lightrocks.workbench.modelpath import LIBRARY
from lightrocks.workbench.workspace import IMPLICIT_PACKAGES, Loaded, Workspace, _shown


class IncrementalCheck:
    """Findings of a set of models, kept current as files change."""

    def __init__(self, paths: Iterable[Path], model_path: Iterable[Path] = ()) -> None:
        self.paths = [Path(p) for p in paths]
        self.model_path = [Path(p) for p in model_path]
        self.texts: dict[Path, str] = {}
        self.graph: nx.DiGraph = nx.DiGraph()
        self.findings: dict[str, list[Diagnostic]] = {}
        self.context: CheckContext | None = None
        self.package_files: Callable[[str], frozenset[Path]] = frozenset
        self.rechecked: set[Path] = set()

    def full(self) -> list[Diagnostic]:
        """Check everything and rebuild the dependency graph."""
        self.context = check(self.paths, self.model_path, self.texts)
        workspace = self.context.workspace
        self.model_path = [root for root in workspace.model_path.roots if root != LIBRARY]
        self.package_files = cache(partial(_package_files, workspace))
        self.graph = dependency_graph(workspace, self.package_files)
        self.findings = {}
        for finding in self.context.diagnostics.items:
            self.findings.setdefault(finding.file, []).append(finding)
        self.rechecked = set(self.graph)
        return self.items

    def update(self, changed: Mapping[Path, str | None]) -> list[Diagnostic]:
        """Apply edits (new text, or ``None`` to read the file from disk again) and re-check."""
        changed = {path.resolve(): text for path, text in changed.items()}
        for path, text in changed.items():
            if text is None:
                self.texts.pop(path, None)
            else:
                self.texts[path] = text
        if self.context is None or any(path not in self.graph for path in changed):
            return self.full()
        affected = set(changed)
        for path in changed:
            affected |= nx.ancestors(self.graph, path)
        context = check(sorted(affected), self.model_path, self.texts)
        shown = {_shown(path) for path in affected}
        for file in shown:
            self.findings.pop(file, None)
        for finding in context.diagnostics.items:
            if finding.file in shown:
                self.findings.setdefault(finding.file, []).append(finding)
        for path in changed:  # only an edited file can have changed its imports
            self.graph.remove_edges_from(list(self.graph.out_edges(path)))
            found = dependencies(context.workspace, path, self.package_files)
            self.graph.add_edges_from((path, dep) for dep in found)
        self.context = context
        self.rechecked = affected
        return self.items

    @property
    def items(self) -> list[Diagnostic]:
        return sorted(d for findings in self.findings.values() for d in findings)


def dependency_graph(
    workspace: Workspace, package_files: Callable[[str], frozenset[Path]]
) -> nx.DiGraph:
    """An edge from each loaded file to every file it may resolve names through."""
    graph = nx.DiGraph()
    graph.add_nodes_from(workspace.files)
    for path in list(workspace.files):
        graph.add_edges_from((path, dep) for dep in dependencies(workspace, path, package_files))
    return graph


def dependencies(
    workspace: Workspace, path: Path, package_files: Callable[[str], frozenset[Path]]
) -> set[Path]:
    """The files of every package a file's names may resolve through."""
    loaded = workspace.files.get(path)
    packages = set(IMPLICIT_PACKAGES) | set(workspace.model_path.packages_of(path))
    if isinstance(loaded, Loaded):
        packages.add(loaded.package)
        for imported in loaded.unit.imports:
            packages.add(imported.name if imported.wildcard else imported.name.rpartition(".")[0])
    files = set().union(*(package_files(package) for package in packages))
    files.discard(path)
    return files


def _package_files(workspace: Workspace, package: str) -> frozenset[Path]:
    return frozenset(
        file.resolve()
        for folder in workspace.model_path.package_folders(package)
        for file in folder.iterdir()
        if file.suffix in extensions() and file.is_file()
    )
