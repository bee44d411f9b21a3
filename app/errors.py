"""What the run pipeline reports to its caller as the user's mistake, not as a crash."""

from __future__ import annotations


class RunError(Exception):
    """A problem the user can fix: unknown adapter, parameter or value."""


class ModelError(Exception):
    """The model has check errors; the argument is the report."""


class SceneError(Exception):
    """The scene of a run is broken (its MJCF does not load, a hook raised): the scene
    author's to fix, reported with exit code 1, not as a wrong use of the command."""
