"""Every request the studio takes, checked against its schema: each field left out (where
it has no default) and each field given a value of another JSON type is refused with a
message naming the field, before the session sees it; a minimal request passes."""

from __future__ import annotations

import dataclasses
from typing import Any, Literal, get_args, get_origin, get_type_hints

import pytest

from lightrocks.app.studio import requests
from lightrocks.app.studio.operations import OPERATIONS, operation
from lightrocks.app.web.schema import BadRequest, parsed

SCHEMAS = [
    requests.Chart,
    requests.Target,
    requests.Rename,
    requests.NewChart,
    requests.HistoryStep,
    requests.StartRun,
    *OPERATIONS.values(),
]
JSON_VALUES = [None, 3, 1.5, True, "x", [], ["x"], {}]


def fits(value: Any, hint: Any) -> bool:
    if get_origin(hint) is Literal:
        return value in get_args(hint) and isinstance(value, str)
    if get_origin(hint) is tuple:
        return isinstance(value, list) and (get_args(hint)[1:] == (Ellipsis,) and not value)
    if hint is int:
        return isinstance(value, int) and not isinstance(value, bool)
    return isinstance(value, hint)


def cases() -> list[tuple[type, str, Any]]:
    """(schema, field, value) for every field of every schema: ``...`` leaves it out."""
    found = []
    for schema in SCHEMAS:
        hints = get_type_hints(schema)
        for field in dataclasses.fields(schema):
            if field.default is dataclasses.MISSING:
                found.append((schema, field.name, ...))
            hint = hints[field.name]
            found += [(schema, field.name, v) for v in JSON_VALUES if not fits(v, hint)]
    return found


@pytest.mark.parametrize("schema", SCHEMAS, ids=lambda s: s.__name__)
def test_a_minimal_request_passes(minimal, schema: type) -> None:
    assert isinstance(parsed(schema, minimal(schema)), schema)


@pytest.mark.parametrize(
    ("schema", "name", "value"), cases(), ids=lambda v: getattr(v, "__name__", repr(v))
)
def test_a_field_left_out_or_of_another_type_is_named(
    minimal, schema: type, name: str, value
) -> None:
    given = {k: v for k, v in minimal(schema).items() if k != name}
    if value is not ...:
        given[name] = value
    with pytest.raises(BadRequest) as refused:
        parsed(schema, given)
    assert refused.value.field == name
    assert f"'{name}'" in str(refused.value)


@pytest.mark.parametrize(
    ("given", "field", "message"),
    [
        ({}, "op", "missing 'op'"),
        ({"op": 3}, "op", "no edit 3; known: add-state, add-transition"),
        ({"op": "rename"}, "op", "no edit 'rename'"),
        ({"op": "move", "state": "A", "steps": 1.0}, "steps", "'steps' must be a whole number"),
        ({"op": "move", "state": "A"}, "steps", "missing 'steps'"),
        (
            {"op": "set-arguments", "state": "A", "arguments": [["a", 1]]},
            "arguments",
            "'arguments' must be a list of [text, text]",
        ),
        (
            {"op": "set-parameters", "parameters": [["T", "a"]]},
            "parameters",
            "'parameters' must be a list of [text, text, text]",
        ),
        ([1], "", "not a JSON object"),
    ],
)
def test_an_edit_is_chosen_by_its_op(given, field: str, message: str) -> None:
    with pytest.raises(BadRequest) as refused:
        operation(given)
    assert (refused.value.field, message in str(refused.value)) == (field, True), refused.value


def test_an_edit_request_becomes_typed_values() -> None:
    rows = [["Length", "x", "1 mm"], ["Force", "f", ""]]
    made = operation({"op": "set-parameters", "parameters": rows, "chart": "ignored"})
    assert made.parameters == (("Length", "x", "1 mm"), ("Force", "f", ""))
    assert made.label == "set-parameters"
    step = operation({"op": "set-transition", "source": "A", "target": "B", "number": 2})
    assert (step.number, step.stimulus, step.label) == (2, "", "set-transition A -> B")
