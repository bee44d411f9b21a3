"""The Franka protocol simulator: franky-sim on loopback with a LightRocks scene's objects in
its world, stepped in lock-step with the client and reporting the external wrench from the
hand's contacts, so that ``lightrocks run … --adapter franka --robot-ip 127.0.0.1`` rehearses
a task before it meets a real arm. Start it with ``lightrocks franka-sim SCENE_OR_CELL`` or
in Python::

    from lightrocks.app.franka_sim import FrankaSim

    with FrankaSim("screwing", address="127.0.0.2") as sim:
        sim.serve_in_thread()
        ...  # connect pylibfranka or franky to 127.0.0.2, run, then read sim.physics()

Importing this package needs franky-sim (``pip install 'lightrocks[franka]'``); see
docs/adapters.md, "The Franka protocol simulator".
"""

from lightrocks.app.franka_sim.server import READY, AddressError, FrankaSim, check_address

__all__ = ["READY", "AddressError", "FrankaSim", "check_address"]
