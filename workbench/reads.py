"""What a check read from disk: file contents, folder listings and the folders of packages.

Besides its arguments and the checking code, these reads are all a check's findings depend
on. Recorded while the check runs (each value is the one the check itself used), they tell
later whether the findings still hold: make every read again and compare.
"""

from __future__ import annotations

import hashlib
import os
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from lightrocks.workbench.modelpath import ModelPath, model_files


def digest(content: bytes) -> str:
    return hashlib.blake2b(content, digest_size=20).hexdigest()


SIZE_VARIABLE = "LIGHTROCKS_MODEL_BYTES"
DEFAULT_SIZE_LIMIT = 16 * 1024 * 1024
"""The largest model file read (bytes), a hundred times the largest example; a larger file
is a finding instead of memory that parsing it would run out of."""


def size_limit() -> int:
    """``LIGHTROCKS_MODEL_BYTES`` when it is a number of bytes, else ``DEFAULT_SIZE_LIMIT``."""
    setting = os.environ.get(SIZE_VARIABLE, "").strip()
    return int(setting) if setting.isdigit() else DEFAULT_SIZE_LIMIT


class TooLarge(OSError):
    """A model file over :func:`size_limit`."""

    def __init__(self, size: int, limit: int) -> None:
        super().__init__(
            f"the file is {size:,} bytes, over the limit of {limit:,} for a model "
            f"(set {SIZE_VARIABLE} to raise it)"
        )


def raw(path: Path, texts: Mapping[Path, str]) -> bytes:
    """The bytes of a model file: its editor buffer when there is one, else the file; a
    file over :func:`size_limit` is ``TooLarge`` before it is read."""
    limit = size_limit()
    if path in texts:
        data = texts[path].encode("utf-8", "surrogateescape")
        if len(data) > limit:
            raise TooLarge(len(data), limit)
        return data
    size = path.stat().st_size
    if size > limit:
        raise TooLarge(size, limit)
    return path.read_bytes()


def content(path: Path, texts: Mapping[Path, str]) -> bytes | None:
    """What a check reads for ``path``: ``None`` when it is not a regular file (a FIFO or
    device would block or never end) or cannot be read."""
    if not path.is_file():
        return None
    try:
        return raw(path, texts)
    except OSError:
        return None


def listing(folder: Path, extensions: Iterable[str]) -> list[str]:
    """The entries of a folder that matter to a check: model files, and sub-folders (written
    with a trailing ``/``), which name packages."""
    suffixes = tuple(extensions)
    entries = []
    for entry in sorted(folder.iterdir()):
        if entry.is_dir():
            entries.append(f"{entry.name}/")
        elif entry.suffix in suffixes and entry.is_file():
            entries.append(entry.name)
    return entries


@dataclass
class Reads:
    """Every read of one check, as plain data (stored as JSON between runs)."""

    files: dict[str, str | None] = field(default_factory=dict)
    """Path -> digest of the bytes read; ``None``: not a regular file, or unreadable."""
    trees: dict[str, list[str]] = field(default_factory=dict)
    """A path given to the check -> the model files found below it."""
    packages: dict[str, list[str]] = field(default_factory=dict)
    """Package -> its folders on the model path, in model-path order."""
    listings: dict[str, list[str]] = field(default_factory=dict)
    """Folder -> its :func:`listing`."""
    roots: list[str] = field(default_factory=list)
    """The model path the package folders were found on."""
    extensions: list[str] = field(default_factory=list)
    """The suffixes of model files, which the listings were made with."""
    links: dict[str, str] = field(default_factory=dict)
    """A path as found (a symlink, or relative) -> the file it resolved to."""
    complete: bool = True
    """False once the check took a file as given instead of reading it."""

    def file(self, path: Path, data: bytes | None) -> None:
        self.files[str(path)] = None if data is None else digest(data)

    def still_hold(self, texts: Mapping[Path, str]) -> bool:
        """Every read made again gives what the check read (``texts``: editor buffers)."""
        if not self.complete:
            return False
        extensions = tuple(self.extensions)
        try:
            for name, known in self.files.items():
                data = content(Path(name), texts)
                if (None if data is None else digest(data)) != known:
                    return False
            if any(str(Path(name).resolve()) != target for name, target in self.links.items()):
                return False
            for name, found in self.trees.items():
                if [str(f) for f in model_files(Path(name), extensions)] != found:
                    return False
            model_path = ModelPath(Path(root) for root in self.roots)
            for package, folders in self.packages.items():
                if [str(f) for f in model_path.package_folders(package)] != folders:
                    return False
            return all(
                listing(Path(name), extensions) == entries
                for name, entries in self.listings.items()
            )
        except OSError:
            return False

    def to_json(self) -> dict[str, Any]:
        return {
            "files": self.files,
            "trees": self.trees,
            "packages": self.packages,
            "listings": self.listings,
            "roots": self.roots,
            "extensions": self.extensions,
            "links": self.links,
        }

    @classmethod
    def from_json(cls, data: Any) -> Reads:
        """Reads stored by :meth:`to_json`; ``ValueError`` for anything else."""
        if not isinstance(data, dict) or set(data) != {*cls().to_json()}:
            raise ValueError("not a record of reads")
        files, links = data["files"], data["links"]
        if not isinstance(files, dict) or not all(
            isinstance(k, str) and (v is None or isinstance(v, str)) for k, v in files.items()
        ):
            raise ValueError("bad file digests")
        if not isinstance(links, dict) or not all(
            isinstance(k, str) and isinstance(v, str) for k, v in links.items()
        ):
            raise ValueError("bad links")
        names = {"roots": data["roots"], "extensions": data["extensions"]}
        if not all(_strings(value) for value in names.values()):
            raise ValueError("bad roots or extensions")
        lists = {name: data[name] for name in ("trees", "packages", "listings")}
        for mapping in lists.values():
            if not isinstance(mapping, dict) or not all(
                isinstance(k, str) and _strings(v) for k, v in mapping.items()
            ):
                raise ValueError("bad listing")
        return cls(files, **lists, **names, links=links)


def _strings(value: Any) -> bool:
    return isinstance(value, list) and all(isinstance(item, str) for item in value)
