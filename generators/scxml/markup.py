"""The XML vocabulary that the SCXML writer and reader share: the SCXML namespace, the
namespace of LightRocks' own annotations, and the event prefix of the generator's errors.

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
