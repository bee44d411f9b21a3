"""The MuJoCo adapter: the LightRocks devices on a MuJoCo simulation of a scene."""

from __future__ import annotations

from lightrocks.adapters.devices import SimulatedCell
from lightrocks.adapters.mujoco.plant import MujocoPlant


class MujocoAdapter(SimulatedCell):
    """``runtime.contract.Adapter`` on MuJoCo; scenes are adapters/models/<scene>.xml."""

    PLANT = MujocoPlant


__all__ = ["MujocoAdapter"]
