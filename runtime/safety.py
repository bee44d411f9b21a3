"""Safe ranges enforced where a command leaves the runtime: a value only known at run time
(a parameter given on the command line, a computed pose component) that lies outside the
range the device declares is refused before the robot moves. The runtime turns the refusal
into the outcome ``error`` with its origin and holds the devices."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from lightrocks.runtime.contract import AdapterError, CommandResult, StopCondition

Bounds = tuple[tuple[float, ...] | None, tuple[float, ...] | None]
"""Lower and upper bound in SI, one number for every element or one per element."""

Ranges = Mapping[str, Mapping[str, Mapping[str, Bounds]]]
"""Device instance -> command -> argument -> its bounds."""


class UnsafeCommand(AdapterError):
    """A command argument outside its declared safe range; the command was not sent."""


@dataclass
class SafeRanges:
    """An adapter that refuses commands with an argument outside its declared safe range."""

    adapter: Any
    ranges: Ranges

    def execute(
        self,
        device: str,
        command: str,
        args: Mapping[str, Any],
        stop: Sequence[StopCondition],
        budget: float,
    ) -> CommandResult:
        for name, (low, high) in self.ranges.get(device, {}).get(command, {}).items():
            if name in args:
                _check(f"{device}.{command}({name})", args[name], low, high)
        return self.adapter.execute(device, command, args, stop, budget)

    def __getattr__(self, name: str) -> Any:
        if name == "adapter":  # not yet set (copying, unpickling): no recursion
            raise AttributeError(name)
        return getattr(self.adapter, name)


def _numbers(value: Any) -> list[float] | None:
    if isinstance(value, bool):
        return None
    if isinstance(value, int | float):
        return [float(value)]
    array = getattr(value, "array", None)
    values = array() if callable(array) else value
    try:
        return [float(v) for v in values]
    except (TypeError, ValueError):
        return None


def _check(
    where: str, value: Any, low: tuple[float, ...] | None, high: tuple[float, ...] | None
) -> None:
    numbers = _numbers(value)
    if numbers is None:
        return
    for index, number in enumerate(numbers):
        lo, hi = _pick(low, index), _pick(high, index)
        if (
            math.isnan(number)
            or (lo is not None and number < lo)
            or (hi is not None and number > hi)
        ):
            shown = "-inf" if not low else ", ".join(f"{v:g}" for v in low)
            top = "inf" if not high else ", ".join(f"{v:g}" for v in high)
            raise UnsafeCommand(
                f"refused: {where} = {value!r} is outside the safe range [{shown}] .. [{top}]"
            )


def _pick(values: tuple[float, ...] | None, index: int) -> float | None:
    if not values:
        return None
    return values[index] if len(values) > 1 and index < len(values) else values[0]
