"""The model path: folders whose sub-folders are packages, MontiCore style.

A model ``a.b.C`` lives in ``<root>/a/b/C.<ext>``; declarations of package ``a.b`` may also
live in any file of ``<root>/a/b/`` whose language holds several declarations per file. The
registered languages' libraries follow the user's roots on every model path.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from pathlib import Path

from lightrocks.workbench.languages import libraries


class ModelPath:
    def __init__(self, roots: Iterable[Path]) -> None:
        unique = dict.fromkeys(root.resolve() for root in roots)
        added = [library for library in libraries() if library not in unique]
        self.roots = [*unique, *added]
        self._libraries = len(added)  # the last roots: add_root puts a root before them
        self._packages: dict[Path, list[str]] = {}  # of each file asked, while roots stay

    def add_root(self, root: Path) -> None:
        """Add a folder the checked files imply (``root_for``); a check adds one per file,
        mostly the same few, so a root already on the path costs no resolution."""
        if root in self.roots:
            return
        root = root.resolve()
        if root not in self.roots:
            self.roots.insert(len(self.roots) - self._libraries, root)
            self._packages.clear()

    def package_folders(self, package: str) -> Iterator[Path]:
        """Existing folders of ``package`` in model-path order."""
        parts = package.split(".") if package else []
        for root in self.roots:
            folder = root.joinpath(*parts)
            if folder.is_dir():
                yield folder

    def packages_of(self, file: Path) -> list[str]:
        """The packages a file can be in: one per root that contains it."""
        found = self._packages.get(file)
        if found is None:
            real = file.resolve()
            found = self._packages[file] = [
                ".".join(real.parent.relative_to(root).parts)
                for root in self.roots
                if real.is_relative_to(root)
            ]
        return found


def in_library(file: Path) -> bool:
    """Whether a (resolved) file belongs to a registered language's library."""
    return any(file.is_relative_to(library) for library in libraries())


def root_for(file: Path, package: str) -> Path:
    """The model-path root implied by a file (resolved, as loading leaves it) and the
    package it declares."""
    folder = file.parent
    depth = len(package.split(".")) if package else 0
    for _ in range(depth):
        if folder.parent == folder:
            break
        folder = folder.parent
    return folder


def model_files(path: Path, extensions: tuple[str, ...]) -> list[Path]:
    """Model files below ``path`` (or ``path`` itself), sorted for deterministic output."""
    if path.exists() and not path.is_dir():
        return [path]  # a file, or something that is not one: reading it reports which
    return sorted(p for p in path.rglob("*") if p.suffix in extensions and p.is_file())
