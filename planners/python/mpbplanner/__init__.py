"""mpbplanner - the Python kit of mpbench: the protocol (node), the world
of libmpbench through ctypes (world), reading a request (request), time
and memory limits (limits, memory). docs/writing-a-planner.md."""
