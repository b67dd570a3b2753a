#!/bin/sh
# bench/ompl_peer.sh - the peer of item 6 (docs/performance.md): OMPL's own
# ompl_benchmark_statistics.py, of the OMPL that is installed. Prints its
# path, or one line on stderr and exit 1 when it cannot be had.
#
#   bench/ompl_peer.sh [DIR]     (default .cache/ompl-peer of the sources)
#
# The script is not part of mpbench and no Debian package installs it, but
# Debian's source package of OMPL carries it. This takes that package, of
# the version of libompl-dev that is installed, from the Debian archive
# with apt-get source (which checks the archive's signature and every
# file's hash), from the archives the machine's own apt sources name, into
# a private apt state under DIR: nothing of the system's apt setup
# changes. The script is kept in DIR for the next run (and the next build:
# make deps fetches it, tests/integration/test_import_parity.sh runs it);
# the rest is removed. It needs the network, so bench/run.sh calls it
# before it leaves the network behind (unshare -n).
set -eu
src=$(cd "$(dirname "$0")/.." && pwd)
. "$src/tools/usage.sh"
case ${1:-} in
-h|--help) mpb_usage; exit 0 ;;
-*) echo "bench/ompl_peer.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
esac
DIR=${1:-$src/.cache/ompl-peer}

fail() { echo "bench/ompl_peer.sh: $*" >&2; exit 1; }

version=$(dpkg-query -W -f='${source:Version}' libompl-dev 2>/dev/null) ||
    fail "libompl-dev is not installed (make deps)"
out=$DIR/ompl-$version/ompl_benchmark_statistics.py
[ -s "$out" ] && { echo "$out"; exit 0; }

apt_dir=$DIR/apt
rm -rf "$apt_dir" && mkdir -p "$apt_dir/lists/partial" \
    "$apt_dir/cache/archives/partial" "$apt_dir/source" "$apt_dir/sources" ||
    fail "cannot write $DIR"
trap 'rm -rf "$apt_dir"' EXIT
# The machine's own sources, as apt reads them (its mirrors, proxies and
# keys), each "deb" entry turned into "deb-src" of the same archive: no
# host is written here. One-line files and deb822 files alike.
etc=$(apt-config shell E Dir::Etc/d | sed "s/^E='\(.*\)'$/\1/")
etc=${etc:-/etc/apt/}
n=0
for f in "$etc/sources.list" "$etc"/sources.list.d/*.list; do
    [ -f "$f" ] || continue
    n=$((n + 1))
    sed -n 's/^[[:space:]]*deb[[:space:]]/deb-src /p' "$f" \
        >"$apt_dir/sources/$n.list"
done
for f in "$etc"/sources.list.d/*.sources; do
    [ -f "$f" ] || continue
    n=$((n + 1))
    awk 'tolower($1) == "types:" {
             deb = 0
             for (i = 2; i <= NF; i++) if ($i == "deb") deb = 1
             print deb ? "Types: deb-src" : $0; next }
         { print }' "$f" >"$apt_dir/sources/$n.sources"
done
[ "$n" -gt 0 ] || fail "no apt sources in $etc (sources.list, sources.list.d)"
apt() {
    apt-get -qq -o Dir::Etc::SourceList=/dev/null \
        -o Dir::Etc::SourceParts="$apt_dir/sources" \
        -o Dir::State::Lists="$apt_dir/lists" \
        -o Dir::Cache="$apt_dir/cache" -o Debug::NoLocking=1 \
        -o APT::Sandbox::User=root "$@"
}
# apt's first complaint, for the one line of a failure (the log goes).
why() { grep -m1 '^[EW]:' "$apt_dir/log" | cut -c1-200; }
# A source of the machine that serves no source index (a third party's
# archive) fails the update but not what follows: apt source says whether
# the package was found.
apt update >"$apt_dir/log" 2>&1 || :
(cd "$apt_dir/source" && apt source --download-only "ompl=$version") \
    >>"$apt_dir/log" 2>&1 || fail "apt-get source ompl=$version failed: $(why)"
mkdir -p "$(dirname "$out")"
tar -xJf "$apt_dir"/source/ompl_*.orig.tar.xz --wildcards -O \
    '*/scripts/ompl_benchmark_statistics.py' >"$out.part" 2>/dev/null &&
    [ -s "$out.part" ] || { rm -f "$out.part"; fail "no scripts/ompl_benchmark_statistics.py in OMPL $version's sources"; }
mv "$out.part" "$out"
echo "$out"
