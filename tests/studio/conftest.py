"""The browser of the monitor's page tests, for the studio's page; the smallest valid
request of a schema, for the tests of bad requests."""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from typing import Any, Literal, get_args, get_origin, get_type_hints

import pytest
from monitor.browser_page import browser  # noqa: F401

from lightrocks.app.studio.operations import OPERATIONS


def _valid(hint: Any) -> Any:
    """A value of type ``hint`` as JSON has it."""
    if get_origin(hint) is Literal:
        return get_args(hint)[0]
    if get_origin(hint) is tuple:
        arguments = get_args(hint)
        return [] if arguments[1:] == (Ellipsis,) else [_valid(a) for a in arguments]
    return {str: "x", int: 1, bool: True}[hint]


@pytest.fixture
def minimal() -> Callable[[type], dict[str, Any]]:
    """``minimal(schema)``: its required fields, each with a valid value (and an edit's
    ``op``)."""

    def made(schema: type) -> dict[str, Any]:
        hints = get_type_hints(schema)
        given = {
            f.name: _valid(hints[f.name])
            for f in dataclasses.fields(schema)
            if f.default is dataclasses.MISSING
        }
        return {"op": schema.OP, **given} if schema in OPERATIONS.values() else given

    return made
