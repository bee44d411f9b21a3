"""LightRocks metamodel package."""
