"""PLCopen TC6 XML v2.01: the POUs of the SFC target with graphical SFC bodies, for Beremiz,
OpenPLC, CODESYS and other IEC 61131-3 tools that import PLCopen XML.

One ``<Top>.xml`` per selected task or skill. Byte-identical on every run: the file's
creation time is ``SOURCE_DATE_EPOCH`` (reproducible builds), else the Unix epoch.
"""

from __future__ import annotations

import io
import os
from datetime import UTC, datetime

from lightrocks.generators.plcopen.document import project
from lightrocks.generators.sfc_iec61131 import (
    INTERVAL,
    build_unit,
    checked_text,
    environment_of,
    interval_option,
    unit_files,
)
from lightrocks.generators.sfc_iec61131.extensions import Extensions
from lightrocks.languages.lightrocks.analysis import analysis
from lightrocks.workbench.generators import GenerationError, GenerationRequest


def creation_time() -> datetime:
    epoch = os.environ.get("SOURCE_DATE_EPOCH", "0")
    if not epoch.isdigit():
        raise GenerationError(f"SOURCE_DATE_EPOCH='{epoch}' is not a whole number of seconds")
    return datetime.fromtimestamp(int(epoch), UTC)


class PlcopenGenerator:
    name = "plcopen"
    description = "PLCopen TC6 XML v2.01 with graphical SFC"
    options = (INTERVAL,)

    def generate(self, request: GenerationRequest) -> dict[str, str]:
        environment = environment_of(request)  # for syntax of language extensions
        extensions = Extensions(environment)
        interval = interval_option(request)
        typing = analysis(request.context).typing
        created = creation_time()
        files: dict[str, str] = {}
        for name, top in unit_files(request, ".xml").items():
            unit = build_unit(top, typing, extensions)
            checked_text(environment, unit, interval)  # the POUs pass the SFC checker
            document = project(unit, interval, created)
            buffer = io.BytesIO()
            document.write(buffer, encoding="utf-8", xml_declaration=True)
            files[name] = buffer.getvalue().decode("utf-8") + "\n"
        return files


GENERATOR = PlcopenGenerator()
