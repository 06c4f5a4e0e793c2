#!/bin/sh
# predict_bench.sh: does a render's prediction of the time to a target error come true (issue
# 14)? For each scene (films shrunk by $SHRINK, default 2), a progressive render of passes of 4
# spp for $FIRST seconds (default 4) gives est_relmse, seconds and relmse_slope (--stats); its
# prediction for a target 4 times lower, seconds·(target/est)^(1/slope), is then compared with
# the seconds a --target-error render of that target takes (passes of 4 spp, another seed). Not
# a test (it times renders): a benchmark for the README and the notes (make bench-error).
MCRT=${MCRT:-build/mcrt}
SHRINK=${SHRINK:-2}
FIRST=${FIRST:-4}
tmp=$(mktemp -d) || exit 2
trap 'rm -rf "$tmp"' EXIT
cp scenes/*.obj scenes/*.mtl scenes/*.exr scenes/*-glaze.png "$tmp"/ 2>/dev/null # what the scenes read
. tests/outputs.sh.inc

printf '%-14s %10s %8s %7s %10s %10s %10s %6s\n' scene est seconds slope target predicted \
    measured ratio
for scene in ${SCENES:-scenes/soft-shadows.mcrt scenes/cornell.mcrt scenes/glossy.mcrt}; do
    name=$(basename "$scene" .mcrt)
    s="$tmp/$name.mcrt"
    film_shrink "$scene" "$SHRINK" >"$s"
    "$MCRT" --quiet --spp 4 --time "$FIRST" --seed 1 -o "$tmp/a.pfm" \
        --stats "$tmp/a.json" "$s" || exit 1
    est=$(json_num "$tmp/a.json" est_relmse)
    secs=$(json_num "$tmp/a.json" seconds)
    slope=$(json_num "$tmp/a.json" relmse_slope)
    target=$(echo "$est" | awk '{ printf "%.4g", $1 / 4 }')
    pred=$(echo "$secs $target $est $slope" | awk '{ printf "%.3f", $1 * ($2 / $3) ^ (1 / $4) }')
    "$MCRT" --quiet --spp 4 --target-error "$target" --seed 2 -o "$tmp/b.pfm" \
        --stats "$tmp/b.json" "$s" || exit 1
    took=$(json_num "$tmp/b.json" seconds)
    printf '%-14s %10.4g %8.2f %7.3f %10s %10s %10.2f %6.2f\n' "$name" "$est" "$secs" "$slope" \
        "$target" "$pred" "$took" "$(echo "$took $pred" | awk '{ print $1 / $2 }')"
done
