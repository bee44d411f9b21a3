"""LightRocks domain package."""
