"""The behaviour checker: guards and conditions judged by an SMT solver (fast, run by
``check``), and the outcome flow of the hierarchy model-checked (run by ``verify``)."""
