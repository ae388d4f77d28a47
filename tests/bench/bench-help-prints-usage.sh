#!/bin/sh
# A benchmark given --help printed no usage and ran (boneless-bench-c3d wrote 100 MB and read it
# three times). Each must print its usage and exit 0 without running, and refuse an argument it
# does not know, exit 1 or more, without running.
# Usage: bench-help-prints-usage.sh BENCH...
fail=0
for bench in "$@"; do
    out=$("$bench" --help 2>&1)
    code=$?
    if [ $code -ne 0 ] || ! printf '%s' "$out" | grep -q "Usage" ||
        printf '%s' "$out" | grep -qE "PASS|FAIL"; then
        echo "FAIL $bench --help: exit $code:"
        echo "$out"
        fail=1
    fi
    out=$("$bench" --no-such-option 2>&1)
    code=$?
    if [ $code -eq 0 ] || printf '%s' "$out" | grep -qE "PASS|FAIL"; then
        echo "FAIL $bench --no-such-option: exit $code:"
        echo "$out"
        fail=1
    fi
done
exit $fail
