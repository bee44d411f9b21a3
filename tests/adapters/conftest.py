"""Adapters are built per test: each is a few MB and starts in ~0.3 s of simulated settling."""

import pytest

from lightrocks.adapters.mujoco import MujocoAdapter
from lightrocks.adapters.pinocchio import PinocchioAdapter

ADAPTERS = {"mujoco": MujocoAdapter, "pinocchio": PinocchioAdapter}


@pytest.fixture(params=sorted(ADAPTERS))
def adapter(request):
    instance = ADAPTERS[request.param]()
    yield instance
    instance.close()
