#!/bin/sh
# Runs every test program ($O/tests/test_*) and script (tests/*.sh), $JOBS at a time (default:
# the number of cores); they are independent, each with its own scratch folder. Each ends with a
# line "N passed, N failed" or "N passed, N failed, N skipped"; a program that crashes or prints
# no such line counts as one failure. The report is in the order of the names, whatever order the
# programs finish in: for each, its FAIL and note lines, then "NAME: N passed, N failed (Ts)".
# Last come the skipped checks, each named with its reason, and the grand total
# "N passed, N failed, N skipped"; exits 1 if anything failed.
#
#   sh tests/run.sh --one TEST DIR   (internal) runs TEST into DIR/NAME.log, then DIR/NAME.done
O=${O:-build}
export O

if [ "$1" = --one ]; then
    name=$(basename "$2")
    start=$(date +%s)
    case "$2" in
        *.sh) sh "$2" >"$3/$name.log" 2>&1 ;;
        *) "$2" >"$3/$name.log" 2>&1 ;;
    esac
    status=$?
    # Written last, and renamed into place, so that the report never reads a half-written log.
    echo "$status $(($(date +%s) - start))" >"$3/$name.tmp" && mv "$3/$name.tmp" "$3/$name.done"
    exit 0
fi

jobs=${JOBS:-$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 1)}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
for t in "$O"/tests/test_* tests/*.sh; do
    [ -f "$t" ] || continue
    case "$t" in tests/run.sh|*.d) continue ;; esac
    echo "$t"
done >"$dir/list"

# The slowest start first (by the times of the last run, kept in $O/tests/times; a program not
# timed yet counts as slow), so that no long one starts last and runs alone at the end.
times=$O/tests/times
mkdir -p "$O/tests" && [ -f "$times" ] || : >"$times"
awk 'FILENAME == ARGV[1] { t[$2] = $1; next }
     { n = $0; sub(/.*\//, "", n); print (n in t ? t[n] : 999999), $0 }' "$times" "$dir/list" |
    sort -k1,1rn -k2 | cut -d ' ' -f 2- >"$dir/order"
xargs -P "$jobs" -I '{}' sh "$0" --one '{}' "$dir" <"$dir/order" &
pool=$!

passed=0
failed=0
skipped=0
: >"$dir/skips"
while IFS= read -r t; do
    name=$(basename "$t")
    while [ ! -f "$dir/$name.done" ]; do
        if ! kill -0 "$pool" 2>/dev/null && [ ! -f "$dir/$name.done" ]; then
            echo "0 0" >"$dir/$name.done" # the pool ended without running it (killed)
            echo "FAIL $name: never ran" >"$dir/$name.log"
        fi
        sleep 1
    done
    read -r status secs <"$dir/$name.done"
    log=$dir/$name.log
    last=$(grep -E '^[0-9]+ passed, [0-9]+ failed(, [0-9]+ skipped)?$' "$log" | tail -n 1)
    if [ -z "$last" ]; then
        p=0 f=1 s=0
        echo "FAIL $name: exit $status without a result line"
        tail -n 20 "$log"
    else
        p=${last%% passed*}
        f=${last#*, }; f=${f%% failed*}
        case "$last" in *skipped) s=${last##*, }; s=${s%% skipped} ;; *) s=0 ;; esac
        if [ "$status" -ne 0 ] && [ "$f" -eq 0 ]; then f=1; fi
        grep -E '^(FAIL|  note:)' "$log"
        grep -E '^skip ' "$log" | sed "s/^skip /  $name: /" >>"$dir/skips"
    fi
    if [ "$s" -gt 0 ]; then
        echo "$name: $p passed, $f failed, $s skipped (${secs}s)"
    else
        echo "$name: $p passed, $f failed (${secs}s)"
    fi
    echo "$secs $name" >>"$dir/times"
    passed=$((passed + p))
    failed=$((failed + f))
    skipped=$((skipped + s))
done <"$dir/list"
wait "$pool"
mv "$dir/times" "$times"

if [ -s "$dir/skips" ]; then
    echo "skipped (not failures: this machine lacks what they need):"
    cat "$dir/skips"
fi
echo "$passed passed, $failed failed, $skipped skipped"
[ "$failed" -eq 0 ]
