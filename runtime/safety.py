"""Safe ranges enforced where a value leaves the runtime for a device: a command argument only
known at run time (a run parameter, a computed value) outside the range its device declares
is refused before anything moves. Generated classes carry the ranges as data, so every way of
running them (command line, ``run_once``, ``--seeds``, plain Python) is held to them.

This is the one implementation of the check and its message, here because the runtime may
import nothing of ours: the language's checks of constant values (languages/domain/ranges.py)
import it, so that check and run judge a value alike (NaN is never safe)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class Bound:
    """One element's bounds in SI, and the unit (with its SI factor) the model wrote them in."""

    low: float | None
    high: float | None
    unit: str = ""
    factor: float = 1.0

    def holds(self, number: float) -> bool:
        if math.isnan(number):
            return False
        return (self.low is None or number >= self.low) and (
            self.high is None or number <= self.high
        )

    def show(self, number: float | None, unbounded: str = "") -> str:
        if number is None:
            return unbounded
        return f"{number / self.factor:g} {self.unit}".rstrip()

    def describe(self) -> str:
        return f"{self.show(self.low, '-inf')} .. {self.show(self.high, 'inf')}"


@dataclass(frozen=True)
class SafeRange:
    """The safe range of ``device.command(argument)``: one bound for a scalar, one per element
    (or one for all elements) for a vector."""

    device: str
    command: str
    argument: str
    bounds: tuple[Bound, ...]

    def breach(self, value: Any) -> str | None:
        """Which element of ``value`` lies outside, and by what; ``None`` when all are safe."""
        numbers = _numbers(value)
        if numbers is None:
            return None
        vector = len(numbers) > 1 or len(self.bounds) > 1
        for index, number in enumerate(numbers):
            bound = self.bounds[index] if index < len(self.bounds) else self.bounds[0]
            if not bound.holds(number):
                element = f"{self.argument}[{index}]" if vector else self.argument
                return (
                    f"{self.device}.{self.command}({element}) = {bound.show(number)} is outside "
                    f"its safe range {bound.describe()}"
                )
        return None


def refusal(ranges: Mapping[str, SafeRange], arguments: Mapping[str, Any]) -> str | None:
    """Why a command with these arguments must not be sent; ``None`` when it may."""
    for name, safe in ranges.items():
        if name in arguments:
            reason = safe.breach(arguments[name])
            if reason is not None:
                return f"refused: {reason}"
    return None


def _numbers(value: Any) -> list[float] | None:
    """The numbers of a scalar or a vector (tuple, list, numpy array); None for anything else,
    which no range constrains."""
    if isinstance(value, bool | str | bytes):
        return None
    try:
        return [float(value)]
    except (TypeError, ValueError):
        pass
    try:
        return [float(v) for v in value]
    except (TypeError, ValueError):
        return None
