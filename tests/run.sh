#!/bin/sh
# Runs every test program (build/tests/test_*) and script (tests/*.sh); each ends with a line
# "N passed, N failed". A program that crashes or prints no such line counts as one failure.
# Prints the grand total last and exits 1 if anything failed.
O=${O:-build}
export O
passed=0
failed=0
log=$(mktemp)
trap 'rm -f "$log"' EXIT
for t in "$O"/tests/test_* tests/*.sh; do
    [ -f "$t" ] || continue
    case "$t" in tests/run.sh|*.d) continue ;; esac
    name=$(basename "$t")
    start=$(date +%s)
    case "$t" in
        *.sh) sh "$t" >"$log" 2>&1 ;;
        *) "$t" >"$log" 2>&1 ;;
    esac
    status=$?
    secs=$(( $(date +%s) - start ))
    last=$(grep -E '^[0-9]+ passed, [0-9]+ failed$' "$log" | tail -n 1)
    if [ -z "$last" ]; then
        p=0; f=1
        echo "FAIL $name: exit $status without a result line"
        tail -n 20 "$log"
    else
        p=${last%% passed*}
        f=${last#*, }; f=${f%% failed*}
        if [ "$status" -ne 0 ] && [ "$f" -eq 0 ]; then f=1; fi
        grep -E '^(FAIL|  note:)' "$log"
    fi
    echo "$name: $p passed, $f failed (${secs}s)"
    passed=$((passed + p))
    failed=$((failed + f))
done
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
