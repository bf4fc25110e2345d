"""N: naming conventions of REP 103/105/120/199, run only with a `profile`."""
