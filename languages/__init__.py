"""LightRocks languages package."""
