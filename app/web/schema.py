"""Requests checked once, on arrival, against a small typed schema: a frozen dataclass per
kind of request whose fields, with their types, say what it holds. A request that does not
fit is refused naming the field (a 400, see :mod:`.routes`); what passes is typed, so no
handler behind it meets a missing key or a value of the wrong type.

The types a field may have are those the pages send: ``str``, ``int`` (not ``bool``),
``bool``, a ``Literal`` of texts, ``tuple[X, ...]`` for a list of any length and
``tuple[X, Y]`` for one of fixed length (both from a JSON array). Fields a request holds
that its schema does not name are left aside, as a form may send more.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from typing import Any, Literal, TypeVar, get_args, get_origin, get_type_hints

T = TypeVar("T")

NAMES = {
    str: ("a text", "text", "texts"),
    int: ("a whole number", "whole number", "whole numbers"),
    bool: ("true or false", "true or false", "values true or false"),
}
"""How a refusal names a value of each plain type: alone, in a fixed list, in any list."""


class BadRequest(Exception):
    """A request the page would never send; ``field`` names what is wrong ('': the whole
    request)."""

    def __init__(self, message: str, field: str = "") -> None:
        super().__init__(message)
        self.field = field


class _Mismatch(Exception):
    """A value that does not have the type asked for."""


def parsed(schema: type[T], given: Mapping[str, Any]) -> T:
    """``given`` (a JSON object, a query or a route's path parameters) as an instance of
    ``schema``; :class:`BadRequest` naming the first field that is missing or of the wrong
    type."""
    if not isinstance(given, Mapping):
        raise BadRequest("the request's body is not a JSON object")
    hints = get_type_hints(schema)
    values = {}
    for field in dataclasses.fields(schema):
        if not field.init:
            continue
        if field.name not in given:
            if field.default is dataclasses.MISSING and (
                field.default_factory is dataclasses.MISSING
            ):
                raise BadRequest(f"missing '{field.name}'", field.name)
            continue
        try:
            values[field.name] = _fitted(given[field.name], hints[field.name])
        except _Mismatch:
            raise BadRequest(
                f"'{field.name}' must be {described(hints[field.name])}", field.name
            ) from None
    return schema(**values)


def one_of(kinds: Mapping[str, type[T]], given: Mapping[str, Any], key: str, what: str) -> T:
    """``given`` parsed by the schema that its ``key`` names among ``kinds`` (an edit by its
    ``op``); ``what`` names the kinds in the refusal of an unknown one."""
    if not isinstance(given, Mapping):
        raise BadRequest("the request's body is not a JSON object")
    if key not in given:
        raise BadRequest(f"missing '{key}'", key)
    kind = given[key]
    if not isinstance(kind, str) or kind not in kinds:
        known = ", ".join(kinds)
        raise BadRequest(f"no {what} {_shown(kind)}; known: {known}", key)
    return parsed(kinds[kind], given)


def described(hint: Any) -> str:
    """What a value of type ``hint`` is, as a refusal says it: ``a list of [text, text]``."""
    origin, arguments = get_origin(hint), get_args(hint)
    if origin is Literal:
        return "one of " + ", ".join(_shown(a) for a in arguments)
    if origin is tuple:
        if len(arguments) == 2 and arguments[1] is Ellipsis:
            return f"a list of {_plural(arguments[0])}"
        return f"[{', '.join(_item(a) for a in arguments)}]"
    return NAMES[hint][0]


def _item(hint: Any) -> str:
    return NAMES[hint][1] if hint in NAMES else described(hint)


def _plural(hint: Any) -> str:
    return NAMES[hint][2] if hint in NAMES else described(hint)


def _fitted(value: Any, hint: Any) -> Any:
    """``value`` when it has the type ``hint`` (a JSON array as a tuple), else _Mismatch."""
    origin, arguments = get_origin(hint), get_args(hint)
    if origin is Literal:
        if any(type(value) is type(a) and value == a for a in arguments):
            return value
        raise _Mismatch
    if origin is tuple:
        if not isinstance(value, list | tuple):
            raise _Mismatch
        if len(arguments) == 2 and arguments[1] is Ellipsis:
            return tuple(_fitted(v, arguments[0]) for v in value)
        if len(value) != len(arguments):
            raise _Mismatch
        return tuple(_fitted(v, a) for v, a in zip(value, arguments, strict=True))
    if hint not in NAMES:
        raise TypeError(f"a schema field of type {hint!r}, which JSON does not bring")
    if isinstance(value, hint) and (hint is bool or not isinstance(value, bool)):
        return value
    raise _Mismatch


def _shown(value: Any) -> str:
    text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."
