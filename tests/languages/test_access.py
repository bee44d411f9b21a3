"""Reads and writes per element, as the semantic model answers them
(``languages/lightrocks/access.py``): on the screwing example, and on nested expressions,
vectors, calls, indices and targets that are no variable."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import pytest

from lightrocks.languages.lightrocks.access import Access, access, assigned
from lightrocks.languages.lightrocks.analysis import analysis
from lightrocks.languages.lightrocks.model import Component
from lightrocks.languages.lightrocks.syntax import parse_statechart
from lightrocks.metamodel import ast
from lightrocks.workbench.check import check

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.fixture(scope="module")
def screwing() -> dict[str, Component]:
    context = check([EXAMPLES / "screwing"], [EXAMPLES])
    return {c.name: c for c in analysis(context).models.components}


def reads(*paths: str) -> Access:
    return Access(frozenset(paths))


def test_a_guard_reads_a_scene_attribute_and_parameters(screwing: dict[str, Component]) -> None:
    screw_in = screwing["ScrewIn"]
    turn = next(
        t for t in screw_in.region.transitions if (t.source, t.target) == ("Turn", "screwed")
    )
    assert screw_in.access(turn) == reads("screw.depth", "depth", "tolerance")


def test_an_exit_action_writes_what_it_reads_a_sensor_for(screwing: dict[str, Component]) -> None:
    turn_tool = screwing["TurnTool"]
    exit_action = next(a for a in turn_tool.region.actions if a.kind == "exit")
    found = turn_tool.access(exit_action)
    assert found.writes == {"screw.depth"}
    assert found.reads == {"screw.depth", "robot.travel.z"}


def test_a_command_reads_its_arguments_not_its_device_or_functions(
    screwing: dict[str, Component],
) -> None:
    turn_tool = screwing["TurnTool"]
    do = next(a for a in turn_tool.region.actions if a.kind == "do")
    names = ("robot.tcp", "angle", "advance", "stiffness", "damping", "angularSpeed")
    assert turn_tool.access(do) == reads(*names)


def test_conditions_read_sensor_leaves(screwing: dict[str, Component]) -> None:
    turn_tool = screwing["TurnTool"]
    torque = turn_tool.region.conditions["torqueLimit"]
    assert turn_tool.access(torque) == reads("robot.wrench.torque.z", "maxTorque")
    done = turn_tool.region.conditions["done"]
    assert turn_tool.access(done) == reads("robot.goalReached", "robot.turned", "angle")


def test_a_state_reads_its_arguments(screwing: dict[str, Component]) -> None:
    screw_in = screwing["ScrewIn"]
    assert screw_in.access(screw_in.region.states["Turn"].state) == reads("turn", "pitch", "tight")
    assert screw_in.access(screw_in.region.states["LetGo"].state) == Access()


def test_a_transition_action_reads_and_writes(screwing: dict[str, Component]) -> None:
    screw_in = screwing["ScrewIn"]
    regrasp = next(
        t for t in screw_in.region.transitions if (t.source, t.target) == ("Regrasp", "Turn")
    )
    assert screw_in.access(regrasp) == Access(
        frozenset({"screw.cycles", "maxCycles"}), frozenset({"screw.cycles"})
    )


def test_each_element_is_computed_once(screwing: dict[str, Component]) -> None:
    turn_tool = screwing["TurnTool"]
    torque = turn_tool.region.conditions["torqueLimit"]
    assert turn_tool.access(torque) is turn_tool.access(torque)


CHART = """\
statechart Tricky {
  parameters {
    Integer n = 0;
    Length x = 0 mm;
    Length3 v = [1 mm, 2 mm, 3 mm];
  }
  initial state A {
    entry / { n = n + 1; x = max(abs(x), v[n] * 2) + [x, o.size, 1 mm][0]; }
    exit / { o.pose.x = -(x + o.pose.y); v[n] = x; }
  }
  final state B;
  A -> B [!(n > 2 && (o.ok || abs(robot.wrench.force.z) < 1 N))] tick / { n = 0; };
}
"""


@pytest.fixture(scope="module")
def tricky() -> ast.Statechart:
    return parse_statechart(CHART, "Tricky.lr").statechart


def state(chart: ast.Statechart, name: str) -> ast.State:
    return next(e for e in chart.elements if isinstance(e, ast.State) and e.name == name)


def test_nested_calls_vectors_and_indices(tricky: ast.Statechart) -> None:
    entry = state(tricky, "A").body[0]
    assert access(entry) == Access(frozenset({"n", "x", "v", "o.size"}), frozenset({"n", "x"}))


def test_a_target_that_is_no_variable_writes_nothing(tricky: ast.Statechart) -> None:
    exit_action = state(tricky, "A").body[1]
    found = access(exit_action)
    assert found.writes == {"o.pose.x"}
    assert found.reads == {"x", "o.pose.y", "v", "n"}


def test_a_nested_guard(tricky: ast.Statechart) -> None:
    transition = next(e for e in tricky.elements if isinstance(e, ast.Transition))
    expected = {"n", "o.ok", "robot.wrench.force.z"}
    assert access(transition) == Access(frozenset(expected), frozenset({"n"}))
    assert access(transition.guard) == Access(frozenset(expected))


def test_assigned_parameters_are_the_plain_names_written(tricky: ast.Statechart) -> None:
    assert assigned(tricky) == {"n", "x"}


WHERE = ast.Position("<test>", 1, 1)


@dataclass(frozen=True)
class Twice(ast.ExtensionNode):
    """An expression a language extension might add: its parts are read like any other."""

    arguments: tuple[ast.Argument, ...]
    position: ast.Position = WHERE

    def text(self, expression):
        return "twice(…)"

    def infer(self, infer):
        return None


def test_an_extension_node_reads_its_parts() -> None:
    node = Twice(
        (ast.Argument(ast.Member(ast.Name("screw"), "depth")), ast.Argument(ast.Name("n")))
    )
    statement = ast.Assignment(ast.Name("x"), node)
    assert access(statement) == Access(frozenset({"screw.depth", "n"}), frozenset({"x"}))


def test_a_plain_chart_assigns_its_counter_not_its_constant() -> None:
    context = check([EXAMPLES / "plain"])
    (turnstile,) = analysis(context).models.components
    assert turnstile.assigned == {"passages"}
    operating = turnstile.region.states["Operating"].state
    assert turnstile.access(operating) == reads("passages", "capacity")
