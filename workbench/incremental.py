"""Incremental checking: after an edit, re-check only the files the edit can affect.

Two graphs say what an edit can affect. The *use* graph has an edge from a file to every
file whose declarations its names resolved to while it was checked. The *scope* graph has
an edge from a file to every file of the packages its names may resolve through: the
implicit library, its own package and the packages of its imports.

An edit that keeps the names a file declares (and their kinds) changes only what those
names mean: it affects the file and every file that reaches it in the use graph. An edit
that adds, removes or re-kinds a name may change how names resolve anywhere in its scope:
it affects every file that reaches it in the scope graph or the use graph. Only affected
files are loaded and checked again (parsing is answered by the content-keyed parse cache);
the findings of all other files are kept from the previous run.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from functools import cache, partial
from pathlib import Path

import networkx as nx

from lightrocks.workbench.check import CheckContext, check
from lightrocks.workbench.diagnostics import Diagnostic, Diagnostics
from lightrocks.workbench.languages import extensions, implicit_packages, libraries
from lightrocks.workbench.modelpath import ModelPath
from lightrocks.workbench.workspace import Loaded, Workspace, shown_name


class IncrementalCheck:
    """Findings of a set of models, kept current as files change."""

    def __init__(self, paths: Iterable[Path], model_path: Iterable[Path] = ()) -> None:
        self.paths = [Path(p) for p in paths]
        self.model_path = [Path(p) for p in model_path]
        self.texts: dict[Path, str] = {}
        self.graph: nx.DiGraph = nx.DiGraph()  # the scope graph
        self.uses: nx.DiGraph = nx.DiGraph()
        self.interfaces: dict[Path, frozenset[tuple[str, str]] | None] = {}
        self.findings: dict[str, list[Diagnostic]] = {}
        self.context: CheckContext | None = None
        self.package_files: Callable[[str], frozenset[Path]] = frozenset
        self.rechecked: set[Path] = set()
        self.loaded: dict[Path, Loaded] = {}  # the latest load of every file, for reuse

    def full(self) -> list[Diagnostic]:
        """Check everything and rebuild the dependency graph."""
        self.context = check(self.paths, self.model_path, self.texts)
        workspace = self.context.workspace
        self.model_path = [root for root in workspace.model_path.roots if root not in libraries()]
        self.package_files = cache(partial(_package_files, workspace))
        self.graph = dependency_graph(workspace, self.package_files)
        self.uses = nx.DiGraph()
        self.uses.add_nodes_from(self.graph)
        self._record(workspace, self.graph)
        self.loaded = _loaded(workspace)
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
        wide = any(self._parsed_interface(path) != self.interfaces.get(path) for path in changed)
        affected = self._affected(changed, wide)
        unchanged = {p: f for p, f in self.loaded.items() if p not in changed}
        context = check(sorted(affected), self.model_path, self.texts, True, unchanged)
        workspace = context.workspace
        shown = {shown_name(path) for path in affected}
        for file in shown:
            self.findings.pop(file, None)
        for finding in context.diagnostics.items:
            if finding.file in shown:
                self.findings.setdefault(finding.file, []).append(finding)
        for path in changed:  # only an edited file can have changed its imports
            self.graph.remove_edges_from(list(self.graph.out_edges(path)))
            found = dependencies(workspace, path, self.package_files)
            self.graph.add_edges_from((path, dep) for dep in found)
        self._record(workspace, affected)
        for path in changed:
            self.loaded.pop(path, None)
        self.loaded.update(_loaded(workspace))
        self.context = context
        self.rechecked = affected
        return self.items

    def _affected(self, changed: Mapping[Path, str | None], wide: bool) -> set[Path]:
        affected = set(changed)
        for path in changed:
            affected |= nx.ancestors(self.uses, path)
            if wide:
                affected |= nx.ancestors(self.graph, path)
        if wide:  # files that used an affected file are affected in turn
            for path in list(affected):
                affected |= nx.ancestors(self.uses, path)
        return affected

    def _parsed_interface(self, path: Path) -> frozenset[tuple[str, str]] | None:
        """What an edited file declares now, from a parse of it alone (the parse cache keeps
        the check that follows from parsing it again)."""
        alone = Workspace(ModelPath([]), Diagnostics(), self.texts)
        alone.load(path)
        return _interface(alone, path)

    def _record(self, workspace: Workspace, checked: Iterable[Path]) -> None:
        """Take the uses and interfaces of checked files from the run that checked them."""
        for path in checked:
            self.uses.remove_edges_from(list(self.uses.out_edges(path)))
            self.uses.add_edges_from((path, used) for used in workspace.uses.get(path, ()))
            self.interfaces[path] = _interface(workspace, path)

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
    packages = set(implicit_packages()) | set(workspace.model_path.packages_of(path))
    if isinstance(loaded, Loaded):
        packages.add(loaded.package)
        for imported in loaded.unit.imports:
            packages.add(imported.name if imported.wildcard else imported.name.rpartition(".")[0])
    files = set().union(*(package_files(package) for package in packages))
    files.discard(path)
    return files


def _loaded(workspace: Workspace) -> dict[Path, Loaded]:
    return {path: loaded for path, loaded in workspace.files.items() if loaded is not None}


def _interface(workspace: Workspace, path: Path) -> frozenset[tuple[str, str]] | None:
    loaded = workspace.files.get(path)
    return workspace.interface(loaded) if isinstance(loaded, Loaded) else None


def _package_files(workspace: Workspace, package: str) -> frozenset[Path]:
    return frozenset(
        file.resolve()
        for folder in workspace.model_path.package_folders(package)
        for file in folder.iterdir()
        if file.suffix in extensions() and file.is_file()
    )
