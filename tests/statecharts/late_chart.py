"""A chart whose choice, entered by a time event, has no branch that holds while a time event
of the enclosing state is due at the same instant: the construct tests and the differential
run against sismic both judge it."""

from __future__ import annotations

LATE = """package d;

statechart Late {
  parameters {
    Integer n = 0;
    Integer m = 0;
    Integer k = 0;
  }

  initial state Outer {
    initial state Wait;
    state Done;
    choice Which;
    Wait -> Which after(500 ms);
    Which -> Done [n == 1];
  }
  state Away;

  Outer -> Away after(500 ms);
}
"""
