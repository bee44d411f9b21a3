"""Watching a run: force, torque and TCP samples in the trace, and plots of a recorded trace."""
