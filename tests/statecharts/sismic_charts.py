"""The plain charts, as LightRocks text by name, that the differential tests run on LightRocks
and on sismic and the SCXML judge converts."""

from __future__ import annotations

CHARTS = {
    "Turnstile": """package d;

statechart Turnstile {
  parameters {
    Integer passages = 0;
    Integer capacity = 3;
  }

  initial state Operating {
    initial state Locked;
    state Unlocked;
    Locked -> Unlocked [passages < capacity] coin;
    Unlocked -> Unlocked coin;
    Unlocked -> Locked push / { passages = passages + 1; };
  }
  state Maintenance {
    entry / { passages = 0; }
  }
  final state Off;

  Operating -> Maintenance service;
  Maintenance -> Operating resume;
  Operating -> Off shutdown;
  Maintenance -> Off shutdown;
}
""",
    "Q": """package d;

statechart Q {
  initial state Idle;
  state Job {
    end condition out;
    initial state Load;
    final state Ok;
    Load -> Ok load;
    Load -> out bail;
  }
  state Other;

  Idle -> Job go;
  Job -> Idle Ok;
  Job -> Other out;
  Other -> Idle back;
}
""",
    "Line": """package d;

statechart Line {
  parameters {
    Integer scrapped = 0;
  }

  initial state Idle;
  state Process {
    initial state Work;
    state Check {
      initial state Measure;
      state Retry;
      final state Good;
      Measure -> Good pass;
      Measure -> Retry fail;
      Retry -> Measure pass;
    }
    final state Ok;
    Work -> Check done;
    Check -> Ok;
    Check -> Work fail;
  }
  state Scrap {
    entry / { scrapped = scrapped + 1; }
  }

  Idle -> Process go;
  Process -> Idle;
  Process -> Scrap bad;
  Scrap -> Idle [scrapped < 2] reset;
}
""",
    "Nest": """package d;

statechart Nest {
  parameters {
    Integer ticks = 0;
    Boolean armed = false;
  }

  initial state A {
    initial state B {
      initial state C;
      state D;
      C -> D tick / { ticks = ticks + 1; };
      D -> C tick;
    }
    state E;
    B -> E [ticks >= 2] tick;
    B -> E jump;
    E -> B jump / { armed = !armed; };
  }
  state F;

  A -> F [armed && ticks % 2 == 0] leave;
  A -> F reset;
  F -> A back / { ticks = 0; };
}
""",
    "Pump": """package d;

statechart Pump {
  events {
    start;
    stop;
    tick;
  }

  parameters {
    Integer strokes = 0;
  }

  initial state Off;
  state On {
    initial state Priming;
    state Running {
      internal [strokes < 3] tick / { strokes = strokes + 1; };
    }
    Priming -> Running after(500 ms);
    Running -> Priming [strokes >= 3] tick / { strokes = 0; };
  }
  state Cooling {
    entry / { strokes = 0; }
  }

  Off -> On start;
  On -> Cooling stop;
  Cooling -> Off after(750 ms);
}
""",
    "Router": """package d;

statechart Router {
  parameters {
    Integer n = 0;
  }

  initial state Idle;
  state Small;
  state Large;
  state Huge;
  choice Size;

  Idle -> Size go / { n = n + 1; };
  Size -> Small [n < 2];
  Size -> Large [n < 4];
  Size -> Huge;
  Small -> Idle back;
  Large -> Idle back;
  Huge -> Idle back / { n = 0; };
}
""",
    "Player": """package d;

statechart Player {
  initial state Stopped;
  state Playing {
    initial state Intro;
    state Song {
      initial state Verse;
      state Chorus;
      Verse -> Chorus next;
      Chorus -> Verse next;
    }
    history H;
    deep history D;
    Intro -> Song next;
  }
  state Paused;

  Stopped -> Playing play;
  Playing -> Paused pause;
  Paused -> Playing.H resume;
  Paused -> Playing.D deepresume;
  Paused -> Stopped stop;
  Playing -> Stopped stop;
}
""",
    "Cell": """package d;

statechart Cell {
  parameters {
    Integer parts = 0;
  }

  initial state Idle;
  state Work {
    region Arm {
      initial state Reach;
      state Grip;
      final state Placed;
      Reach -> Grip near;
      Grip -> Placed close / { parts = parts + 1; };
      Grip -> Reach slip;
    }

    region Camera {
      initial state Search;
      state Track;
      final state Seen;
      Search -> Track found;
      Track -> Seen near;
      Track -> Search lost;
    }
  }
  state Fault;

  Idle -> Work [parts < 2] go;
  Work -> Idle;
  Work -> Fault slip;
  Fault -> Idle reset;
}
""",
    "Crossing": """package d;

statechart Crossing {
  parameters {
    Integer calls = 0;
  }

  region Traffic {
    initial state Red;
    state Green;
    state Yellow;
    Red -> Green after(1 s);
    Green -> Yellow after(750 ms);
    Yellow -> Red after(250 ms);
    Green -> Yellow press;
  }

  region Walker {
    initial state Wait {
      internal [calls < 3] press / { calls = calls + 1; };
    }
    state Cross {
      initial state Steady;
      state Blink {
        region Lamp {
          initial state Lit;
          state Dark;
          Lit -> Dark after(250 ms);
          Dark -> Lit after(250 ms);
        }

        region Beep {
          initial state Quiet;
          state Loud;
          Quiet -> Loud press;
          Loud -> Quiet after(500 ms);
        }
      }
      Steady -> Blink after(500 ms);
    }
    Wait -> Cross go;
    Cross -> Wait stop;
  }
}
""",
    "Press": """package d;

statechart Press {
  initial state Off;
  state On {
    exit / { }

    region Motor {
      initial state Slow;
      state Fast {
        initial state Ramp;
        final state Top;
        Ramp -> Top up;
      }
      final state Halted;
      Slow -> Fast up;
      Fast -> Slow down;
      Fast -> Halted;
    }

    region Guard {
      initial state Closed;
      final state Locked;
      state Open;
      Closed -> Open open;
      Open -> Closed close;
      Closed -> Locked lock;
    }
  }
  final state Done;

  Off -> On power;
  On -> Off power;
  On -> Done;
}
""",
    "Unhandled": """package d;

statechart Unhandled {
  initial state Idle;
  state Job {
    initial state Load;
    final state Ok;
    final state Late;
    Load -> Ok load;
    Load -> Late wait;
  }

  Idle -> Job go;
  Job -> Idle Ok;
}
""",
}
