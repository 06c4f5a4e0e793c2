#!/bin/sh
# error_bench.sh: how well every render's own error estimate (est_relmse, --stats) matches its
# true relative MSE, for every sampler, at 16, 64 and 256 spp, on every scene in scenes/ (issue
# 14). Not a test: a benchmark for the README and the notes (make bench-error). Each scene's film
# is shrunk by $SHRINK (default 4) in both directions; its reference is a sobol render of $REF_SPP
# (default 4096) spp with seed 9999, whose own estimated relMSE is subtracted from each render's
# relMSE against it (the errors are independent, so their mean squares add). Each cell is the
# mean over $SEEDS seeds (default 2) of the estimated and of the true relMSE: est/true then
# estimates E[est]/E[true], which is 1 for an unbiased estimate. Writes one line per scene,
# sampler and spp, then the median ratio per sampler and spp. $MCRT is the binary (default
# build/mcrt); $SCENES the scene files (default scenes/*.mcrt); $SPPS the ladder. With $BASE set
# to another mcrt binary (e.g. an earlier commit's), each cell also renders with it, with the
# same seeds and reference, and two more columns give its true relMSE and the ratio of this
# binary's to it: the cost of a change to the samplers in error at equal spp, side by side.
MCRT=${MCRT:-build/mcrt}
SHRINK=${SHRINK:-4}
REF_SPP=${REF_SPP:-4096}
SEEDS=${SEEDS:-2}
SPPS=${SPPS:-16 64 256}
SAMPLERS=${SAMPLERS:-random stratified sobol}
tmp=$(mktemp -d) || exit 2
trap 'rm -rf "$tmp"' EXIT
cp scenes/*.obj scenes/*.mtl scenes/*.exr scenes/*-glaze.png "$tmp"/ 2>/dev/null # what the scenes read
. tests/outputs.sh.inc

printf '%-16s %-10s %5s %11s %11s %6s%s\n' scene sampler spp est_relmse true_relmse ratio \
    "${BASE:+  base_relmse  new/base}"
for scene in ${SCENES:-scenes/*.mcrt}; do
    name=$(basename "$scene" .mcrt)
    s="$tmp/$name.mcrt"
    film_shrink "$scene" "$SHRINK" >"$s"
    "$MCRT" --quiet --sampler sobol --spp "$REF_SPP" --seed 9999 -o "$tmp/ref.pfm" \
        --stats "$tmp/ref.json" "$s" || { echo "$name: the reference did not render" >&2; continue; }
    ref_est=$(json_num "$tmp/ref.json" est_relmse)
    for sampler in $SAMPLERS; do
        for spp in $SPPS; do
            sum_est=0 sum_true=0 sum_base=0 k=1
            while [ "$k" -le "$SEEDS" ]; do
                if [ -n "$BASE" ]; then
                    "$BASE" --quiet --sampler "$sampler" --spp "$spp" --seed "$k" \
                        -o "$tmp/b.pfm" "$s" || exit 1
                    sum_base=$(echo "$sum_base $(diff_num relMSE "$tmp/b.pfm" "$tmp/ref.pfm") $ref_est" |
                        awk '{ print $1 + $2 - $3 }')
                fi
                "$MCRT" --quiet --sampler "$sampler" --spp "$spp" --seed "$k" -o "$tmp/t.pfm" \
                    --stats "$tmp/t.json" "$s" || exit 1
                sum_est=$(echo "$sum_est $(json_num "$tmp/t.json" est_relmse)" | awk '{ print $1 + $2 }')
                sum_true=$(echo "$sum_true $(diff_num relMSE "$tmp/t.pfm" "$tmp/ref.pfm") $ref_est" |
                    awk '{ print $1 + $2 - $3 }')
                k=$((k + 1))
            done
            echo "$name $sampler $spp $sum_est $sum_true $SEEDS $sum_base" | awk '{
                printf "%-16s %-10s %5d %11.4e %11.4e %6.3f", $1, $2, $3, $4 / $6, $5 / $6, $4 / $5
                if ($7 > 0) printf "  %11.4e  %8.3f", $7 / $6, $5 / $7
                printf "\n" }'
        done
    done
done | tee "$tmp/table"
# median COLUMN TITLE: the median of a column per sampler and spp.
median() {
    echo
    echo "$2 over the scenes:"
    for sampler in $SAMPLERS; do
        for spp in $SPPS; do
            awk -v s="$sampler" -v n="$spp" -v k="$1" '$2 == s && $3 == n { print $k }' "$tmp/table" | sort -g |
                awk -v s="$sampler" -v n="$spp" '{ v[NR] = $1 } END {
                    m = NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2
                    printf "  %-10s %5d spp: %.3f (range %.3f to %.3f, %d scenes)\n", s, n, m, v[1], v[NR], NR }'
        done
    done
}
median 6 "median est/true"
[ -z "$BASE" ] || median 8 "median relMSE of this binary over the base's"
