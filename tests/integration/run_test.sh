#!/bin/sh
# run_test.sh - run one integration test in a PID namespace of its own, so
# that every process it starts ends with it, however it ends: passed,
# failed, or killed by ctest's timeout.
#
#   sh tests/integration/run_test.sh SCRIPT [ARG...]     (tests/CMakeLists.txt)
#
# The test's shell runs under a small first process of the namespace (a
# shell that waits for it and reaps the orphans it leaves). When that
# first process ends, the kernel kills every process left in the
# namespace; --kill-child makes it end when unshare, the process ctest
# started, is killed. A planner started in the test's own network
# namespace (unshare -n), or under another process that died, used to
# outlive the test; now nothing does. /proc is the namespace's own, so
# the pids a test sees ($!, /proc/PID, nsenter -t PID) are its own.
#
# Where the kernel refuses a PID namespace (a user without root and no
# user namespaces), the test runs as it is, and says so.
script=$1
shift
if [ -z "${MPB_IN_PIDNS:-}" ]; then
    export MPB_IN_PIDNS=1
    user=
    [ "$(id -u)" -eq 0 ] || user=-r
    if unshare $user --pid --mount-proc --kill-child true 2>/dev/null; then
        exec unshare $user --pid --mount-proc --kill-child \
            sh -c 'sh "$@"; exit $?' mpb-test-init "$script" "$@"
    fi
    echo "run_test.sh: no PID namespace here (unshare --pid): a process" \
        "this test leaves behind is not ended" >&2
fi
exec sh "$script" "$@"
