#!/bin/sh
# script_help.sh - every script a user runs (tools/*.sh, bench/*.sh; not
# the sourced ones, which have no #! line) answers --help with its usage
# and exit 0, and refuses an option it does not know in one line naming
# it, exit 2, without doing anything else: each runs with an empty
# environment, in an empty folder, with a build tree that does not exist,
# bounded in time.
#
#   tests/tools/script_help.sh SOURCE_DIR
set -u
src=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failed=0
fail() { echo "not ok - $1"; failed=1; }
run() {     # run SCRIPT ARG: the script's stdout to out, stderr to err
    (cd "$work/cwd" && env -i PATH="$PATH" HOME="$work/home" \
        MPB_BUILD="$work/no-build" timeout --kill-after=2 20 \
        sh "$1" "$2" >"$work/out" 2>"$work/err")
}
mkdir "$work/cwd" "$work/home"
for script in "$src"/tools/*.sh "$src"/bench/*.sh; do
    head -1 "$script" | grep -q '^#!' || continue    # sourced, not run
    name=${script#"$src"/}
    run "$script" --help
    rc=$?
    base=$(basename "$script" .sh)
    if [ $rc -ne 0 ]; then
        fail "$name --help exits $rc: $(head -1 "$work/err")"
    elif [ "$(wc -l <"$work/out")" -lt 3 ] ||
            ! head -1 "$work/out" | grep -q "$base"; then
        fail "$name --help prints no usage naming it: $(head -1 "$work/out")"
    else
        echo "ok - $name --help prints its usage"
    fi
    run "$script" --no-such-option
    rc=$?
    if [ $rc -ne 2 ] || [ "$(wc -l <"$work/err")" -ne 1 ] ||
            ! grep -q -- "--no-such-option" "$work/err"; then
        fail "$name refuses an unknown option in one line (exit $rc): $(head -2 "$work/err" | tr '\n' ' ')"
    else
        echo "ok - $name refuses an unknown option in one line"
    fi
    [ -z "$(ls -A "$work/cwd")" ] || {
        fail "$name left files where it ran: $(ls -A "$work/cwd" | head -3 | tr '\n' ' ')"
        rm -rf "$work/cwd"/* "$work/cwd"/.[!.]* 2>/dev/null
    }
done
exit $failed
