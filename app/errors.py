"""What the run pipeline reports to its caller as the user's mistake, not as a crash."""

from __future__ import annotations


class RunError(Exception):
    """A problem the user can fix: unknown adapter, parameter or value."""


class ModelError(Exception):
    """The model has check errors; the argument is the report."""
