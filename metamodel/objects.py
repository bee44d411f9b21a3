"""textX model objects built straight from Arpeggio's parse tree.

textX turns a parse tree into a model with a general object-graph builder: it resolves
cross-references, runs user classes and object processors, and computes the line and column
of every object and every keyword. The grammars of this workbench use none of that (every
attribute is contained, names are plain strings, positions are turned into lines by the AST
converter), and for a large model the general builder took two fifths of the parse. This
builder makes the same objects (instances of the metamodel's classes with the same
attributes, ``parent`` and ``_tx_position``) in one pass over the tree, with a plan per
grammar rule made on first use.

A metamodel that does use cross-references, user classes or object processors of its own is
not eligible (:func:`eligible`); :mod:`metamodel.grammar` then lets textX build the model.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from arpeggio import Terminal
from textx.const import MULT_ONEORMORE, MULT_ZEROORMORE, RULE_ABSTRACT, RULE_COMMON, RULE_MATCH

Plan = Callable[[Any, Any], Any]
"""Builds the value of one parse-tree node: ``plan(node, parent_object)``."""

_MANY = (MULT_ZEROORMORE, MULT_ONEORMORE)


def eligible(metamodel: Any) -> bool:
    """Whether models of ``metamodel`` are plain containment trees of generic classes."""
    if metamodel.user_classes:
        return False
    for cls in metamodel:
        if cls._tx_type == RULE_COMMON and cls.__name__ in metamodel._obj_processors:
            return False
        if any(attr.ref and not attr.cont for attr in cls._tx_attrs.values()):
            return False
    return True


class ObjectBuilder:
    """Builds model objects of one metamodel; plans are kept per grammar rule."""

    def __init__(self, metamodel: Any) -> None:
        self._metamodel = metamodel
        self._plans: dict[int, Plan] = {}

    def build(self, node: Any, parent: Any = None) -> Any:
        """The model object (or plain value) of a parse-tree node."""
        plan = self._plans.get(id(node.rule))
        if plan is None:
            plan = self._plans[id(node.rule)] = self._plan(node)
        return plan(node, parent)

    def _plan(self, node: Any) -> Plan:
        process = self._metamodel.process
        if isinstance(node, Terminal):
            kind = node.rule_name
            return lambda n, _parent: process(n.value, kind, None, None, None)
        rule_type = node.rule._tx_class._tx_type
        if rule_type == RULE_MATCH:
            return lambda n, _parent: self._match(n)
        if rule_type == RULE_ABSTRACT:
            return self._abstract
        return self._object_plan(node.rule._tx_class)

    def _match(self, node: Any) -> Any:
        """A match rule's value: a terminal's converted text, or the joined texts of its
        parts, converted by the rule (as textX does)."""
        process = self._metamodel.process
        if isinstance(node, Terminal):
            return process(node.value, node.rule_name, None, None, None)
        if len(node) > 1:
            text = "".join(str(self._match(part)) for part in node)
        else:
            text = self._match(node[0])
        return process(text, node.rule_name, None, None, None)

    def _abstract(self, node: Any, parent: Any) -> Any:
        """An abstract rule stands for the one concrete rule it matched."""
        if len(node) == 1:
            return self.build(node[0], parent)
        for part in node:
            if not isinstance(part, Terminal):
                return self.build(part, parent)
        return "".join(str(part) for part in node)

    def _object_plan(self, cls: type) -> Plan:
        scalars, lists = self._blank(cls)
        many = frozenset(lists)
        build = self.build

        def plan(node: Any, parent: Any) -> Any:
            obj = cls.__new__(cls)
            attrs = dict(scalars)
            for name in lists:
                attrs[name] = []
            attrs["_tx_position"] = node.position
            attrs["_tx_position_end"] = node.position_end
            if parent is not None:
                attrs["parent"] = parent
            for part in node:
                kind = part.rule_name
                if not kind.startswith("__asgn"):
                    continue
                name = part.rule._attr_name
                if kind == "__asgn_optional":
                    attrs[name] = True
                elif kind == "__asgn_plain":
                    value = build(part[0], obj)
                    if name in many:
                        attrs[name].append(value)
                    else:
                        attrs[name] = value
                else:
                    values = attrs[name]
                    for item in part:
                        if item.rule_name != "sep":
                            values.append(build(item, obj))
            obj.__dict__ = attrs
            return obj

        return plan

    def _blank(self, cls: type) -> tuple[dict[str, Any], tuple[str, ...]]:
        """The initial attributes of a new ``cls`` object, as textX sets them: scalar
        defaults, and the names of the list attributes (each object needs its own lists)."""
        template = cls.__new__(cls)
        self._metamodel._init_obj_attrs(template)
        lists = tuple(name for name, attr in cls._tx_attrs.items() if attr.mult in _MANY)
        return {k: v for k, v in vars(template).items() if k not in lists}, lists
