"""Camera localisation: true poses without noise, reproducible noise with a seed."""

import numpy as np
import pytest

from lightrocks.adapters.mujoco import MujocoAdapter
from lightrocks.adapters.pinocchio import PinocchioAdapter
from lightrocks.runtime.contract import Command, StopCondition

DONE = [StopCondition("done", lambda s: s.camera.done)]


def localize(adapter, count=3):
    return [
        adapter.execute([Command("camera", "localize", {"target": "block"}, DONE, 1.0)])[0]
        for _ in range(count)
    ]


@pytest.mark.parametrize("kind", [MujocoAdapter, PinocchioAdapter])
def test_without_noise_the_true_pose(kind):
    adapter = kind()
    result = localize(adapter, 1)[0]
    assert result.outcome == "done"
    assert np.allclose(result.value.homogeneous, adapter.scene_pose("block").homogeneous)
    assert np.allclose(result.value.translation, [0.5, 0.0, 0.125])


def test_noise_is_reproducible_with_a_seed():
    noise = (0.002, 0.01)
    first = [r.value for r in localize(PinocchioAdapter(seed=3, perception_noise=noise))]
    again = [r.value for r in localize(PinocchioAdapter(seed=3, perception_noise=noise))]
    other = [r.value for r in localize(PinocchioAdapter(seed=4, perception_noise=noise))]
    for a, b, c in zip(first, again, other, strict=True):
        assert np.array_equal(a.homogeneous, b.homogeneous)
        assert not np.allclose(a.translation, c.translation)
    spread = np.linalg.norm(first[0].translation - np.array([0.5, 0.0, 0.125]))
    assert 0 < spread < 0.02
