"""LightRocks lightrocks package."""
