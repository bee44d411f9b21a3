"""The Pinocchio adapter: the LightRocks devices on the fast dynamics twin."""

from __future__ import annotations

from adapters.devices import SimulatedCell
from adapters.pinocchio.plant import PinocchioPlant
from adapters.video import VideoRecorder


class PinocchioAdapter(SimulatedCell):
    """``runtime.contract.Adapter`` on Pinocchio ABA-style dynamics with penalty contacts."""

    def __init__(
        self,
        scene: str = "empty",
        *,
        seed: int = 0,
        perception_noise: tuple[float, float] = (0.0, 0.0),
        video: str | None = None,
    ) -> None:
        plant = PinocchioPlant(scene)
        recorder = None if video is None else VideoRecorder(video, plant.model)
        super().__init__(
            plant, scene, seed=seed, perception_noise=perception_noise, recorder=recorder
        )


__all__ = ["PinocchioAdapter"]
