"""The Pinocchio adapter: the LightRocks devices on the fast dynamics twin."""

from __future__ import annotations

from lightrocks.adapters.devices import SimulatedCell
from lightrocks.adapters.pinocchio.plant import PinocchioPlant


class PinocchioAdapter(SimulatedCell):
    """``runtime.contract.Adapter`` on the twin: Pinocchio rigid-body dynamics (CRBA and RNEA)
    with penalty contacts against static boxes and the scenes' fixture twins."""

    PLANT = PinocchioPlant


__all__ = ["PinocchioAdapter"]
