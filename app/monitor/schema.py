"""What a trace record must hold for ``plot`` and ``replay`` to read it (see *Trace* in
docs/runtime.md): a record that does not is named with its line, instead of failing deep
inside a figure or a page. Kinds this tool does not know pass with a valid time."""

from __future__ import annotations

import math
from typing import Any

TEXT_FIELDS = {
    "enter": ("state",),
    "exit": ("state",),
    "transition": ("state", "source", "target"),
    "command": ("state", "device", "command"),
    "stop": ("state", "outcome"),
    "outcome": ("state", "outcome"),
    "error": ("state",),
    "finished": ("outcome",),
    "run": ("model",),
}
"""Fields each kind must hold as text."""
LIST_FIELDS = {"interrupted": ("active",), "aborted": ("active",), "run": ("path",)}
"""Fields each kind may only hold as a list of texts."""
NOT_FINITE = ("nan", "inf", "-inf")
"""How the runtime writes a number that is not finite."""


class RecordError(ValueError):
    """What is wrong with one record."""


def check(record: dict[str, Any]) -> None:
    """Raise ``RecordError`` when ``record`` lacks what its kind needs."""
    time, kind = record["time"], record["kind"]
    if isinstance(time, bool) or not isinstance(time, int | float) or not math.isfinite(time):
        raise RecordError(f"time {_shown(time)} is not a number of seconds")
    if not isinstance(kind, str):
        raise RecordError(f"kind {_shown(kind)} is not a name")
    for field in TEXT_FIELDS.get(kind, ()):
        if not isinstance(record.get(field), str):
            raise RecordError(f"{_a(kind)} record needs its {field} as text")
    for field in LIST_FIELDS.get(kind, ()):
        value = record.get(field, [])
        if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
            raise RecordError(f"the {field} of {_a(kind)} record is not a list of texts")
    if kind == "enter" and not isinstance(record.get("layer", ""), str | None):
        raise RecordError("the layer of an enter record is not text")
    if kind == "sample":
        for key, value in record.items():
            if key.endswith(".wrench") and not _is_wrench(value):
                raise RecordError(f"{key} is not {{force, torque}} of three numbers each")
            if key.endswith(".tcp") and not _is_vector(value):
                raise RecordError(f"{key} is not three numbers")


def _is_vector(value: Any) -> bool:
    return isinstance(value, list) and len(value) == 3 and all(map(_is_number, value))


def _is_number(value: Any) -> bool:
    if isinstance(value, bool):
        return False
    return isinstance(value, int | float) or value in NOT_FINITE


def _is_wrench(value: Any) -> bool:
    return (
        isinstance(value, dict)
        and _is_vector(value.get("force"))
        and _is_vector(value.get("torque"))
    )


def _a(kind: str) -> str:
    return f"{'an' if kind[:1] in 'aeiou' else 'a'} {kind}"


def _shown(value: Any) -> str:
    text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."
