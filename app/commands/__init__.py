"""The commands of the ``lightrocks`` command line, one module each; importing this package
registers them all in :data:`common.COMMANDS`, in the order ``--help`` lists them."""

# isort: off
from lightrocks.app.commands import check, verify, fmt, generate, run, sweep  # noqa: F401
from lightrocks.app.commands import replay, plot, listing, lsp  # noqa: F401
from lightrocks.app.commands import studio  # noqa: F401
from lightrocks.app.commands import convert  # noqa: F401
from lightrocks.app.commands import franka_sim  # noqa: F401

# isort: on
