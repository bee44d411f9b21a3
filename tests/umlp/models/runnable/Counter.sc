// A UML/P chart whose actions LightRocks can express: converted to .lr, it runs in the
// Python runtime. Its variables belong to the class the chart describes; the conversion
// declares them as parameters of the types their uses show.
package runnable;

statechart Counter {
  event tick();
  event reset();
  event stop();

  initial { count = 0; entries = 10; } state Counting [count <= 3] {
    entry / { entries = entries + 1; }

    initial state Even;
    state Odd;

    -> reset / { count = 0; };

    Even -> Odd tick / { count++; };
    Odd -> Even tick / { count += 1; };
  };

  final state Stopped;

  Counting -> Stopped [count >= 2] stop;
}
