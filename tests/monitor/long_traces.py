"""A long run's trace, made up: the tests of plotting and replaying long traces share it."""

from __future__ import annotations

from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCREW_TASK = ROOT / "examples" / "screwing" / "tasks" / "ScrewTask.lr"


def records(spans: int) -> list[dict]:
    """A run that passes ``spans`` times through a skill and its action, sampled once each."""
    made = [
        {"time": 0.0, "kind": "run", "model": str(SCREW_TASK), "path": []},
        {"time": 0.0, "kind": "enter", "state": "ScrewTask", "layer": "task"},
    ]
    sample = {"robot.tcp": [0, 0, 0.1], "robot.wrench": {"force": [0, 0, 1], "torque": [0, 0, 0]}}
    for i in range(spans):
        t = i * 0.01
        made += [
            {"time": t, "kind": "enter", "state": "ScrewTask/FindScrew", "layer": "skill"},
            {"time": t, "kind": "enter", "state": "ScrewTask/FindScrew/Look", "layer": "action"},
            {"time": t + 0.005, "kind": "sample", **sample},
            {"time": t + 0.01, "kind": "exit", "state": "ScrewTask/FindScrew/Look"},
            {"time": t + 0.01, "kind": "exit", "state": "ScrewTask/FindScrew"},
        ]
    end = spans * 0.01
    made += [
        {"time": end, "kind": "exit", "state": "ScrewTask"},
        {"time": end, "kind": "finished", "outcome": "screwed"},
    ]
    return made
