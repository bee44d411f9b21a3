"""LightRocks graphviz package."""
