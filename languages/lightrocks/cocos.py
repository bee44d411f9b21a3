"""The context conditions of LightRocks components, collected from the module of each area.

Each CoCo is one small check with a stable code, written in the module of its area:
:mod:`.cocos_names` (names and references), :mod:`.cocos_components` (layers and how
components use one another), :mod:`.cocos_flow` (the transitions of a region),
:mod:`.cocos_orthogonal` (orthogonal regions), :mod:`.cocos_safety` (stereotype values,
actions that end, safe ranges through parameters), :mod:`.cocos_silent` (what the tools
would quietly ignore) and :mod:`.cocos_properties` (what a property names). The typing
(:mod:`.cocos_typing`) and the judgement of behaviour (:mod:`.cocos_behaviour`) are passes
that report several codes each.
"""

from __future__ import annotations

from lightrocks.languages.lightrocks import (
    cocos_behaviour,
    cocos_components,
    cocos_dataflow,
    cocos_flow,
    cocos_names,
    cocos_orthogonal,
    cocos_properties,
    cocos_safety,
    cocos_silent,
    cocos_typing,
)
from lightrocks.workbench.cocos import CoCo, cocos_in
from lightrocks.workbench.passes import Pass, passes_in

AREAS = (
    cocos_names,
    cocos_typing,
    cocos_components,
    cocos_flow,
    cocos_orthogonal,
    cocos_safety,
    cocos_behaviour,
    cocos_dataflow,
    cocos_silent,
    cocos_properties,
)
COCOS: tuple[CoCo, ...] = cocos_in(*AREAS)
PASSES: tuple[type[Pass], ...] = passes_in(*AREAS)
