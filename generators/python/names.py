"""Python names for model names, collision-free by construction.

A model name becomes one of three disjoint forms:

- *plain*: ASCII letters and digits in ``_``-separated words (``depth``, ``Screw_In``), not
  reserved — kept as it is;
- *reserved*: a plain name that Python, the runtime or the generated modules already use
  (``class``, ``print``, ``path``, ``parent``, ``rt``) — one ``_`` appended (``path_``);
- *anything else* (a leading or trailing ``_``, ``__``, non-ASCII letters such as the
  NFKC-equal ``ｐａｒｅｎｔ``, …) — its ASCII letters and digits, a hash of the exact name and
  ``__`` (``parent_1b2c3d4e__``), so two names that Python would normalise alike stay apart.

No form starts with ``_``: names beginning with one ``_`` belong to the generator (``_domain``,
``_guard_0``, import aliases) and the runtime (``_executor``); dunder names to Python. Module
and file names use the same forms, so they are ASCII and need no Unicode normalisation.
"""

from __future__ import annotations

import builtins
import hashlib
import keyword
import re
import unicodedata

from lightrocks import runtime

DOMAIN = "_domain"  # the generator's own module of device types and cells
_PLAIN = re.compile(r"[A-Za-z][A-Za-z0-9]*(?:_[A-Za-z0-9]+)*")
_STATE_CLASSES = (runtime.CompositeComponent, runtime.ActionComponent, runtime.Final)


def _runtime_names() -> set[str]:
    """Class attributes, instance attributes and annotated attributes of generated states,
    and the attributes of the environment (scene objects live beside them)."""
    names = set(dir(runtime.Environment))
    for cls in _STATE_CLASSES:
        names |= set(dir(cls)) | set(vars(cls()))
        for base in cls.__mro__:
            names |= set(getattr(base, "__annotations__", {}))
    return names


MODULE_NAMES = frozenset({"annotations", "rt", "Any", "ClassVar", "Protocol", "s", "self", "value"})
"""Names every generated module or method binds itself."""

RESERVED = frozenset(
    {*keyword.kwlist, *keyword.softkwlist, *dir(builtins), *_runtime_names(), *MODULE_NAMES}
)


def identifier(name: str) -> str:
    """``name`` as a Python identifier that meets no other name (see the module doc)."""
    if _PLAIN.fullmatch(name):
        return f"{name}_" if name in RESERVED else name
    readable = re.sub(r"[^A-Za-z0-9]+", "_", unicodedata.normalize("NFKC", name)).strip("_")
    if not readable[:1].isalpha():
        readable = "n" + readable
    digest = hashlib.sha256(name.encode("utf-8", "surrogatepass")).hexdigest()[:10]
    return f"{readable}_{digest}__"


def nested(outer: str, name: str) -> str:
    """The class of state ``name`` inside the class ``outer``: parts joined by ``__``, which
    no part contains in its middle, so different state paths never meet."""
    return f"{outer}__{identifier(name)}"


def alias(module_parts: list[str], name: str) -> str:
    """An imported class under a name of the generator's own (leading ``_``), unique per
    module and class."""
    return "_" + "__".join([*module_parts, name])


def attribute(target: str, name: str) -> str:
    """Read attribute ``name`` that is fixed by someone else (a sensor, a structure field)."""
    plain = name.isidentifier() and unicodedata.normalize("NFKC", name) == name
    if plain and not keyword.iskeyword(name) and not name.startswith("__"):
        return f"{target}.{name}"
    return f"getattr({target}, {name!r})"


def module_parts(qualified_name: str) -> list[str]:
    """The package path of a statechart's module (the domain module is the generator's)."""
    if qualified_name == DOMAIN:
        return [DOMAIN]
    return [identifier(part) for part in qualified_name.split(".")]


def module_path(qualified_name: str) -> str:
    return "/".join(module_parts(qualified_name)) + ".py"
