"""LightRocks runtime package."""
