"""The PLCopen projects of the worked extension package (``extension_units``) are valid
against the TC6 XML v2.01 schema, and their ST bodies carry the package's syntax."""

from __future__ import annotations

import pytest
from extension_units import ExtensionUnits, extension_units
from lxml import etree
from plcopen_schema import NS


@pytest.fixture(scope="module")
def units(tmp_path_factory: pytest.TempPathFactory) -> ExtensionUnits:
    return extension_units(tmp_path_factory)


def test_every_project_of_the_extension_validates(
    schema: etree.XMLSchema, units: ExtensionUnits, tally
) -> None:
    invalid = {}
    for name, document in units.plcopen.items():
        if not schema.validate(etree.parse(str(document))):
            invalid[name] = str(schema.error_log)
    tally(
        "{valid}/{files} PLCopen projects of the extension valid against the TC6 schema",
        valid=len(units.plcopen) - len(invalid),
        files=len(units.plcopen),
    )
    assert units.plcopen and not invalid, invalid


def test_requirements_document_their_pou(units: ExtensionUnits) -> None:
    root = etree.parse(str(units.plcopen["PegInHole"]))
    pou = root.find(".//p:pou[@name='PegInHole']", NS)
    text = "".join(pou.find("p:documentation", NS).itertext())
    assert "requirement T1: the peg ends in the hole (verified by the outcome done)" in text
