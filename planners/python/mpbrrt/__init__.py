"""mpbrrt - mpb-planner-python, the example planner written with the
kit (mpbplanner): RRT-Connect and a shortcut stage (see __main__.py)."""
