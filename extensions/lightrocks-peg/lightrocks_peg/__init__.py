"""LightRocks extended from outside: requirements in statecharts, a Markdown documentation
target, a guarded MuJoCo adapter and a peg-in-hole scene."""
