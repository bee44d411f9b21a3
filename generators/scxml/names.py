"""Names in an SCXML document written for a LightRocks statechart, collision-free.

Three kinds of names, each allocated by a :class:`Names` of its own document:

- **State ids** are the LightRocks path of a state joined by ``-`` (``Lamp-On-Dim``).
  LightRocks names are identifiers, which hold no ``-``, so two paths never meet; an id is an
  XML ``NCName`` as SCXML requires. ``.`` is kept for the generator's own states
  (``Lamp.end``, ``Press-Job.post1``): no path holds one, and no ``done.state.…`` event is ever
  raised for them, so SCXML's matching of event names by prefix (``done.state.A`` also
  matches ``done.state.A.b``) cannot confuse them with a state.
- **Data names** are the variables of the data model, read by python-statemachine's
  restricted Python evaluator: ASCII identifiers that are no Python keyword, do not start
  with ``_`` (the evaluator never resolves those), are none of the names the evaluator gives
  to the machine itself (``machine``, ``event``, ``state``, …) and none of the words it
  rewrites in conditions (``true``, ``false``, ``null``). Any other name becomes ``v_`` with
  its letters and the code points of the rest, and a suffix keeps them apart.
- **Event names** (:func:`languages.scxml.markup.event_name`, shared with the reader): a
  LightRocks event keeps its name, except ``done`` and ``error``, which become
  ``done-event`` and ``error-event``: SCXML matches a transition's event by prefix,
  so a transition on ``done`` would also take the engine's own ``done.state.…`` events. The
  generator's time events are ``after-<state id>-<n>`` and ``timeout-<chart>``: their ``-``
  keeps them apart from every LightRocks event.
"""

from __future__ import annotations

import keyword
import re

_IDENTIFIER = re.compile(r"[A-Za-z][A-Za-z0-9_]*")
_NCNAME = re.compile(r"[^\W\d][\w.\-]*")
_COND_WORDS = {"true", "false", "null"}
"""python-statemachine rewrites these words in a condition (``true`` to ``True`` …)."""
_MACHINE = {
    "event_data",
    "machine",
    "event",
    "model",
    "transition",
    "state",
    "source",
    "target",
    "In",
}
"""Names the evaluator binds to the engine (never to the data model), and its ``In()``."""


def plain_data_name(name: str) -> bool:
    """``name`` can be a variable of the data model as it is."""
    return bool(
        _IDENTIFIER.fullmatch(name)
        and not keyword.iskeyword(name)
        and name not in _COND_WORDS
        and name not in _MACHINE
    )


def _mangled(name: str) -> str:
    parts = [c if c.isascii() and (c.isalnum() or c == "_") else f"_{ord(c):x}_" for c in name]
    return "v_" + "".join(parts).strip("_")


def _segment(name: str) -> str:
    """One segment of a state id: the name itself where SCXML and the evaluator's rewriting
    of ``true``/``false``/``null`` in conditions (which name states in ``In('…')``) leave it
    alone, else its code points."""
    if _NCNAME.fullmatch(name) and "." not in name and "-" not in name:
        return f"{name}_" if name in _COND_WORDS else name
    return "x" + "".join(c if c.isascii() and c.isalnum() else f"_{ord(c):x}" for c in name)


class Names:
    """The names of one document: each model name gets one SCXML name, no two the same."""

    def __init__(self) -> None:
        self._data: dict[str, str] = {}
        self._ids: dict[tuple[str, ...], str] = {}
        self._taken_data: set[str] = set()
        self._taken_ids: set[str] = set()

    def data(self, name: str) -> str:
        """The data-model variable of the parameter ``name``."""
        if name not in self._data:
            self._data[name] = self.fresh_data(name if plain_data_name(name) else _mangled(name))
        return self._data[name]

    def fresh_data(self, wanted: str) -> str:
        """A variable of the generator's own (or ``wanted`` itself when free)."""
        candidate, number = wanted, 1
        while candidate in self._taken_data or not plain_data_name(candidate):
            number += 1
            candidate = f"{wanted}_{number}"
        self._taken_data.add(candidate)
        return candidate

    def state(self, path: tuple[str, ...]) -> str:
        """The id of the state at ``path`` (chart name first)."""
        if path not in self._ids:
            self._ids[path] = self._unique("-".join(_segment(p) for p in path), "_")
        return self._ids[path]

    def helper(self, owner: str, suffix: str) -> str:
        """The id of a state of the generator's own inside (or beside) ``owner``."""
        return self._unique(f"{owner}.{suffix}", "")

    def _unique(self, wanted: str, separator: str) -> str:
        candidate, number = wanted, 1
        while candidate in self._taken_ids:
            number += 1
            candidate = f"{wanted}{separator}{number}"
        self._taken_ids.add(candidate)
        return candidate

    @property
    def paths(self) -> dict[str, tuple[str, ...]]:
        """State id -> LightRocks path, for every state with a path."""
        return {state_id: path for path, state_id in self._ids.items()}

    @property
    def variables(self) -> dict[str, str]:
        """Parameter -> data-model variable."""
        return dict(self._data)
