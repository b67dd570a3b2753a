"""mpbplanner - the Python planner of mpbench (see __main__.py)."""
