# TAP helpers for the shell tests (sourced).  Each check prints "ok N - name"
# or "not ok N - name"; finish prints the plan.
tap_n=0
tap_failed=0
TMPD=$(mktemp -d "${TMPDIR:-/tmp}/mimas-cli-XXXXXX")
trap 'rm -rf "$TMPD"' EXIT

ok() {
    tap_n=$((tap_n + 1))
    echo "ok $tap_n - $1"
}
not_ok() {
    tap_n=$((tap_n + 1))
    tap_failed=$((tap_failed + 1))
    echo "not ok $tap_n - $1"
    shift
    for line in "$@"; do echo "# $line"; done
}
# check NAME COMMAND...: passes when the command succeeds
check() {
    name=$1
    shift
    if "$@" >"$TMPD/out" 2>"$TMPD/err"; then ok "$name"; else
        not_ok "$name" "command: $*" "stderr: $(head -c 400 "$TMPD/err")"
    fi
}
# expect_fail NAME STATUS PATTERN COMMAND...: the command exits with STATUS,
# prints exactly one line on stderr matching PATTERN, nothing on stdout
expect_fail() {
    name=$1 status=$2 pattern=$3
    shift 3
    "$@" >"$TMPD/out" 2>"$TMPD/err"
    got=$?
    lines=$(wc -l <"$TMPD/err")
    if [ "$got" -eq "$status" ] && [ "$lines" -eq 1 ] && grep -q -- "$pattern" "$TMPD/err" &&
        [ ! -s "$TMPD/out" ]; then
        ok "$name"
    else
        not_ok "$name" "command: $*" "exit $got (want $status), $lines stderr lines" \
            "stderr: $(head -c 400 "$TMPD/err")"
    fi
}
finish() {
    echo "1..$tap_n"
    [ "$tap_failed" -eq 0 ]
}
