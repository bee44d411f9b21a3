"""LightRocks pinocchio package."""
