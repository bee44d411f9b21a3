"""File names of generated outputs that no two statecharts can share, on any file system.

A target names its files after statecharts. Two of them must never become one file: not
by equal names (two charts ``Twin`` in two packages), not on a file system that ignores case
or normalises Unicode (``Kase`` and ``KASE``), and no name may exceed what a file system
takes. So a file is named after a chart's simple name where no other chart of the run has
a name that folds alike, else after its qualified name; a stem too long for a file name is
cut and ends in a digest of the whole; paths that still fold into one are a generation
error at the statechart, never an overwrite.
"""

from __future__ import annotations

import hashlib
import unicodedata
from collections.abc import Iterable

from lightrocks.languages.lightrocks.model import Component
from lightrocks.workbench.generators import GenerationError

MAX_STEM_BYTES = 200
"""Below the 255 bytes a file name may have on common file systems, leaving room for a
suffix (``.st``, ``.svg``) and for the names tools derive from it (MatIEC's ``<name>.c``)."""
DIGEST = 10  # hex digits of the digest that keeps two shortened names apart


def fold(name: str) -> str:
    """What a case-insensitive file system, or an IEC 61131-3 identifier, makes of ``name``."""
    return unicodedata.normalize("NFKC", name).casefold()


def shortened(stem: str, limit: int = MAX_STEM_BYTES) -> str:
    """``stem`` itself within ``limit`` UTF-8 bytes, else its start and a digest of all of it."""
    if len(stem.encode("utf-8")) <= limit:
        return stem
    digest = hashlib.sha256(stem.encode("utf-8")).hexdigest()[:DIGEST]
    start = stem.encode("utf-8")[: limit - DIGEST - 1].decode("utf-8", errors="ignore")
    return f"{start}_{digest}"


def chart_stems(components: Iterable[Component], qualified: bool = False) -> dict[str, str]:
    """Qualified name -> the stem of the files of that chart: its simple name where no other
    chart's name folds alike (unless ``qualified``), else its qualified name; shortened."""
    components = list(components)
    folded = [fold(c.name) for c in components]
    stems = {}
    for component, key in zip(components, folded, strict=True):
        alone = not qualified and folded.count(key) == 1
        stems[component.qualified_name] = shortened(
            component.name if alone else component.qualified_name
        )
    return stems


def distinct(paths: dict[str, Component | None]) -> None:
    """Stop where two output paths (or two of their folders) fold into one: on a file system
    that ignores case one would overwrite the other. ``paths`` maps each relative path to
    the statechart it is written for (None: a file of the whole run)."""
    seen: dict[str, tuple[str, Component | None]] = {}
    for path, component in sorted(paths.items()):
        parts = path.split("/")
        for depth in range(1, len(parts) + 1):
            claimed = "/".join(parts[:depth])
            earlier, owner = seen.setdefault(fold(claimed), (claimed, component))
            if earlier != claimed:
                raise GenerationError(_collision(claimed, component, earlier, owner))
            if len(parts[depth - 1].encode("utf-8")) > 255:
                where = f"{component.statechart.position}: " if component else ""
                raise GenerationError(f"{where}output name '{claimed}' is longer than 255 bytes")


def _collision(path: str, component: Component | None, other: str, owner: Component | None) -> str:
    where = f"{component.statechart.position}: " if component else ""
    there = f" (statechart {owner.qualified_name} at {owner.statechart.position})" if owner else ""
    return (
        f"{where}output '{path}' and '{other}'{there} differ only in case or in Unicode "
        "normalisation: on many file systems they are one file; rename one of the statecharts"
    )
