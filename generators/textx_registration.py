"""textX generator registrations, so that ``textx generate model.lr --target sfc|dot`` works.

textX hands over one parsed file; the workbench checks it with its folder's model path and
runs the LightRocks generator of the same name, writing next to the model or to
``output_path``.
"""

from __future__ import annotations

from pathlib import Path

from textx import generator

from lightrocks.workbench.check import check
from lightrocks.workbench.generators import (
    GenerationError,
    GenerationRequest,
    load_generator,
    write_all,
)


def _run(target: str, model, output_path: str | None) -> None:
    file = Path(model._tx_filename).resolve()
    context = check([file])
    if context.diagnostics.has_errors:
        raise GenerationError("\n".join(str(d) for d in context.diagnostics.items))
    request = GenerationRequest(context, [file])
    output = Path(output_path) if output_path else file.parent
    write_all(output, load_generator(target).generate(request))


@generator("lightrocks", "sfc")
def sfc_generator(metamodel, model, output_path, overwrite, debug, **custom_args):
    """IEC 61131-3 textual SFC of a LightRocks task or skill."""
    _run("sfc", model, output_path)


@generator("lightrocks", "dot")
def dot_generator(metamodel, model, output_path, overwrite, debug, **custom_args):
    """Graphviz DOT of a LightRocks statechart."""
    _run("dot", model, output_path)
