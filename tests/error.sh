#!/bin/sh
# error.sh: every render's own error estimate against the truth (issues 5 and 14). For three
# scenes of scenes/ (films overridden to 128x96 and 64x48), a 1024 spp sobol render of another seed is the
# reference; its own error is known (its est_relmse) and subtracted from each render's relMSE
# against it (the two renders are independent, so their errors' mean squares add).
#   - For every sampler, the est_relmse of 64 spp renders (--stats) agrees with their true
#     relMSE within [0.8, 1.25] (issue 14's target), as means over 2 seeds; with --adaptive
#     within [0.7, 1.25] on the two scenes without fireflies.
#   - On the soft-shadow scene, the random sampler's relMSE falls as spp^-1 (log-log slope -1 +-
#     0.15 from 16 to 64 spp).
#   - --target-error E with the default sampler stops with a true relMSE within a factor 1.3 of E
#     on the three scenes.
# Also `mcrt converge` writes its CSV and plot. Run from the repository root after the build; $O
# is the build folder. Prints "ok ..." or "FAIL ...: why" per check, then "N passed, N failed";
# exits 1 if any failed.
. tests/harness.sh.inc

cp scenes/*.obj "$tmp"/ 2>/dev/null
. tests/outputs.sh.inc

# true_relmse SCENE OPTIONS...: render SCENE (seed 1) and print "EST TRUE": its estimated
# relMSE and its relMSE against $tmp/ref.pfm minus the reference's own (in $ref_est).
true_relmse() {
    scene=$1
    shift
    "$MCRT" --quiet --seed 1 -o "$tmp/t.pfm" --stats "$tmp/t.json" "$@" "$scene" || return 1
    d=$(diff_num relMSE "$tmp/t.pfm" "$tmp/ref.pfm")
    echo "$(json_num "$tmp/t.json" est_relmse) $d $ref_est" | awk '{ print $1, $2 - $3 }'
}

# reference SCENE WIDTH HEIGHT: $s, SCENE with its film set to WIDTH x HEIGHT, and its 1024 spp
# sobol reference of seed 99 in $tmp/ref.pfm, its own estimated relMSE in $ref_est.
reference() {
    film_size "scenes/$1.mcrt" "$2" "$3" | sed -E 's/^(film .*) spp [0-9]+/\1 spp 16/' >"$s"
    "$MCRT" --quiet --spp 1024 --sampler sobol --seed 99 -o "$tmp/ref.pfm" \
        --stats "$tmp/r.json" "$s" || return 1
    ref_est=$(json_num "$tmp/r.json" est_relmse)
}

# est_vs_true LABEL LOW OPTIONS...: $s rendered at 64 spp with OPTIONS for seeds 1 and 2; ok
# when the mean est_relmse over the mean true relMSE is within [LOW, 1.25].
est_vs_true() {
    label=$1 low=$2
    shift 2
    sums="0 0"
    for seed in 1 2; do
        sums=$(echo "$sums $(true_relmse "$s" --spp 64 "$@" --seed "$seed")" |
            awk '{ print $1 + $3, $2 + $4 }')
    done
    set -- $(echo "$sums" | awk '{ print $1 / 2, $2 / 2 }')
    if echo "$1 $2 $low" | awk '{ r = $1 / $2; exit !(r >= $3 && r <= 1.25) }'; then
        ok "$label: estimated relMSE $1 vs true $2 at 64 spp (means of 2 seeds), within [$low, 1.25]"
    else
        fail "$label" "estimated relMSE $1 vs true $2 at 64 spp (means of 2 seeds): not within [$low, 1.25]"
    fi
}

for name in soft-shadows cornell glossy; do
    s="$tmp/$name.mcrt"
    if ! reference "$name" 128 96; then
        fail "$name" "the reference did not render"
        continue
    fi
    # At 64 spp on a 128x96 film, as means over 2 seeds (E[est]/E[true]). The estimate's bias
    # grows with each pixel's own relative variance (its denominator comes from the same two
    # halves, film.h), so it is largest in the noisiest pixels, and where few pixels hold most
    # of the error: on a 64x48 film the light's edge pixels of the Cornell box, which hold 0 to 3
    # hits of the light per half, made the stratified sampler's estimate 1.27 times the truth
    # (means of 4 seeds); on this film 1.15, on the 102x102 one of make bench-error 0.97. One
    # render's est/true varies where rare bright paths land in a few pixels (0.86 to 1.56 for
    # one 64-spp 64x48 Cornell box over seeds), hence the means.
    for sampler in random stratified sobol; do
        est_vs_true "$name, $sampler" 0.8 --sampler "$sampler"
    done
    # --adaptive: the passes after the first give each pixel samples by its estimated error
    # (render/adaptive.c), so a pixel whose estimate came out low gets fewer samples and keeps
    # it, and the image's estimate reads low (selection bias). Allocated by the halves' own
    # difference, the stratified and Sobol estimates read 0.36 and 0.40 of the truth here on
    # cornell and soft-shadows (2 seeds); by the pooled sample variance, 0.84 and 0.94 to 0.99
    # (random 0.84, 0.95). glossy is left out: its fireflies make pixels without one yet get
    # few samples, 0.42 to 0.53 for every sampler (uniform sampling: the check above).
    if [ "$name" != glossy ]; then
        for sampler in random stratified sobol; do
            est_vs_true "$name, $sampler, --adaptive" 0.7 --adaptive --sampler "$sampler"
        done
    fi
    # The slope and --target-error on the 64x48 film.
    if ! reference "$name" 64 48; then
        fail "$name" "the reference did not render"
        continue
    fi
    if [ "$name" = soft-shadows ]; then
        set -- $(true_relmse "$s" --spp 64 --sampler random)
        t64=$2
        set -- $(true_relmse "$s" --spp 16 --sampler random)
        slope=$(echo "$2 $t64" | awk '{ printf "%.3f", log($2 / $1) / log(4) }')
        # Noise of the slope: each relMSE is a mean over 9216 channels; measured -1.02.
        if echo "$slope" | awk '{ exit !($1 > -1.15 && $1 < -0.85) }'; then
            ok "$name: relMSE slope $slope against spp (16 to 64), within -1 +- 0.15"
        else
            fail "$name" "relMSE slope $slope against spp (16 to 64), not within -1 +- 0.15"
        fi
    fi
    # --target-error: passes of 4 spp until est_relmse <= E, E chosen to need about 20 to 40
    # passes here. The render stops at the first pass at or below E, so its estimate lies in
    # (E·k/(k + 1), E] after k passes, and its true relMSE is about 0.9 E in the mean. One render's
    # true relMSE varies by about 0.2 E (rare bright paths; on the Cornell box at this size with
    # the Sobol sampler, 16 seeds: 0.47 to 1.26 times E, mean 0.88), so the check is on the mean
    # over 16 seeds: sd about 0.05 E, a factor 1.3 (0.77 E) 2.2 sd below that mean. With 4 seeds
    # (sd 0.1 E) the check had failed at 0.74 when the sampler's dimensions moved (a lobe choice
    # no longer drawn for diffuse surfaces), the same 8 seeds reading 0.90 and 0.93 before and
    # after.
    E=2e-3 sum_est=0 sum_true=0
    for seed in 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16; do
        "$MCRT" --quiet --seed "$seed" --spp 4 --target-error "$E" -o "$tmp/t.pfm" \
            --stats "$tmp/t.json" "$s" || break
        d=$(diff_num relMSE "$tmp/t.pfm" "$tmp/ref.pfm")
        sum_est=$(echo "$sum_est $(json_num "$tmp/t.json" est_relmse)" | awk '{ print $1 + $2 }')
        sum_true=$(echo "$sum_true $d $ref_est" | awk '{ print $1 + $2 - $3 }')
    done
    set -- $(echo "$sum_est $sum_true" | awk '{ print $1 / 16, $2 / 16 }')
    if echo "$1 $2 $E" | awk '{ r = $2 / $3; exit !($1 <= $3 && r >= 1 / 1.3 && r <= 1.3) }'; then
        ok "$name: --target-error $E stopped at est $1, true $2 (means of 16 seeds): within a factor 1.3"
    else
        fail "$name" "--target-error $E stopped at est $1, true $2 (means of 16 seeds): not within a factor 1.3"
    fi
done

# mcrt converge: one CSV row per (sampler, rung), a reference rendered when none is given, and
# the plot when gnuplot is installed.
printf 'film { width 24 height 16 spp 1 }\nsphere { }\nenvironment { radiance 1 }\n' >"$tmp/c.mcrt"
if "$MCRT" converge --quiet --spp 2,8 --compare sampler=random,stratified -o "$tmp" "$tmp/c.mcrt" &&
    [ "$(grep -c '^scene,\(random\|stratified\),off,[28],' "$tmp/c-converge.csv")" -eq 4 ] &&
    head -1 "$tmp/c-converge.csv" | grep -q '^# reference: a render of 128 spp'; then
    ok "converge: CSV of 2 samplers x 2 rungs and reference"
else
    fail "converge" "$(cat "$tmp/c-converge.csv" 2>/dev/null)"
fi
check_plot "converge: plot" "$tmp/c-converge.png"

finish
