"""Faults and stops from outside: what ends a state with ``error`` and how it is described,
the built-in outcomes, and ``Abort``, which stops a run safely."""

from __future__ import annotations

from dataclasses import dataclass, field

ERROR, PREEMPTED, INTERRUPTED = "error", "preempted", "interrupted"


class Abort(KeyboardInterrupt):
    """Raised on the run's thread (by a stop condition or a listener) to stop the run
    safely from outside: the arm holds, no exit action runs, the outcome is ``preempted``.
    A kind of Ctrl-C, so that every handler lets it through as it does Ctrl-C."""


class UnknownEvent(ValueError):
    """An event that no transition of the statechart names and no declaration lists."""


class DescribedFault(Exception):
    """A fault already described (message and model location) on its way to the executor,
    which makes it the ``error`` of a state."""

    def __init__(self, message: str, location: str) -> None:
        super().__init__(message)
        self.message, self.location = message, location


def describe(exc: BaseException) -> str:
    """What a Python error in model code, an adapter or a sensor read says about itself."""
    return f"{type(exc).__name__} in model code: {exc}"


@dataclass
class Fault:
    """Why a state ended with ``error``, and the states the error passed through."""

    message: str
    location: str
    origin: list[str] = field(default_factory=list)
