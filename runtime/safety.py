"""Safe ranges enforced where a value leaves the runtime for a device: a command argument only
known at run time (a run parameter, a computed value) outside the range its device declares
is refused before anything moves. Generated classes carry the ranges as data, so every way of
running them (command line, ``spec_for``, ``--seeds``, plain Python) is held to them.

This is the one implementation of the check and its message, here because the runtime may
import nothing of ours: the language's checks of constant values (languages/domain/ranges.py)
import it, so that check and run judge a value alike (NaN is never safe). Whatever its range,
no argument that holds a number that is not finite (``inf``, ``nan``) reaches a device."""

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


def not_finite(device: str, command: str, arguments: Mapping[str, Any]) -> str | None:
    """Why a command must not be sent because an argument holds a number that is not finite
    (``inf``, ``nan``, a whole number beyond a Real): no device is asked to move to infinity,
    whether or not the argument has a safe range. ``None`` when every number is finite."""
    for name, value in arguments.items():
        numbers = _numbers(value)
        if numbers is None:
            number = _non_finite_inside(value)
            if number is not None:
                return f"refused: {device}.{command}({name}) holds {number}, not a finite number"
            continue
        for index, number in enumerate(numbers):
            if not math.isfinite(number):
                element = f"{name}[{index}]" if len(numbers) > 1 else name
                return f"refused: {device}.{command}({element}) = {number}, not a finite number"
    return None


def _non_finite_inside(value: Any) -> float | None:
    """The first number of a frame (``homogeneous``), a vector or a wrench (``array()``) that
    is not finite; ``None`` when they all are or ``value`` is none of these."""
    inside = getattr(value, "homogeneous", None)
    if inside is None and callable(getattr(value, "array", None)):
        try:
            inside = value.array()
        except Exception:  # not one of ours: nothing to judge
            return None
    if inside is None:
        return None
    ravel = getattr(inside, "ravel", None)  # an array of numpy, which is not loaded here
    try:
        numbers = [float(v) for v in (ravel() if callable(ravel) else inside)]
    except (TypeError, ValueError, OverflowError):
        return None
    return next((n for n in numbers if not math.isfinite(n)), None)


def _float(value: Any) -> float:
    """``float(value)``; a whole number beyond a Real is infinite, as it is no Real."""
    try:
        return float(value)
    except OverflowError:
        return math.inf if value > 0 else -math.inf


def _numbers(value: Any) -> list[float] | None:
    """The numbers of a scalar or a vector (tuple, list, numpy array); None for anything else,
    which no range constrains."""
    if isinstance(value, bool | str | bytes) or value is None:
        return None
    try:
        return [_float(value)]
    except (TypeError, ValueError):
        pass
    try:
        return [_float(v) for v in value]
    except (TypeError, ValueError):
        return None
