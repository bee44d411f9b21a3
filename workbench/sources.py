"""Digests of source code: an editable install changes the code without changing any version,
and every cache keyed by code (parse results, findings, generated packages) must notice."""

from __future__ import annotations

import hashlib
from collections.abc import Iterable
from pathlib import Path


def sources_digest(places: Iterable[Path], suffixes: tuple[str, ...]) -> str:
    """A digest of the files with ``suffixes`` in the folders (searched recursively) or
    files ``places``: each file's path and bytes, in a fixed order."""
    digest = hashlib.sha256()
    for place in sorted(set(places)):
        files = sorted(place.rglob("*")) if place.is_dir() else [place]
        for path in files:
            if path.suffix in suffixes and "__pycache__" not in path.parts:
                digest.update(str(path).encode("utf-8", "surrogateescape") + b"\x00")
                digest.update(path.read_bytes() + b"\x00")
    return digest.hexdigest()
