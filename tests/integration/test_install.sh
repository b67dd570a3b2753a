#!/bin/sh
# make install: what `cmake --install` (which `make install` runs) puts in a
# prefix is complete and usable from outside the tree. A small C program
# builds against the installed libmpbench with pkg-config (shared, and
# static with --static) and with find_package(mpbench) (mpbench::mpbench,
# mpbench::mpbench_static), then writes and reads a database; every
# installed program answers --help (exit 0) and an unknown option (one
# line, exit 2); every program has a man page that renders without
# warnings and names each option its --help names.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
# No LCM here; a private namespace all the same, should a program start it.
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix

# ---- the install itself -----------------------------------------------------
cmake --install "$MPB_BUILD" --prefix "$prefix" >"$work/install.log" 2>&1
check "cmake --install into a fresh prefix exits 0" eq $? 0
pc=$(find "$prefix" -name libmpbench.pc)
libdir=$(dirname "$(dirname "$pc")")
echo "# libdir: $libdir"
for f in bin/mpbenchd bin/mpb bin/mpb-planner-null bin/mpb-planner-ompl \
         bin/mpb-planner-python share/mpbench/python/mpbplanner/node.py \
         share/mpbench/python/mpb/plan_result_t.py \
         include/mpbench/mpbench.h include/mpbench/planner.h \
         include/mpbench/lcmtypes/mpb_plan_request_t.h \
         include/mpbench/lcmtypes/mpb/plan_request_t.hpp \
         share/mpbench/mpb_types.jar share/mpbench/lcmtypes/daemon_status_t.lcm \
         share/man/man1/mpbenchd.1 share/man/man3/libmpbench.3; do
    check "installs $f" test -s "$prefix/$f"
done
for f in libmpbench.so.0 libmpbench.a pkgconfig/libmpbench.pc \
         cmake/mpbench/mpbenchConfig.cmake cmake/mpbench/mpbenchConfigVersion.cmake; do
    check "installs ${libdir#"$prefix"/}/$f" test -s "$libdir/$f"
done
check "libmpbench.pc names the prefix of the install" \
    grep -qx "prefix=$prefix" "$pc"

DESTDIR=$work/stage cmake --install "$MPB_BUILD" --prefix /opt/mpbench \
    >/dev/null 2>&1
check "with DESTDIR, everything lands under DESTDIR/PREFIX" \
    sh -c "[ \"\$(ls '$work/stage')\" = opt ] && [ \"\$(ls '$work/stage/opt')\" = mpbench ] &&
           test -x '$work/stage/opt/mpbench/bin/mpbenchd'"
check "... and libmpbench.pc names PREFIX, not the staging directory" \
    sh -c "grep -qx 'prefix=/opt/mpbench' \"\$(find '$work/stage' -name libmpbench.pc)\""
make -n -C "$MPB_SOURCE" install BUILD="$MPB_BUILD" PREFIX=/p DESTDIR=/d \
    >"$work/make.out" 2>&1
check "make install PREFIX=... DESTDIR=... runs cmake --install with both" \
    grep -q "^DESTDIR=\"/d\" cmake --install $MPB_BUILD --prefix /p\$" "$work/make.out"

# ---- a program outside the tree ---------------------------------------------
mkdir -p "$work/outside"
cat >"$work/outside/outside.c" <<'EOT'
/* Writes an experiment into a new database, reads it back, names errors. */
#include <stdio.h>
#include <mpbench/mpbench.h>
#include <mpbench/planner.h>   /* includes the generated message headers */

static int print_experiment(void *ud, const mpb_experiment_row *row)
{
    (void)ud;
    printf("read: %s, %d runs per query, %.1f s\n", row->name,
           row->runs_per_query, row->time_limit);
    return 0;
}

int main(int argc, char **argv)
{
    mpb_store *s = NULL;
    int64_t id = 0;
    mpb_experiment_info info = {.name = argv[2], .config_file = "x.yaml",
        .config_hash = "00", .config_text = "", .runs_per_query = 7,
        .time_limit = 2.5};
    if (argc != 3)
        return 2;
    if (mpb_store_open(argv[1], 0, &s) != MPB_OK ||
        mpb_store_experiment_create(s, &info, &id) != MPB_OK) {
        printf("write failed: %s\n", mpb_store_errmsg(s));
        return 1;
    }
    mpb_store_close(s);
    s = NULL;
    if (mpb_store_open(argv[1], 1, &s) != MPB_OK ||
        mpb_store_experiments(s, print_experiment, NULL) != MPB_OK)
        return 1;
    printf("missing: %s (%s)\n", mpb_strerror(mpb_store_experiment_get(
               s, id + 1, print_experiment, NULL)),
           mpb_err_name(MPB_ENOTFOUND));
    mpb_store_close(s);
    /* A generated message type, through the installed headers. */
    char run_id[] = "run-1", sender[] = "outside", buf[256];
    mpb_run_ack_t ack = {.attempt_id = run_id, .sender_id = sender,
                         .kind = MPB_RUN_ACK_T_RESULT_STORED}, back;
    int n = mpb_run_ack_t_encode(buf, 0, sizeof buf, &ack);
    if (n <= 0 || mpb_run_ack_t_decode(buf, 0, n, &back) != n)
        return 1;
    printf("version %s, status on %s, ack %s from %s\n", MPB_VERSION_STRING,
           MPB_CHANNEL_STATUS, back.attempt_id, back.sender_id);
    mpb_run_ack_t_decode_cleanup(&back);
    return 0;
}
EOT
# expected NAME: what outside.c prints, into $work/NAME.expected.
expected() {
    printf '%s\n' "read: $1, 7 runs per query, 2.5 s" \
        "missing: not found (MPB_ENOTFOUND)" \
        "version $version, status on MPB_STATUS, ack run-1 from outside" \
        >"$work/$1.expected"
}
version=$(sed -n 's/^project(mpbench VERSION \([0-9.]*\).*/\1/p' "$MPB_SOURCE/CMakeLists.txt")

export PKG_CONFIG_PATH="$libdir/pkgconfig"
# A sanitizer build installs a sanitized library: its users link the
# sanitizers' runtimes too.
san=""
if grep -q '^MPB_SANITIZE:BOOL=ON' "$MPB_BUILD/CMakeCache.txt"; then
    san="-fsanitize=address,undefined"
fi
cd "$work/outside" || exit 1
# shellcheck disable=SC2046
cc -std=c11 -Wall -Wextra -Werror $san -o outside_pc outside.c \
    $(pkg-config --cflags --libs libmpbench) 2>"$work/cc.err"
check "pkg-config --cflags --libs libmpbench builds a C program" eq $? 0
cat "$work/cc.err"
LD_LIBRARY_PATH=$libdir ./outside_pc "$work/pc.db" with_pkg_config >"$work/pc.out" 2>&1
check "... that runs" eq $? 0
expected with_pkg_config
check "... writing and reading a database through the installed library" \
    cmp -s "$work/with_pkg_config.expected" "$work/pc.out"
check "... loading the installed libmpbench.so" \
    sh -c "LD_LIBRARY_PATH='$libdir' ldd ./outside_pc | grep -q 'libmpbench.so.0 => $libdir/libmpbench.so.0'"

# shellcheck disable=SC2046
cc -std=c11 -Wall -Wextra -Werror $san -o outside_static outside.c \
    $(pkg-config --cflags libmpbench) \
    $(pkg-config --static --libs libmpbench | sed 's/-lmpbench/-l:libmpbench.a/') \
    2>"$work/cc_static.err"
check "pkg-config --static links the static library" eq $? 0
cat "$work/cc_static.err"
./outside_static "$work/static.db" statically >"$work/static.out" 2>&1
expected statically
check "... which runs, with the same output" \
    cmp -s "$work/statically.expected" "$work/static.out"
check "... without libmpbench.so" sh -c "! ldd ./outside_static | grep -q libmpbench"

mkdir -p "$work/cmake"
cat >"$work/cmake/CMakeLists.txt" <<'EOT'
cmake_minimum_required(VERSION 3.16)
project(outside LANGUAGES C CXX)
find_package(mpbench 0.1 REQUIRED)
add_executable(outside_cmake outside.c)
target_link_libraries(outside_cmake PRIVATE mpbench::mpbench)
add_executable(outside_cmake_static outside.c)
target_link_libraries(outside_cmake_static PRIVATE mpbench::mpbench_static)
EOT
cp outside.c "$work/cmake/"
cmake -S "$work/cmake" -B "$work/cmake/build" -DCMAKE_PREFIX_PATH="$prefix" \
    -DCMAKE_C_FLAGS="$san" -DCMAKE_CXX_FLAGS="$san" -DCMAKE_EXE_LINKER_FLAGS="$san" \
    >"$work/cmake.log" 2>&1 &&
    cmake --build "$work/cmake/build" >>"$work/cmake.log" 2>&1
status=$?
check "find_package(mpbench) builds the program (shared and static)" eq $status 0
[ $status -eq 0 ] || cat "$work/cmake.log"
LD_LIBRARY_PATH=$libdir "$work/cmake/build/outside_cmake" "$work/cm.db" with_cmake \
    >"$work/cm.out" 2>&1
expected with_cmake
check "... mpbench::mpbench runs, with the expected output" \
    cmp -s "$work/with_cmake.expected" "$work/cm.out"
"$work/cmake/build/outside_cmake_static" "$work/cms.db" cmake_static >"$work/cms.out" 2>&1
expected cmake_static
check "... mpbench::mpbench_static too" \
    cmp -s "$work/cmake_static.expected" "$work/cms.out"
cat >"$work/cmake/CMakeLists.txt" <<'EOT'
cmake_minimum_required(VERSION 3.16)
project(outside LANGUAGES C)
find_package(mpbench 9.0)
if(mpbench_FOUND)
  message(FATAL_ERROR "found mpbench 9.0")
endif()
EOT
cmake -S "$work/cmake" -B "$work/cmake/build9" -DCMAKE_PREFIX_PATH="$prefix" \
    >"$work/cmake9.log" 2>&1
check "find_package(mpbench 9.0) does not take 0.1" eq $? 0
cd "$work" || exit 1

# ---- every program: --help, a bad option, a man page -----------------------
bin=$prefix/bin
"$bin/mpb" spy --print-command >"$work/spy.out"
check "the installed mpb spy finds the installed mpb_types.jar" \
    grep -q ":$prefix/share/mpbench/mpb_types.jar lcm.spy.Spy " "$work/spy.out"

# The mpb subcommands, as its own --help lists them.
commands=$("$bin/mpb" --help | sed -n '/^Commands:/,/^$/s/^  \([a-z-]*\) .*/\1/p')
echo "# mpb commands:" $commands
check "mpb lists its commands" test -n "$commands"
programs="mpbenchd mpb"
for c in $commands; do programs="$programs mpb:$c"; done
for p in "$bin"/mpb-planner-*; do programs="$programs $(basename "$p")"; done
for prog in $programs; do
    cmdline=$(echo "$prog" | tr ':' ' ')
    # shellcheck disable=SC2086
    (cd "$bin" && ./$cmdline --help) >"$work/help.out" 2>"$work/help.err"
    status=$?
    check "$cmdline --help exits 0" eq $status 0
    check "... printing the usage" grep -q '^usage: ' "$work/help.out"
    # shellcheck disable=SC2086
    (cd "$bin" && ./$cmdline --no-such-option) >"$work/bad.out" 2>"$work/bad.err"
    status=$?
    check "$cmdline --no-such-option exits 2" eq $status 2
    check "... with one line, on stderr" \
        sh -c "[ \$(wc -l <'$work/bad.err') -eq 1 ] && [ ! -s '$work/bad.out' ]"
    # The man page: the program's own (mpb's covers its commands).
    page=$prefix/share/man/man1/${prog%%:*}.1
    check "${prog%%:*} has a man page" test -s "$page"
    LC_ALL=C MANWIDTH=1000 man -l "$page" 2>/dev/null >"$work/page.txt"
    for opt in $(grep -o -- '--[a-z][a-z-]*' "$work/help.out" | sort -u); do
        check "... which names $opt ($cmdline)" grep -q -- "$opt" "$work/page.txt"
    done
done

# (lib.sh's check() uses $name: the page is $manpage.)
for page in "$MPB_SOURCE"/man/*.[1-9]; do
    manpage=$(basename "$page")
    groff -man -ww -z "$page" >"$work/groff.err" 2>&1
    check "$manpage: groff -ww finds nothing to warn about" test ! -s "$work/groff.err"
    LC_ALL=C MANWIDTH=80 man --warnings -l "$page" 2>"$work/man.err" >"$work/man.out"
    check "$manpage: man --warnings renders it, silently" \
        sh -c "[ -s '$work/man.out' ] && [ ! -s '$work/man.err' ]"
    title=$(echo "${manpage%.*}" | tr '[:lower:]' '[:upper:]')
    check "$manpage: its title is its name" \
        grep -q "^$title(${manpage##*.})" "$work/man.out"
    check "$manpage: is installed" test -s "$prefix/share/man/man${manpage##*.}/$manpage"
done

mpb_finish
