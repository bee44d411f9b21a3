"""``lightrocks franka-sim``: a simulated Franka FR3 with its hand on a loopback address, in
a cell's scene, that ``lightrocks run … --adapter franka --robot-ip ADDRESS`` drives through
libfranka's own network protocol (docs/adapters.md, "The Franka protocol simulator")."""

from __future__ import annotations

import argparse
import signal
import sys
import threading

from lightrocks.app.commands.common import COMMANDS, EXIT_FINDINGS, EXIT_OK, complain, require

PARTS = ("lightrocks.app.franka_sim",)


def _configure_franka_sim(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "franka-sim", help="serve a simulated Franka arm in a cell's scene on a loopback address"
    )
    parser.add_argument(
        "scene",
        metavar="CELL_OR_SCENE",
        help="a scene name (see 'list scenes') or a .lrd cell file",
    )
    parser.add_argument(
        "--address",
        default="127.0.0.1",
        help="the 127.x.y.z address to listen on (libfranka's ports 1337 and 1338; "
        "default: 127.0.0.1)",
    )


def cmd_franka_sim(args: argparse.Namespace) -> int:
    """Serve until Ctrl-C or SIGTERM, then exit 0; exit 1 for an unknown scene or cell, an
    address that is not loopback or is taken, or a scene the simulator cannot build."""
    require("franka-sim", PARTS, ("franky_sim",), "franka")
    from lightrocks.adapters.scene import SceneFault
    from lightrocks.app.franka_sim import AddressError, FrankaSim
    from lightrocks.app.franka_sim.cells import CellError, scene_of

    try:
        scene = scene_of(args.scene)
        sim = FrankaSim(scene, address=args.address)
        sim.start()
    except (CellError, AddressError, SceneFault) as error:
        complain(str(error))
        return EXIT_FINDINGS
    stop = threading.Event()
    previous = {s: signal.signal(s, lambda *_: stop.set()) for s in (signal.SIGINT, signal.SIGTERM)}
    try:
        print(
            f"franka-sim: FR3 in scene {scene!r} ready on {args.address} "
            f"(lightrocks run TASK --adapter franka --robot-ip {args.address})",
            flush=True,
        )
        sim.serve(stop)
    finally:
        for number, handler in previous.items():
            signal.signal(number, handler)
        steps, stalls = sim.steps, sim.stalls
        sim.close()
    stalled = f", {stalls} stalled cycles (not reproducible)" if stalls else ""
    print(
        f"franka-sim: stopped after {steps} steps ({steps / 1000:.3f} s simulated){stalled}",
        file=sys.stderr,
    )
    return EXIT_OK


# The decorator ``common.command`` keys a command by its function's name, which cannot hold
# the hyphen of ``franka-sim``.
COMMANDS["franka-sim"] = (_configure_franka_sim, cmd_franka_sim)
