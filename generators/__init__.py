"""LightRocks generators package."""
