// Every construct UML/P (.sc) and LightRocks (.lr) share, each in the one form both write:
// converted to .lr and back, this file gives an equal syntax tree.
package shared;

<<plain, author="tests">> statechart Door {
  event open();
  event close();
  event lock();
  event unlock();
  event code();
  event alarm();

  initial { openings = 0; broken = false; } state Closed;
  state Opened [openings >= 1];
  final state Gone;

  <<secure>> state Locked [bolts >= 0] {
    entry / { bolts = bolts + 1; }
    exit / bolts = bolts - 1;
    do / { hum(); }

    initial state Bolted;
    final state Free;

    -> code(1234) / { attempts = attempts + 1; };
    -> [attempts > 3] alarm;
    -> alarm / { };

    Bolted -> Free unlock;
  };

  Closed -> Opened [openings < 100 && !broken] open / { openings = openings + 1; } [openings >= 1];
  Opened -> Closed close / { log("closed", openings, -1, 2.5, true); };
  Closed -> Locked lock(1234, "key") / { code = (code + 1) * 2 % 7 - -3; door.bell.ring(); };
  Locked -> Closed [!(attempts > 3 || broken) == true] / { slots[attempts] = door.slot[0]; };
  Locked -> Gone;
}
