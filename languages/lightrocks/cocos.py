"""The context conditions of LightRocks components, gathered in the order the language
registers them.

Each CoCo is one small check with a stable code, written in the module of its area:
:mod:`.cocos_names` (names and references), :mod:`.cocos_typing` (the findings of the
typing pass), :mod:`.cocos_components` (layers and how components use one another),
:mod:`.cocos_flow` (the transitions of a region) and :mod:`.cocos_orthogonal` (orthogonal
regions). :mod:`.cocos_safety`, :mod:`.cocos_behaviour` and :mod:`.cocos_silent` keep
lists of their own.
"""

from __future__ import annotations

from lightrocks.languages.lightrocks.cocos_components import (
    action_has_one_command,
    composite_has_no_command,
    known_stereotypes,
    layering,
    no_reference_cycle,
    one_layer,
)
from lightrocks.languages.lightrocks.cocos_flow import (
    choice_branches,
    completion_needs_outcome,
    declared_events,
    deterministic,
    has_entry,
    history_targets,
    no_transition_from_end,
    no_transition_into_start,
    outcomes_handled,
    reaches_end,
    states_reachable,
)
from lightrocks.languages.lightrocks.cocos_names import (
    name_matches_file,
    package_matches_folder,
    stimulus_is_outcome,
    transition_ends_resolve,
    unique_names,
)
from lightrocks.languages.lightrocks.cocos_orthogonal import (
    no_crossing,
    region_contents,
    regions_share_no_device,
)
from lightrocks.languages.lightrocks.cocos_typing import (
    call_signature,
    command_placement,
    dimension_mismatch,
    narrowing,
    not_assignable,
    not_boolean,
    type_mismatch,
    unknown_unit,
    unresolved_member,
    unresolved_name,
    unresolved_type,
    unsafe_value,
)
from lightrocks.workbench.cocos import CoCo

COCOS: tuple[CoCo, ...] = (
    unique_names,
    unresolved_name,
    unresolved_type,
    unresolved_member,
    unknown_unit,
    package_matches_folder,
    name_matches_file,
    transition_ends_resolve,
    stimulus_is_outcome,
    one_layer,
    layering,
    action_has_one_command,
    composite_has_no_command,
    has_entry,
    reaches_end,
    states_reachable,
    no_transition_from_end,
    outcomes_handled,
    no_reference_cycle,
    deterministic,
    known_stereotypes,
    no_transition_into_start,
    completion_needs_outcome,
    history_targets,
    choice_branches,
    declared_events,
    no_crossing,
    region_contents,
    regions_share_no_device,
    call_signature,
    type_mismatch,
    not_boolean,
    dimension_mismatch,
    unsafe_value,
    not_assignable,
    command_placement,
    narrowing,
)
