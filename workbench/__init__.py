"""LightRocks workbench package."""
