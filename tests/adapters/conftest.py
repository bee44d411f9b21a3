"""Adapters are built per test: each is a few MB and starts in ~0.3 s of simulated settling."""

from collections.abc import Callable

import pytest
from judges import missing

from lightrocks.adapters.mujoco import MujocoAdapter
from lightrocks.adapters.pinocchio import PinocchioAdapter
from lightrocks.adapters.robots.robot import Robot, RobotDataMissing
from lightrocks.adapters.scene_registry import robot

ADAPTERS = {"mujoco": MujocoAdapter, "pinocchio": PinocchioAdapter}


@pytest.fixture(params=sorted(ADAPTERS))
def adapter(request):
    instance = ADAPTERS[request.param]()
    yield instance
    instance.close()


@pytest.fixture(scope="session")
def installed() -> Callable[[str], Robot]:
    """``installed(name)``: the registered robot, once its model files are found; a robot
    whose files are not installed (the Panda without ``lightrocks[panda]``) skips the test
    locally and fails it in CI, which installs them (``make test``)."""

    def check(name: str) -> Robot:
        chosen = robot(name)
        try:
            chosen.mjcf()
        except RobotDataMissing as error:
            missing(f"the model files of robot {name!r}", str(error))
        return chosen

    return check
