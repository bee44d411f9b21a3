"""The Pinocchio adapter: the LightRocks devices on the fast dynamics twin."""

from __future__ import annotations

from lightrocks.adapters.devices import SimulatedCell
from lightrocks.adapters.pinocchio.plant import PinocchioPlant


class PinocchioAdapter(SimulatedCell):
    """``runtime.contract.Adapter`` on Pinocchio ABA-style dynamics with penalty contacts."""

    PLANT = PinocchioPlant


__all__ = ["PinocchioAdapter"]
