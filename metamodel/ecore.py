"""The Ecore metamodel of LightRocks, derived from the AST classes, and XMI export (pyecore).

Every AST dataclass becomes an EClass; plain fields become EAttributes, fields holding nodes
become containment EReferences. A union of node types used by the AST (``Expression``,
``Statement``, ``Element``, ``Declaration``) becomes an abstract EClass that its members
extend; any other union is typed by the abstract root ``Node``. Source positions (every
field typed ``Position``) are left out: they are not part of a model's meaning.
"""

from __future__ import annotations

import dataclasses
import io
import re
import types
import typing
from functools import cache

from pyecore import ecore
from pyecore.resources import ResourceSet
from pyecore.resources.resource import URI

from lightrocks.metamodel import ast

NS_URI = "http://lightrocks.org/lightrocks/1.0"
NAMED_UNIONS = {
    "Expression": ast.Expression,
    "Statement": ast.Statement,
    "Element": ast.Element,
    "Declaration": ast.Declaration,
}
PLAIN = {str: ecore.EString, int: ecore.EInt, float: ecore.EDouble, bool: ecore.EBoolean}
SKIPPED = {"file"}


def _node_classes() -> list[type]:
    found = [c for c in vars(ast).values() if dataclasses.is_dataclass(c) and isinstance(c, type)]
    return sorted((c for c in found if c is not ast.Position), key=lambda c: c.__name__)


def _members(hint: object) -> tuple[object, ...]:
    if typing.get_origin(hint) in (typing.Union, types.UnionType):
        return typing.get_args(hint)
    return (hint,)


@cache
def metamodel() -> ecore.EPackage:
    """The EPackage ``lightrocks`` (built once)."""
    package = ecore.EPackage("lightrocks", nsURI=NS_URI, nsPrefix="lightrocks")
    root = ecore.EClass("Node", abstract=True)
    package.eClassifiers.append(root)
    unions = {name: ecore.EClass(name, abstract=True, superclass=(root,)) for name in NAMED_UNIONS}
    package.eClassifiers.extend(unions.values())
    classes = {c: ecore.EClass(c.__name__, superclass=(root,)) for c in _node_classes()}
    for cls, eclass in classes.items():
        for name, union in NAMED_UNIONS.items():
            if cls in _members(union):
                eclass.eSuperTypes.append(unions[name])
    package.eClassifiers.extend(classes.values())
    for cls, eclass in classes.items():
        hints = typing.get_type_hints(cls, vars(ast))
        for field in dataclasses.fields(cls):
            if field.name not in SKIPPED and hints[field.name] is not ast.Position:
                eclass.eStructuralFeatures.append(
                    _feature(field.name, hints[field.name], classes, unions, root)
                )
    return package


def _feature(name, hint, classes, unions, root) -> ecore.EStructuralFeature:
    members = [m for m in _members(hint) if m is not type(None)]
    optional = len(members) < len(_members(hint))
    many = len(members) == 1 and typing.get_origin(members[0]) is tuple
    if many:
        members = list(_members(typing.get_args(members[0])[0]))
    lower = 0 if optional or many else 1
    upper = -1 if many else 1
    if len(members) == 1 and members[0] in PLAIN:
        return ecore.EAttribute(name, PLAIN[members[0]], lower=lower, upper=upper)
    if len(members) == 1 and members[0] in classes:
        target = classes[members[0]]
    else:
        union = next((u for n, u in NAMED_UNIONS.items() if set(_members(u)) == set(members)), None)
        name_of = {id(u): n for n, u in NAMED_UNIONS.items()}
        target = unions[name_of[id(union)]] if union is not None else root
    return ecore.EReference(name, target, containment=True, lower=lower, upper=upper)


_NOT_IN_XML = re.compile("[^\t\n\r\x20-\ud7ff\ue000-\ufffd\U00010000-\U0010ffff]")


def xml_text(value: str) -> str:
    """``value`` with the characters XML 1.0 cannot carry (controls such as ESC or NUL)
    written as ``\\uXXXX``, so that any model string can be exported."""
    return _NOT_IN_XML.sub(lambda m: f"\\u{ord(m.group()):04x}", value)


def to_eobject(node: object) -> ecore.EObject:
    """An instance of the metamodel holding the same values as the AST ``node``."""
    eclass = metamodel().getEClassifier(type(node).__name__)
    instance = eclass()
    for feature in eclass.eAllStructuralFeatures():
        value = getattr(node, feature.name)
        if value is None:
            continue
        if isinstance(value, str):
            value = xml_text(value)
        elif feature.many:
            value = [xml_text(v) if isinstance(v, str) else v for v in value]
        if feature.many:
            values = [to_eobject(v) if dataclasses.is_dataclass(v) else v for v in value]
            getattr(instance, feature.name).extend(values)
        else:
            setattr(
                instance,
                feature.name,
                to_eobject(value) if dataclasses.is_dataclass(value) else value,
            )
    return instance


class _MemoryURI(URI):
    """A URI whose output stream stays in memory, so that callers get the text."""

    def __init__(self, name: str) -> None:
        super().__init__(name)
        self.buffer = io.BytesIO()

    def create_outstream(self) -> io.BytesIO:
        return self.buffer

    def close_stream(self) -> None:
        pass


def _save(name: str, content: ecore.EObject) -> str:
    resources = ResourceSet()
    uri = _MemoryURI(name)
    resource = resources.create_resource(uri)
    resource.append(content)
    resource.save()
    return uri.buffer.getvalue().decode("utf-8")


def metamodel_text() -> str:
    """``lightrocks.ecore``: the metamodel as Ecore XMI."""
    return _save("lightrocks.ecore", metamodel())


def model_text(unit: ast.StatechartUnit, name: str) -> str:
    """One statechart unit as XMI, an instance of ``lightrocks.ecore``."""
    return _save(name, to_eobject(unit))
