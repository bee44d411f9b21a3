"""Deterministic IEC 61131-3 identifiers: legal, not reserved, unique without regard to case."""

from __future__ import annotations

import re

from lightrocks.generators.sfc_iec61131.reserved import is_reserved


def legal(name: str) -> str:
    """Letters, digits and single underscores, not starting with a digit or ending in ``_``."""
    text = re.sub(r"[^A-Za-z0-9_]", "_", name)
    text = re.sub(r"_+", "_", text).strip("_") or "x"
    return f"x{text}" if text[0].isdigit() else text


class Namer:
    """Hands out names of one scope; a name already taken (any case) gets a suffix ``_2``…"""

    def __init__(self, taken: Namer | None = None) -> None:
        self._used: set[str] = set(taken._used) if taken else set()

    def claim(self, wanted: str) -> str:
        base = legal(wanted)
        if is_reserved(base):
            base = f"{base}_1"
        name, count = base, 1
        while name.upper() in self._used:
            count += 1
            name = f"{base}_{count}"
        self._used.add(name.upper())
        return name
