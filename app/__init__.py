"""The application on top of the workbench kernel, the languages and the generators: the
command line and the run pipeline (check → generate → cache → import → bind → run)."""
