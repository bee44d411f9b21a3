"""The MuJoCo adapter: the LightRocks devices on a MuJoCo simulation of a scene."""

from __future__ import annotations

from adapters.devices import SimulatedCell
from adapters.mujoco.plant import MujocoPlant
from adapters.video import VideoRecorder


class MujocoAdapter(SimulatedCell):
    """``runtime.contract.Adapter`` on MuJoCo; scenes are adapters/models/<scene>.xml."""

    def __init__(
        self,
        scene: str = "empty",
        *,
        seed: int = 0,
        perception_noise: tuple[float, float] = (0.0, 0.0),
        video: str | None = None,
    ) -> None:
        plant = MujocoPlant(scene)
        recorder = None if video is None else VideoRecorder(video, plant.model)
        super().__init__(
            plant, scene, seed=seed, perception_noise=perception_noise, recorder=recorder
        )


__all__ = ["MujocoAdapter"]
