"""The CoCos for textX's own commands: ``textx check`` and ``textx generate`` parse with the
metamodels registered in ``textx_languages``, and this model processor then checks the file
the way ``lightrocks check`` does, so a model with findings fails there too (exit 1).

Imported packages are found beside the file's package root, in the folders of the model
parameter ``path`` (``textx generate … --path DIR``) and in those of ``LIGHTROCKS_PATH``
(``os.pathsep``-separated; ``textx check`` takes no options of its own).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from textx import TextXSemanticError

from lightrocks.workbench import report
from lightrocks.workbench.check import check

PATH_VARIABLE = "LIGHTROCKS_PATH"


def model_path(given: str = "") -> list[Path]:
    """The folders of ``given`` and of ``LIGHTROCKS_PATH``; a missing folder is an error."""
    texts = [given, os.environ.get(PATH_VARIABLE, "")]
    folders = [Path(p) for text in texts for p in text.split(os.pathsep) if p]
    missing = [str(f) for f in folders if not f.is_dir()]
    if missing:
        raise TextXSemanticError(f"model path: no such folder: {', '.join(missing)}")
    return folders


def with_cocos(metamodel: Any) -> Any:
    """``metamodel`` with the model parameter ``path`` and the CoCos as model processor."""
    metamodel.model_param_defs.add("path", "model-path folders, os.pathsep-separated")
    metamodel.register_model_processor(_run_cocos)
    return metamodel


def _run_cocos(model: Any, metamodel: Any) -> None:
    file = getattr(model, "_tx_filename", None)
    if not file:
        return  # a model parsed from a string has no place among packages
    params = getattr(model, "_tx_model_params", None)
    given = params.get("path", "") if params is not None else ""
    context = check([Path(file)], model_path(given))
    if context.diagnostics.has_errors:
        raise TextXSemanticError(report.text(context.diagnostics.items))
