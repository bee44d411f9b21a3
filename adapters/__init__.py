"""LightRocks adapters package."""
