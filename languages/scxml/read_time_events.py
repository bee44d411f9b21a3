"""The time events of an SCXML state: a delayed ``<send>`` of its ``<onentry>`` that its
``<onexit>`` cancels is LightRocks' ``after(d)`` of that state.

The target also relays such events (``lr:helper="tie"`` transitions that send them on, to
keep LightRocks' order at one deadline); a transition on any relay is on the time event.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from lightrocks.languages.scxml.read_context import ReadContext
from lightrocks.languages.scxml.xml_tree import Element
from lightrocks.metamodel import ast

_DELAY = re.compile(r"\s*(\d+(?:\.\d+)?|\.\d+)(ms|s)\s*")


@dataclass
class Timer:
    """One time event of a state: the event it sends, the id of its ``<send>``, its delay."""

    event: str
    send_id: str
    delay: ast.Quantity
    events: set[str] = field(default_factory=set)  # the sent event and its relays


class TimeEventReader:
    """The time events of each state of one document, found once per state."""

    def __init__(self, context: ReadContext) -> None:
        self.context = context
        self._found: dict[int, list[Timer]] = {}

    def of(self, element: Element) -> list[Timer]:
        """The delayed ``<send>`` s of ``element``'s ``<onentry>`` that its ``<onexit>``
        cancels: its time events (with the events the generator relays them by)."""
        if id(element) not in self._found:
            self._found[id(element)] = self._find(element)
        return self._found[id(element)]

    def _find(self, element: Element) -> list[Timer]:
        cancelled = {
            c.get("sendid")
            for exit_ in element.all("onexit")
            for c in exit_.all("cancel")
            if c.get("sendid")
        }
        timers = []
        for entry in element.all("onentry"):
            for send in entry.all("send"):
                if send.get("id") in cancelled and send.get("event") and send.get("delay"):
                    delay = css2_time(send.get("delay"))
                    if delay is None:
                        self.context.refuse(
                            send, f"a delay '{send.get('delay')}' that is no CSS2 time"
                        )
                        continue
                    timer = Timer(send.get("event"), send.get("id"), delay, {send.get("event")})
                    timers.append(timer)
        for transition in element.all("transition"):
            if transition.lr("helper") == "tie":
                for timer in timers:
                    if transition.get("event") in timer.events:
                        timer.events |= {s.get("event") for s in transition.all("send")}
        return timers


def css2_time(text: str) -> ast.Quantity | None:
    """The SCXML delay ``text`` (``300ms``, ``2s``) as a LightRocks duration."""
    match = _DELAY.fullmatch(text)
    if match is None:
        return None
    number, unit = match.groups()
    value = float(number)
    seconds = value / 1000 if unit == "ms" else value
    return ast.Quantity(seconds, unit, f"{number} {unit}")
