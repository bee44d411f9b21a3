"""Units of measurement: every quantity literal is stored in SI with its dimension.

A dimension is a vector of exponents over (length, mass, time, angle, current). Angles are
kept as a dimension of their own so that a torque (N·m) and a rotational stiffness
(N·m/rad) stay apart, and ``deg`` converts to ``rad``.
"""

from __future__ import annotations

import difflib
import math
import re
from dataclasses import dataclass

BASES = ("m", "kg", "s", "rad", "A")


@dataclass(frozen=True)
class Dimension:
    exponents: tuple[int, int, int, int, int] = (0, 0, 0, 0, 0)

    def __mul__(self, other: Dimension) -> Dimension:
        return Dimension(tuple(a + b for a, b in zip(self.exponents, other.exponents, strict=True)))

    def __truediv__(self, other: Dimension) -> Dimension:
        return Dimension(tuple(a - b for a, b in zip(self.exponents, other.exponents, strict=True)))

    def __pow__(self, power: int) -> Dimension:
        return Dimension(tuple(a * power for a in self.exponents))

    @property
    def dimensionless(self) -> bool:
        return not any(self.exponents)

    def __str__(self) -> str:
        if self.dimensionless:
            return "1"
        up = [
            f"{b}^{e}" if e != 1 else b for b, e in zip(BASES, self.exponents, strict=True) if e > 0
        ]
        down = [
            f"{b}^{-e}" if e != -1 else b
            for b, e in zip(BASES, self.exponents, strict=True)
            if e < 0
        ]
        text = "·".join(up) or "1"
        return f"{text}/{'·'.join(down)}" if down else text


ONE = Dimension()
LENGTH = Dimension((1, 0, 0, 0, 0))
MASS = Dimension((0, 1, 0, 0, 0))
TIME = Dimension((0, 0, 1, 0, 0))
ANGLE = Dimension((0, 0, 0, 1, 0))
CURRENT = Dimension((0, 0, 0, 0, 1))
FORCE = MASS * LENGTH / TIME**2
TORQUE = FORCE * LENGTH


@dataclass(frozen=True)
class UnitInfo:
    factor: float
    dimension: Dimension


_SIMPLE: dict[str, UnitInfo] = {
    "m": UnitInfo(1.0, LENGTH),
    "cm": UnitInfo(1e-2, LENGTH),
    "mm": UnitInfo(1e-3, LENGTH),
    "um": UnitInfo(1e-6, LENGTH),
    "kg": UnitInfo(1.0, MASS),
    "g": UnitInfo(1e-3, MASS),
    "s": UnitInfo(1.0, TIME),
    "ms": UnitInfo(1e-3, TIME),
    "min": UnitInfo(60.0, TIME),
    "rad": UnitInfo(1.0, ANGLE),
    "deg": UnitInfo(math.pi / 180.0, ANGLE),
    "N": UnitInfo(1.0, FORCE),
    "kN": UnitInfo(1e3, FORCE),
    "Nm": UnitInfo(1.0, TORQUE),
    "Nmm": UnitInfo(1e-3, TORQUE),
    "A": UnitInfo(1.0, CURRENT),
    "Hz": UnitInfo(1.0, TIME**-1),
    "percent": UnitInfo(1e-2, ONE),
}


class UnitError(ValueError):
    """An unknown unit symbol; carries close matches for a hint."""

    def __init__(self, unit: str, suggestions: list[str]) -> None:
        super().__init__(f"unknown unit '{unit}'")
        self.unit = unit
        self.suggestions = suggestions


def known_units() -> list[str]:
    return sorted(_SIMPLE)


def lookup(unit: str) -> UnitInfo:
    """Resolve ``sym`` or ``sym/sym`` (``N/m``, ``Nm/rad``, ``m/s``) to factor and dimension."""
    if not unit:
        return UnitInfo(1.0, ONE)
    numerator, _, denominator = unit.partition("/")
    parts = [numerator] + ([denominator] if denominator else [])
    infos = []
    for part in parts:
        info = _SIMPLE.get(part)
        if info is None:
            raise UnitError(unit, difflib.get_close_matches(part, _SIMPLE, n=3))
        infos.append(info)
    if len(infos) == 1:
        return infos[0]
    return UnitInfo(infos[0].factor / infos[1].factor, infos[0].dimension / infos[1].dimension)


_DURATION = re.compile(r"\s*(\d+(?:\.\d+)?(?:[eE][-+]?\d+)?)\s*([A-Za-z]+)\s*")


def seconds(text: str | None) -> float | None:
    """A duration written with a time unit (``<<timeout="5 s">>``, ``200 ms``) in seconds;
    None for anything else. A number beyond a float is ``inf``: the caller decides."""
    match = _DURATION.fullmatch(text or "")
    if match is None:
        return None
    try:
        info = lookup(match.group(2))
    except UnitError:
        return None
    return float(match.group(1)) * info.factor if info.dimension == TIME else None


def to_si(value: float, unit: str) -> float:
    return value * lookup(unit).factor


def from_si(value: float, unit: str) -> float:
    return value / lookup(unit).factor
