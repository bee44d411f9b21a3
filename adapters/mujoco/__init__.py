"""The MuJoCo adapter: the LightRocks devices on a MuJoCo simulation of a scene."""

from __future__ import annotations

from lightrocks.adapters.devices import SimulatedCell
from lightrocks.adapters.mujoco.plant import MujocoPlant


class MujocoAdapter(SimulatedCell):
    """``runtime.contract.Adapter`` on a MuJoCo simulation of a registered scene
    (``lightrocks.scenes``) with a registered robot."""

    PLANT = MujocoPlant


__all__ = ["MujocoAdapter"]
