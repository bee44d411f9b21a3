"""LightRocks mujoco package."""
