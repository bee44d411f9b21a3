"""LightRocks python package."""
