#!/bin/sh
# progressive.sh: --time, --target-error and Ctrl-C as a user meets them: the summary names the
# passes; a first SIGINT writes the image of the complete passes and exits 130; a second quits
# at once (130) and leaves the output alone. Run from the repository root after the build; $O is
# the build folder. Prints "ok ..." or "FAIL ...: why" per check, then "N passed, N failed"; exits
# 1 if any failed.
. tests/harness.sh.inc

printf 'film { width 64 height 48 spp 1 }\ncamera { eye 0 3 6  look 0 0.5 0  fov 40 }\n%s\n%s\n%s\n' \
    'quad { corner -4 0 4  edge1 8 0 0  edge2 0 0 -8 }' 'sphere { center 0 0.7 0  radius 0.7 }' \
    'quad { corner -0.5 3 -0.5  edge1 1 0 0  edge2 0 0 1  emit 20 }' >"$tmp/s.mcrt"

"$MCRT" --time 0.5 -o "$tmp/t.pfm" "$tmp/s.mcrt" 2>"$tmp/err"
rc=$?
if [ "$rc" -eq 0 ] && grep -qE '^.*t\.pfm: 64x48, [0-9]+ spp, .*, [0-9]+ passes$' "$tmp/err"; then
    ok "--time 0.5: $(grep -oE '[0-9]+ passes' "$tmp/err")"
else
    fail "--time" "exit $rc: $(cat "$tmp/err")"
fi
"$MCRT" --target-error 0.02 -o "$tmp/e.pfm" "$tmp/s.mcrt" 2>"$tmp/err"
rc=$?
est=$(sed -n 's/.*est\. relMSE \([^,]*\),.*/\1/p' "$tmp/err")
if [ "$rc" -eq 0 ] && echo "$est" | awk '{ exit !($1 <= 0.02) }'; then
    ok "--target-error 0.02: est. relMSE $est, $(grep -oE '[0-9]+ pass(es)?$' "$tmp/err")"
else
    fail "--target-error" "exit $rc: $(cat "$tmp/err")"
fi

# A render that would run a minute, interrupted after a second.
"$MCRT" --time 60 -o "$tmp/i.pfm" "$tmp/s.mcrt" 2>"$tmp/err" &
pid=$!
sleep 1
kill -INT $pid
wait $pid
rc=$?
if [ "$rc" -eq 130 ] && [ -s "$tmp/i.pfm" ] &&
    grep -qE '^mcrt: interrupted; wrote .*i\.pfm with the [0-9]+ complete pass(es)? \([0-9]+ spp\)$' "$tmp/err"; then
    ok "Ctrl-C: exit 130, $(grep -oE '[0-9]+ complete pass(es)?' "$tmp/err") written"
else
    fail "Ctrl-C" "exit $rc: $(cat "$tmp/err")"
fi

# One 16x16 tile of 10^6 samples per pixel: a pass of minutes that checks for cancelling only
# between tiles, so the first Ctrl-C cannot stop it soon; the second must end mcrt at once.
printf 'film { width 16 height 16 spp 1000000 }\nsphere { }\nenvironment { radiance 1 }\n' \
    >"$tmp/slow.mcrt"
echo old >"$tmp/keep.pfm"
"$MCRT" --time 600 -o "$tmp/keep.pfm" "$tmp/slow.mcrt" 2>"$tmp/err" &
pid=$!
sleep 1
kill -INT $pid
sleep 0.5
kill -INT $pid 2>/dev/null
sleep 0.5
if kill -0 $pid 2>/dev/null; then
    kill -KILL $pid
    fail "two Ctrl-C" "mcrt still running 0.5 s after the second Ctrl-C"
else
    wait $pid
    rc=$?
    if [ "$rc" -eq 130 ] && [ "$(cat "$tmp/keep.pfm")" = old ]; then
        ok "two Ctrl-C: exit 130 at once, the output untouched"
    else
        fail "two Ctrl-C" "exit $rc, output: $(head -c 20 "$tmp/keep.pfm"): $(cat "$tmp/err")"
    fi
fi

finish
