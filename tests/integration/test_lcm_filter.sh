#!/bin/sh
# The kernel-side channel filter (mpb_lcm_create, lcm_filter.h) over
# real UDP multicast: a listener filtered to KEEP_1 and KEEP_TWO receives
# exactly those short messages, not channels one byte or one character
# longer or shorter, while an unfiltered listener made before it in the
# same process receives everything; long (fragmented) messages pass whole.
# A channel list the filter cannot hold gives a filter that keeps every
# channel (it still drops malformed datagrams); a URL that is not udpm://
# a plain instance, and the planners and mpb status then warn once.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$MPB_BUILD/tests/mpb-test-lcm-filter" >"$work/out.txt" 2>&1
check "the filter attaches" eq $? 0
count() { awk -v w="$1" -v c="$2" '$1 == w && $2 == c { n = $3 } END { print n + 0 }' "$work/out.txt"; }
check "kept: KEEP_1, short, both of them" eq "$(count filtered KEEP_1)" 2
check "kept: KEEP_TWO" eq "$(count filtered KEEP_TWO)" 1
for ch in DROP_ME KEEP_1X KEEP_ KEEP_TWP K; do
    check "dropped: $ch" eq "$(count filtered "$ch")" 0
    check "... which the unfiltered listener receives" eq "$(count plain "$ch")" 1
done
check "a long message on a kept channel arrives whole" eq "$(count filtered KEEP_1+big)" 1
check "long messages pass whatever their channel (fragments name none)" \
    eq "$(count filtered DROP_BIG+big)" 1
check "more channels than a filter holds: filtered, every channel kept" grep -qx "too_many instance 1 filtered 1" "$work/out.txt"
check "a name too long for LCM: the same" grep -qx "too_long instance 1 filtered 1" "$work/out.txt"
check "no channels: the same" grep -qx "no_channels instance 1 filtered 1" "$work/out.txt"
check "not udpm: an instance, unfiltered" grep -qx "not_udpm instance 1 filtered 0" "$work/out.txt"

# A process whose socket cannot be filtered (memq:// has none) says so in
# one warning line on stderr; each is stopped after 3 s.
for cmd in "planners/null/mpb-planner-null --lcm-url memq://" \
           "planners/python/mpb-planner-python --lcm-url memq://" \
           "tools/mpb status --lcm-url memq://"; do
    # shellcheck disable=SC2086  # the command's words
    timeout 3 $MPB_BUILD/$cmd >/dev/null 2>"$work/warn.err"
    check "unfiltered, ${cmd%% --lcm-url*} warns once" \
        eq "$(grep -c "warning: LCM's receive socket has no filter" "$work/warn.err")" 1
done
[ "$FAILS" -eq 0 ] || cat "$work/out.txt"
mpb_finish
