"""What watching a MuJoCo run costs: simulated seconds per wall second with the monitor
serving a connected page against the same run without a monitor.

Run: ``.venv/bin/python benchmarks/bench_monitor.py [repeats] [task.lr]`` (default 2 repeats
of the DIN-rail task). The runs alternate between the two settings so that the load of the
machine falls on both alike. The page is a websocket client in its own process that reads
every push, as a browser does (the token in a bearer header, as tools send it). The goal:
the watched run keeps at least 90 % of the unwatched speed, since the run's thread only
appends to the feed and never waits for a page.
On a machine shared with other work the wall-clock figures spread widely; the CPU seconds
of this process (run and server threads) are the steadier measure of the monitor's cost.
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import time
from pathlib import Path

from lightrocks.app import pipeline
from lightrocks.app.monitor.watch import monitor_for

ROOT = Path(__file__).resolve().parents[1]
TASK = ROOT / "examples/din_rail/tasks/AssembleRail.lr"
GOAL = 0.90

CLIENT = """
import json, sys
from websockets.sync.client import connect
pushes = records = size = 0
url, token = sys.argv[1].split("?token=")
with connect(url, additional_headers={"Authorization": f"Bearer {token}"}) as socket:
    print("connected", flush=True)
    for message in socket:
        data = json.loads(message)
        pushes, size = pushes + 1, size + len(message)
        records += len(data.get("records", ()))
        if "measurements" in data.get("status", {}):
            break
print(f"page got {records} records in {pushes} pushes, {size / 1e6:.1f} MB", flush=True)
"""


def speed(model: Path, watched: bool) -> tuple[float, float, str]:
    """Simulated seconds per wall second and per CPU second of this process (the run's and
    the server's threads together) of one run; what the page received."""
    cls = pipeline.load(model, [])
    watch, client = None, None
    if watched:
        monitor, watch = monitor_for(model, [], cls.NAME)
        url = monitor.serve("127.0.0.1", 0)
        stream = url.replace("http", "ws").replace("/?", "/stream?")
        client = subprocess.Popen(
            [sys.executable, "-c", CLIENT, stream], stdout=subprocess.PIPE, text=True
        )
        assert client.stdout.readline().strip() == "connected"
    start, cpu = time.perf_counter(), time.process_time()
    result = pipeline.run(pipeline.spec_for(model, [], adapter="mujoco"), cls, watch=watch)
    wall, cpu = time.perf_counter() - start, time.process_time() - cpu
    received = ""
    if client is not None:
        received = client.communicate(timeout=60)[0].strip()
    return result.time / wall, result.time / cpu, received


def main() -> None:
    repeats = int(sys.argv[1]) if len(sys.argv) > 1 else 2
    model = Path(sys.argv[2]).resolve() if len(sys.argv) > 2 else TASK
    print(f"{model.name} in MuJoCo, {repeats} runs per setting, alternating")
    plain, watched = [], []
    for _ in range(repeats):
        plain.append(speed(model, False)[:2])
        *rates, received = speed(model, True)
        watched.append(tuple(rates))
        print(
            f"  unwatched {plain[-1][0]:.3f}, watched {rates[0]:.3f} sim s / wall s; "
            f"per CPU s {plain[-1][1]:.3f} and {rates[1]:.3f} ({received})"
        )
    for column, unit in enumerate(("wall", "CPU")):
        base = statistics.median(p[column] for p in plain)
        seen = statistics.median(w[column] for w in watched)
        ratio = seen / base
        verdict = "within" if ratio >= GOAL else "OUTSIDE"
        print(
            f"simulated s per {unit} s (median): {base:.3f} without monitor, "
            f"{seen:.3f} with a page connected; ratio {ratio:.3f} "
            f"({verdict} the goal of {GOAL:.0%})"
        )


if __name__ == "__main__":
    main()
