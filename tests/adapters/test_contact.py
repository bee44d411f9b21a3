"""Force stop conditions fire on contact with the static block in both adapters, with every
robot: its fingertips are 15 mm below its TCP."""

import numpy as np
import pinocchio as pin
import pytest

from lightrocks.adapters.mujoco import MujocoAdapter
from lightrocks.adapters.pinocchio import PinocchioAdapter
from lightrocks.runtime.contract import Command, StopCondition

FINGERTIP_BELOW_TCP = 0.015
BLOCK_TOP = 0.15


@pytest.fixture(
    params=[
        (kind, robot) for kind in (MujocoAdapter, PinocchioAdapter) for robot in ("lwr", "panda")
    ],
    ids=lambda param: f"{param[0].__name__}-{param[1]}",
)
def adapter(request, installed):
    kind, robot = request.param
    installed(robot)
    instance = kind("empty", robot=robot)
    yield instance
    instance.close()


def test_tared_wrench_at_rest_is_small(adapter):
    adapter.execute(
        [Command("robot", "moveCartesian", {"goal": adapter.snapshot().robot.tcp}, [], 0.5)]
    )
    wrench = adapter.snapshot().robot.wrench
    assert wrench.force.norm() < 0.1
    assert wrench.torque.norm() < 0.1


def test_move_down_stops_on_the_block(adapter):
    tcp = adapter.snapshot().robot.tcp
    goal = pin.SE3(tcp.rotation, tcp.translation - np.array([0.0, 0.0, 0.2]))
    touch = StopCondition("touch", lambda s: abs(s.robot.wrench.force.z) > 5.0)
    result = adapter.execute(
        [Command("robot", "moveCartesian", {"goal": goal, "speed": 0.05}, [touch], 5)]
    )[0]
    assert result.outcome == "touch"
    snap = adapter.snapshot()
    gap = snap.robot.tcp.translation[2] - FINGERTIP_BELOW_TCP - BLOCK_TOP
    assert abs(gap) < 1e-3
    assert snap.robot.wrench.force.z > 0  # the block pushes the tool up
    assert snap.robot.travel.z < -0.1
