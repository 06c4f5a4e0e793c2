#!/bin/sh
# stiff.sh: the NaN guard of issue 6. Renders every scene in scenes/ and tests/stiff/ at 2 spp
# with 2 threads, with the code built for the scene's features and with --all-features (the
# general path), and asserts, from --stats, that no sample was NaN or infinite (the renderer counts
# such samples and never adds them; a nonzero count is a bug in some shared mechanism). Run from
# the repository root after the build; $O is the build folder. Prints "ok ..." or "FAIL ...: why"
# per scene, then "N passed, N failed"; exits 1 if any failed.
. tests/harness.sh.inc
for scene in scenes/*.mcrt tests/stiff/*.mcrt; do
for mode in built all; do
    flag=
    [ "$mode" = all ] && flag=--all-features
    "$MCRT" "$scene" $flag --spp 2 --threads 2 --quiet -o "$tmp/out.pfm" --stats "$tmp/stats.json" \
        2>"$tmp/err"
    rc=$?
    if [ "$rc" -ne 0 ]; then
        echo "FAIL $scene ($mode): exit status $rc: $(head -n 1 "$tmp/err")"
        failed=$((failed + 1))
        continue
    fi
    nans=$(sed -n 's/.*"nan_count": *\([0-9]*\).*/\1/p' "$tmp/stats.json")
    if [ "$nans" = 0 ]; then
        echo "ok $scene ($mode)"
        passed=$((passed + 1))
    else
        echo "FAIL $scene ($mode): nan_count ${nans:-missing}"
        failed=$((failed + 1))
    fi
done
done
finish
