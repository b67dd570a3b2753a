#!/bin/sh
# no_leftovers.sh - after every other test (a ctest fixture's cleanup,
# tests/CMakeLists.txt): no process of this build is left running. A
# process is this build's when its program, its working directory or
# its command line lies in MPB_BUILD, or its command line names the
# Python planner (python3 -m mpbrrt) of MPB_SOURCE. This check and
# the processes that started it (ctest, make, a shell) are not counted.
#
# Each found is listed with its pid, working directory and command line,
# then killed, and the check fails: a test left it behind.
set -u
: "${MPB_BUILD:?MPB_BUILD must name the build tree}"
: "${MPB_SOURCE:?MPB_SOURCE must name the source tree}"
build=$(cd "$MPB_BUILD" && pwd -P)
source=$(cd "$MPB_SOURCE" && pwd -P)

# This process and its ancestors.
mine=" $$ "
p=$$
while [ "$p" -gt 1 ] 2>/dev/null; do
    p=$(awk '/^PPid:/ {print $2}' "/proc/$p/status" 2>/dev/null) || break
    [ -n "$p" ] || break
    mine="$mine$p "
done

inside() {      # inside PATH DIR: PATH is DIR or below it
    case $1 in "$2"|"$2"/*) return 0 ;; esac
    return 1
}

found=0
for d in /proc/[0-9]*; do
    pid=${d#/proc/}
    case $mine in *" $pid "*) continue ;; esac
    cmd=$(tr '\0' ' ' 2>/dev/null <"$d/cmdline") || continue
    [ -n "$cmd" ] || continue      # a kernel thread, or gone
    exe=$(readlink "$d/exe" 2>/dev/null) || exe=
    cwd=$(readlink "$d/cwd" 2>/dev/null) || cwd=
    ours=0
    inside "$exe" "$build" && ours=1
    inside "$cwd" "$build/tests" && ours=1
    case $cmd in
    *"$build"/*|*"$MPB_BUILD"/*) ours=1 ;;
    *"-m mpbrrt"*) case $cmd in *"$source"*|*"$MPB_SOURCE"*) ours=1 ;; esac
                       inside "$cwd" "$source" && ours=1 ;;
    esac
    [ "$ours" -eq 1 ] || continue
    found=$((found + 1))
    echo "not ok - left running: pid $pid (in $cwd): $cmd"
done
if [ "$found" -eq 0 ]; then
    echo "ok - no process of $build left running"
    exit 0
fi
echo "$found process(es) of this build outlived the tests that started them"
exit 1
