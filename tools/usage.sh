# usage.sh - sourced by the project's scripts for their command line: a
# script's --help is its header comment, so the two never disagree.

# mpb_usage: print the running script's header comment (its lines from the
# second to the first that is not a comment), without the leading '# '.
mpb_usage() {
    sed -n '2,${/^#/!q;s/^# \{0,1\}//;p;}' "$0"
}

# mpb_no_options ARG...: for a script that takes no options, only words:
# -h or --help prints the usage and exits 0; any other word starting with
# '-' is refused in one line (exit 2).
mpb_no_options() {
    for arg in "$@"; do
        case $arg in
        -h|--help) mpb_usage; exit 0 ;;
        -*) echo "$(basename "$0"): unknown option '$arg' (see --help)" >&2
            exit 2 ;;
        esac
    done
}

# mpb_no_arguments ARG...: for a script that takes nothing: as
# mpb_no_options, and any word at all is refused.
mpb_no_arguments() {
    mpb_no_options "$@"
    [ $# -eq 0 ] || {
        echo "$(basename "$0"): takes no arguments, not '$1' (see --help)" >&2
        exit 2
    }
}
