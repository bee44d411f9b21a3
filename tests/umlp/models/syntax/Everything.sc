/* Every construct of MontiCore's UMLStatecharts grammar and of the Java it embeds, written
   for the workbench's tests (no model of MontiCore's corpus is copied). */
package syntax;

import java.util.List;
import java.util.*;

<<generated, author="the \"tests\"">> statechart Everything {
  // SCEvents: with and without return type, typed parameters
  event void reset();
  event int count(int step, java.lang.String label);
  event List<String> names(Map<String, List<?>> table, int[] values, String[][] grid);
  event started();

  (c)

  <<entry>> initial { counter = 0; names.clear(); } state Idle; // SCTransitions4Code: ante
  final state Done;

  state Working [counter >= 0 && !stopped] {
    (...)
    entry / { log("in"); }
    exit / log("out");
    entry / ;
    exit / { close(); } [closed]
    do / {
      int i = 0, j[] = {1, 2,}, k;
      final double d = 1.5e3;
      long big = 10L;
      float f = 2.5f;
      double g = .5;
      char c = '\n';
      String s = "a \"quoted\" string";
      Object o = null;
      boolean b = true;
      int h = 0x1F;
      List<Map<String, Integer>> table = lookup();
      int[][] grid = {{1}, {2, 3}};
      if (i < 3) i++; else { i--; --i; }
      if (b) {
        ++i;
      }
      if (b) i = 1; else if (!b) i = 2;
      while (i > 0) i -= 1;
      do { i = i + 1; } while (i < 5);
      do i++; while (i < 9);
      for (int n = 0; n < 3; n++) { total *= n; }
      for (i = 0, k = 1; ; ) break;
      for (; i < 3; i++, k--) ;
      for (final String name : names) { continue; }
      switch (i) {
        case 1:
        case 2:
          s = "few";
          break;
        default:
          s = "many";
      }
      switch (k) { case 0: k = 1; default: }
      {
        ;
      }
      x = a ? b : c;
      y = (a + b) * c / d % e - -f + +g - (-h);
      z = ~mask & 0xFF | bits ^ flags;
      w = left << 2 >> 1 >>> 3;
      v = p == q != r;
      u = arr[i][j].field.method(1, "two")[0];
      flag = !done || ready && (count <= 10 || count >= 20) && count < 5 == count > 1;
      t %= 3; t /= 2; t &= 1; t |= 2; t ^= 3; t <<= 1; t >>= 1; t >>>= 1; t -= 1; t += 1;
      t *= 2;
      a = b = c;
      return;
    }

    initial state Sub1;
    <<inner>> initial final state Sub2 { };
    state Sub3 [true] {
      state Deep;
    };

    -> [counter > 10] count(1, "x") / { counter++; } [counter > 0];
    -> reset;
    -> [ready] / ;
    -> / {};
    <<internal>> -> started() / counter += 2;;
    Sub1 -> Sub2 tick;
    Sub2 -> Sub3 [x] / [y];
  };

  initial { init(); } state Outer [ok] {
    initial state Inner;
  };

  Idle -> Working [counter == 0] started;
  Working -> Done count(1, "label") / { counter = counter + 1; } [counter > 0];
  Working -> Done / [stopped];
  Working -> Idle reset() / ;
  <<timed>> Done -> Idle a.b.qualified / return;;
  Idle -> Idle [true] / counter++;;
  Idle -> Outer names(list, new_values) / { return counter; };
  Outer -> Idle / x = 1; [x == 1];
}
