"""One passing and one failing model per CoCo code: the table of cases, gathered from the
module of each area.

The models the cases build on and the :class:`~cocos.models.Case` record are in
:mod:`cocos.models`. The first case of every code comes first, then the further failing
models of codes that fail in several ways, in the order the table grew, so that the test
ids are collected and run in a stable order.
"""

from __future__ import annotations

from cocos.cases_behaviour import BEHAVIOUR_CASES, DURATION_CASES, PROPERTY_CASES
from cocos.cases_dataflow import DATAFLOW_CASES
from cocos.cases_names import NAME_CASES, NAME_VARIANTS
from cocos.cases_orthogonal import ORTHOGONAL_CASES
from cocos.cases_safety import SAFETY_CASES
from cocos.cases_structure import STRUCTURE_CASES, STRUCTURE_VARIANTS
from cocos.cases_types import TYPE_CASES
from cocos.cases_umlp import UMLP_CASES
from cocos.models import Case

CASES: list[Case] = [
    *NAME_CASES,
    *STRUCTURE_CASES,
    *ORTHOGONAL_CASES,
    *TYPE_CASES,
    *NAME_VARIANTS,
    *STRUCTURE_VARIANTS,
    *SAFETY_CASES,
    *BEHAVIOUR_CASES,
    *DURATION_CASES,
    *DATAFLOW_CASES,
    *PROPERTY_CASES,
    *UMLP_CASES,
]
