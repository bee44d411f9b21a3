"""Deterministic IEC 61131-3 identifiers: legal, not reserved, and collision-free by construction.

IEC 61131-3 names ignore case, and MatIEC adds two traps of its own: a variable named like a
type is read as that type, and every step and action name becomes a C macro inside its block,
so it rewrites any member access of the same spelling. One ``Namer`` per compilation unit
and one per POU (``scope()``) keep three kinds apart whatever the order of the claims: unit
names (types, blocks, functions, globals), variable names (variables, fields, transitions)
and macro names (steps, actions). No name meets a name of another kind anywhere in the unit;
two variables or two macros only differ within their own POU.
"""

from __future__ import annotations

import re

from lightrocks.generators.sfc_iec61131.reserved import is_reserved, is_reserved_for_unit

UNIT, VARIABLE, MACRO = "unit", "variable", "macro"


def legal(name: str) -> str:
    """Letters, digits and single underscores, not starting with a digit or ending in ``_``."""
    text = re.sub(r"[^A-Za-z0-9_]", "_", name)
    text = re.sub(r"_+", "_", text).strip("_") or "x"
    return f"x{text}" if text[0].isdigit() else text


def _unreserved(name: str, kind: str = VARIABLE) -> str:
    base = legal(name)
    reserved = is_reserved_for_unit if kind == UNIT else is_reserved
    return f"{base}_1" if reserved(base) else base


class Namer:
    """Hands out names of one scope; a name already taken (any case) gets a suffix ``_2``…"""

    def __init__(self, unit: Namer | None = None) -> None:
        self._unit = unit
        self._used: set[str] = set()
        self._kinds: dict[str, set[str]] = {UNIT: set(), VARIABLE: set(), MACRO: set()}

    @property
    def root(self) -> Namer:
        return self._unit or self

    def scope(self) -> Namer:
        """A namer for the variables, steps and actions of one POU."""
        return Namer(self.root)

    def claim(self, wanted: str) -> str:
        """A variable name; on the unit namer, a unit name."""
        return self._take(wanted, VARIABLE if self._unit else UNIT)

    def claim_macro(self, wanted: str) -> str:
        """A step or action name."""
        return self._take(wanted, MACRO)

    def field(self, wanted: str) -> str:
        """A structure field or object attribute: the same spelling wherever it is read."""
        name = _unreserved(wanted)
        self.root._kinds[VARIABLE].add(name.upper())
        return name

    def _take(self, wanted: str, kind: str) -> str:
        kinds = self.root._kinds
        avoid = set().union(*(names for other, names in kinds.items() if other != kind))
        base = _unreserved(wanted, kind)
        name, count = base, 1
        while name.upper() in self._used or name.upper() in avoid:
            count += 1
            name = f"{base}_{count}"
        self._used.add(name.upper())
        kinds[kind].add(name.upper())
        return name
