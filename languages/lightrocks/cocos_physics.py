"""Context conditions on the physics of what actions command, judged with the robot's own
model (:mod:`.behaviour.physics`): joint limits at a goal, the direction of a motion against
its end conditions, the frame an offset is written in, and force and torque thresholds
against the commanded stiffness and the joints' torque limits."""

from __future__ import annotations

from collections.abc import Iterator

from lightrocks.languages.lightrocks.analysis import analysis
from lightrocks.languages.lightrocks.behaviour.conditions import Finding as Judged
from lightrocks.languages.lightrocks.behaviour.judge import SOLVER_TURN
from lightrocks.languages.lightrocks.behaviour.parameters import ParameterValues
from lightrocks.languages.lightrocks.behaviour.physics import Physics
from lightrocks.workbench.check import CheckContext
from lightrocks.workbench.cocos import Code
from lightrocks.workbench.diagnostics import Severity
from lightrocks.workbench.passes import Finding, Pass

W = Severity.WARNING


class PhysicsPass(Pass):
    """Judges the command of every action of the run against the robot's model; nothing is
    judged while names or unit dimensions do not resolve (LR0103, LR0304)."""

    codes = (
        Code("LR0630", W, "a goal leaves every joint room to its limits"),
        Code("LR0631", W, "a motion moves the way its end conditions wait for"),
        Code("LR0632", W, "an offset in the tool frame moves the way it was meant"),
        Code("LR0633", W, "a force threshold is within what the stiffness builds on the way"),
        Code("LR0634", W, "no zero stiffness along an axis the motion or a condition needs"),
        Code("LR0635", W, "a force threshold is within what the joints can exert"),
    )

    def __init__(self, context: CheckContext) -> None:
        super().__init__(context)
        with SOLVER_TURN:
            self.judged = list(self._judge())

    def _judge(self) -> Iterator[Judged]:
        a = analysis(self.context)
        if a.typing.findings.get("LR0103") or a.typing.findings.get("LR0304"):
            return
        values = ParameterValues(a.models)
        for component in a.models.components:
            if component.layer == "action":
                yield from Physics(a.typing, values, component).findings()

    def findings(self) -> Iterator[Finding]:
        for judged in self.judged:
            yield judged.code, judged.position, judged.message, judged.hint
