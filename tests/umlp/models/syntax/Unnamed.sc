// SCBasis: an unnamed statechart, written with the keyword automaton
<<flat>> automaton {
  initial state A;
  state B;
  A -> B go;
  B -> A;
}
