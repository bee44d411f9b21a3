"""``--adapter franka``: a Franka arm through libfranka (``pip install 'lightrocks[franka]'``).

The adapter's module is imported on first use, so that the hand's process, which imports this
package, and ``lightrocks list adapters`` do not load the control loop's dependencies.
"""

from __future__ import annotations

from typing import Any

__all__ = ["FrankaAdapter"]


def __getattr__(name: str) -> Any:
    if name == "FrankaAdapter":
        from lightrocks.adapters.franka.adapter import FrankaAdapter

        return FrankaAdapter
    raise AttributeError(name)
