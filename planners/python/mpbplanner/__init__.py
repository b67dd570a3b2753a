"""mpbplanner - the Python kit of mpbench: the protocol (node), and
through libmpbench with ctypes (libmpbench) its authentication (auth),
hub link (hub), socket filter (sockfilter) and world (world); reading a
request (request), time and memory limits (limits, memory).
docs/writing-a-planner.md."""
