"""What the page's forms and palette show of a chart, read from the checked model: the
boxes and arrows of each level, the outcomes each box can end with, the parameters, and the
charts a chart may import."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from lightrocks.languages.lightrocks.model import Component, Region, may_use
from lightrocks.metamodel import ast, printer


def palette(chart: str, layer: str, components: Mapping[str, Component]) -> list[dict[str, Any]]:
    """The charts a chart of ``layer`` may import, with their parameters and outcomes."""
    return [
        {
            "name": name,
            "layer": c.layer or "",
            "parameters": parameters(c),
            "outcomes": list(c.region.outcomes),
        }
        for name, c in sorted(components.items())
        if may_use(layer or None, c.layer) and name != chart
    ]


def parameters(component: Component, inherited: bool = True) -> list[list[str]]:
    """``[type, name, default text]`` of each parameter of the chart (its own only unless
    ``inherited``)."""
    if inherited:
        found = list(component.region.parameters.values())
    else:
        blocks = [e for e in component.statechart.elements if isinstance(e, ast.ParameterBlock)]
        found = [p for block in blocks for p in block.parameters]
    return [
        [p.type, p.name, printer.expression(p.default) if p.default is not None else ""]
        for p in found
    ]


def levels(component: Component) -> dict[str, dict[str, Any]]:
    """Level key -> what its forms show: each box (a state with the chart it imports and its
    arguments, a condition with its expression) and each arrow with its transitions."""
    found: dict[str, dict[str, Any]] = {}

    def visit(region: Region, key: str, prefix: str) -> None:
        level = found.setdefault(key, {"boxes": {}, "arrows": {}})
        for name, condition in region.conditions.items():
            level["boxes"][prefix + name] = {
                "kind": f"{condition.kind} condition",
                "expression": _text(condition.expression),
            }
        for name, pseudostate in region.pseudostates.items():
            level["boxes"][prefix + name] = {"kind": pseudostate.kind}
        for transition in region.transitions:
            arrow = f"{prefix}{transition.source}->{prefix}{transition.target}"
            level["arrows"].setdefault(arrow, []).append(
                {
                    "stimulus": transition.stimulus,
                    "guard": _text(transition.guard),
                    "action": _statements(transition.action),
                }
            )
        for name, info in region.states.items():
            if region.orthogonal and info.region is not None:
                visit(info.region, key, f"{prefix}{name}/")
                continue
            box: dict[str, Any] = {"kind": "state", "outcomes": list(info.outcomes or ())}
            if info.imported is not None:
                box["imports"] = info.imported.qualified_name
                box["parameters"] = parameters(info.imported)
                box["arguments"] = [
                    [a.name, printer.expression(a.value)] for a in info.state.arguments
                ]
            level["boxes"][prefix + name] = box
            if info.imported is None and info.region is not None:
                visit(info.region, f"{key}/{prefix}{name}", "")

    visit(component.region, component.qualified_name, "")
    return found


def outcomes(component: Component) -> dict[str, dict[str, list[str]]]:
    """Level key -> box -> the outcomes it can end with (a transition's stimuli from it)."""
    return {
        key: {
            name: box.get("outcomes", [])
            for name, box in level["boxes"].items()
            if box["kind"] == "state"
        }
        for key, level in levels(component).items()
    }


def _text(node: ast.Expression | None) -> str:
    return printer.expression(node) if node is not None else ""


def _statements(statements: tuple[ast.Statement, ...] | None) -> str:
    return "\n".join(line for s in statements or () for line in printer.statement(s))
