"""The XML vocabulary that the SCXML writer and reader share: the SCXML namespace, the
namespace of LightRocks' own annotations, the event prefix of the generator's errors, and
the SCXML names of LightRocks events.

Both directions need these names, so they live apart from either.
"""

from __future__ import annotations

SCXML = "http://www.w3.org/2005/07/scxml"
LR = "urn:lightrocks:scxml"
"""The namespace of the annotations that carry what SCXML has no place for (the package,
declared events, types of parameters, stereotypes) and mark the generator's own elements.
SCXML engines ignore attributes of other namespaces."""

ERROR_EVENT = "lr-error."
"""The prefix of the event raised when a state ends with ``error``: ``lr-error.<state id>``."""


def q(name: str) -> str:
    """The qualified name of the SCXML element or attribute ``name``."""
    return f"{{{SCXML}}}{name}"


def lr(name: str) -> str:
    """The qualified name of the LightRocks annotation ``name``."""
    return f"{{{LR}}}{name}"


RESERVED_EVENTS = ("done", "error")
EVENT_SUFFIX = "-event"


def event_name(name: str) -> str:
    """The SCXML name of the LightRocks event ``name``."""
    return f"{name}{EVENT_SUFFIX}" if name in RESERVED_EVENTS else name


def lightrocks_event(name: str) -> str:
    """The LightRocks name of the SCXML event ``name`` (inverse of :func:`event_name`)."""
    base = name.removesuffix(EVENT_SUFFIX)
    return base if name.endswith(EVENT_SUFFIX) and base in RESERVED_EVENTS else name
