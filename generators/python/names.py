"""Python names for model names: never a keyword, a builtin or a name the runtime uses."""

from __future__ import annotations

import builtins
import keyword

from lightrocks import runtime

_RUNTIME = {
    name
    for cls in (runtime.CompositeComponent, runtime.ActionComponent, runtime.Final)
    for name in dir(cls)
}
RESERVED = frozenset(
    {*keyword.kwlist, *keyword.softkwlist, *dir(builtins), *_RUNTIME, "rt", "s", "self"}
)


def identifier(name: str) -> str:
    """``name`` as a Python identifier that shadows nothing (a trailing ``_`` when needed)."""
    cleaned = "".join(c if c.isalnum() or c == "_" else "_" for c in name) or "_"
    if cleaned[0].isdigit():
        cleaned = "_" + cleaned
    while cleaned in RESERVED or cleaned.startswith("__"):
        cleaned += "_"
    return cleaned


def attribute(target: str, name: str) -> str:
    """Read attribute ``name`` that is fixed by someone else (a sensor, a structure field)."""
    if name.isidentifier() and not keyword.iskeyword(name):
        return f"{target}.{name}"
    return f"getattr({target}, {name!r})"
