#!/bin/sh
# denoise_bench.sh: what `mcrt render --denoise` gains (issue 16), a benchmark for the README and
# the notes (make bench-denoise), not a test. For the scenes of $SCENES (default
# scenes/cornell.mcrt, scenes/cornell-spheres.mcrt and scenes/dof.mcrt, whose small lamps far out
# of focus are seen by few samples) with their films set to $SIZE² (default 160, the size of the OIDN figures in
# estimators-anchor.md §2), at 16 and 64 spp and for each seed of $SEEDS (default 1 to 10: one
# render's figures spread, the Cornell box's gain at 16 spp from 12.7 to 21.9 times over those
# ten, cornell-spheres' estimate from 0 to 2.7 times its truth, so that two seeds said little
# about the mean, and the first run renders the 60 inputs and the references in a few
# minutes): the
# true relMSE of the raw and of the denoised image, the reduction, the denoised image's estimated
# relMSE over its true one (the means', the range of the seeds' own, and how many seeds' own are
# not within the issue's factor 2), the shift of the mean (denoised minus raw) and the mean and
# spread of (estimate - truth)/est_relmse_sd over the seeds (0 and 1 when the estimate is unbiased
# and its sd right); then the
# equal-samples
# ratio (raw 64 spp over denoised 16 spp, true relMSE) and the seconds the denoiser takes for a
# 512² image on $THREADS threads (default 2; the median of 3 runs). $MCRT is the binary (default
# build/mcrt), $EXR_AVERAGE tests/tools/exr_average's (default build/tests/exr_average).
#
# The renders are made once and kept in $CACHE (default /tmp/mcrt-denoise-bench), so that a run
# costs only the denoiser (`mcrt denoise` of each kept render) and any two builds denoise the same
# inputs:
#   - the reference of a scene is the mean of two renders of seeds 9001 and 9002 at $REF_SPP each
#     (default 4096; cornell-spheres' caustic, which a few samples of a pixel mostly miss, gets
#     $CAUSTIC_REF_SPP, default 8192). Its own relMSE is measured, not estimated from halves (an
#     estimate from a render's halves misses the caustic as the halves do): the two renders'
#     relMSE against each other is twice one's, so that of their mean is a quarter of it. The
#     truths below have it subtracted (independent errors: their mean squares add), and it is
#     printed;
#   - the inputs are `mcrt render --denoise` EXRs (halves and features) and the raw renders of
#     the same seeds, kept under a key of the feature code (src/render/aov.[ch]), so that changed
#     features are rendered anew. Long renders run under nice -n 10.
MCRT=${MCRT:-build/mcrt}
EXR_AVERAGE=${EXR_AVERAGE:-build/tests/exr_average}
SIZE=${SIZE:-160}
REF_SPP=${REF_SPP:-4096}
CAUSTIC_REF_SPP=${CAUSTIC_REF_SPP:-8192}
SEEDS=${SEEDS:-1 2 3 4 5 6 7 8 9 10}
SCENES=${SCENES:-cornell cornell-spheres dof}
THREADS=${THREADS:-2}
CACHE=${CACHE:-/tmp/mcrt-denoise-bench}
mkdir -p "$CACHE" || exit 2
tmp=$(mktemp -d) || exit 2
trap 'rm -rf "$tmp"' EXIT
key=$(cat src/render/aov.c src/render/aov.h src/api/denoise.h | cksum | cut -d' ' -f1)
stat() { sed -n "s/^ *\"$2\": \\([^,]*\\),*\$/\\1/p" "$1"; }
# diffstat IMAGE REF: the relMSE and the bias of IMAGE against REF.
diffstat() {
    "$MCRT" diff "$1" "$2" |
        sed -n "s/^whole image: .*relMSE \\([^,]*\\),.*bias \\([^ ]*\\) .*/\\1 \\2/p"
}
film() { sed -E "s/^film \\{ *width [0-9]+ height [0-9]+/film { width $2 height $2/" "$1"; }
# render OUT ARGS...: render into OUT (and OUT's stats) unless it is kept already.
render() {
    out=$1
    shift
    [ -s "$out" ] && return 0
    nice -n 10 "$MCRT" --quiet --threads "$THREADS" -o "$out.part.${out##*.}" "$@" &&
        mv "$out.part.${out##*.}" "$out"
}

printf '%-16s %4s %10s %10s %7s %15s %8s %13s %8s %9s %11s\n' scene spp raw denoised gain \
    "gain per seed" est/true "per seed" "not in 2x" d_mean "z mean/sd"
for name in $SCENES; do
    scene=$CACHE/$name-$SIZE.mcrt
    film "scenes/$name.mcrt" "$SIZE" >"$tmp/s.mcrt"
    cmp -s "$tmp/s.mcrt" "$scene" || cp "$tmp/s.mcrt" "$scene"
    spp=$REF_SPP
    [ "$name" = cornell-spheres ] && spp=$CAUSTIC_REF_SPP
    ref=$CACHE/ref-$name-$SIZE
    for seed in 9001 9002; do
        render "$ref-$seed-$spp.exr" --spp "$spp" --seed "$seed" "$scene" || exit 1
    done
    [ -s "$ref-$spp.exr" ] || "$EXR_AVERAGE" "$ref-$spp.exr" "$ref-9001-$spp.exr" \
        "$ref-9002-$spp.exr" || exit 1
    ref_err=$(diffstat "$ref-9001-$spp.exr" "$ref-9002-$spp.exr" | awk '{ print $1 / 4 }')
    ref=$ref-$spp.exr
    for spp in 16 64; do
        rows=
        for seed in $SEEDS; do
            in=$CACHE/in-$name-$SIZE-$spp-$seed-$key
            render "$in.exr" --spp "$spp" --seed "$seed" --denoise "$scene" &&
                render "$in.raw.pfm" --spp "$spp" --seed "$seed" "$scene" || exit 1
            est=$("$MCRT" denoise --threads "$THREADS" "$in.exr" -o "$tmp/d.exr" 2>&1 |
                sed -n 's/.*est\. relMSE \([^ ]*\) +- \([^ ]*\) .*/\1 \2/p')
            rows="$rows$(diffstat "$in.raw.pfm" "$ref") $(diffstat "$tmp/d.exr" "$ref") $est
"
        done
        # Per seed: raw relMSE, raw bias, denoised relMSE, denoised bias, denoised estimate and
        # its standard deviation; z = (estimate - truth)/sd, whose mean and spread (the sample
        # standard deviation) say how well the sd describes the estimate's scatter.
        printf '%s' "$rows" | awk -v name="$name" -v spp="$spp" -v e="$ref_err" '{
            raw = $1 - e; den = $3 - e; n++
            sraw += raw; sden += den; sest += $5; sd += $4 - $2
            g = raw / den; gmin = n == 1 || g < gmin ? g : gmin; gmax = n == 1 || g > gmax ? g : gmax
            r = $5 / den; rmin = n == 1 || r < rmin ? r : rmin; rmax = n == 1 || r > rmax ? r : rmax
            out += r < 0.5 || r > 2; z = ($5 - den) / $6; sz += z; szz += z * z }
            END { zm = sz / n; zs = n > 1 ? sqrt((szz - n * zm * zm) / (n - 1)) : 0
                printf "%-16s %4d %10.3e %10.3e %6.1fx %6.1f-%5.1fx %8.2f %6.2f-%5.2f %4d/%-3d %+9.2e %+5.2f/%4.2f\n",
                name, spp, sraw / n, sden / n, sraw / sden, gmin, gmax, sest / sden, rmin, rmax, out, n,
                sd / n, zm, zs
                print sraw / n, sden / n > "'"$tmp/mean-$spp"'" }'
    done
    read -r raw64 den64 <"$tmp/mean-64"
    read -r raw16 den16 <"$tmp/mean-16"
    echo "$name: equal samples, raw 64 spp / denoised 16 spp = $(echo "$raw64 $den16" |
        awk '{ printf "%.2f", $1 / $2 }'); the reference's own relMSE $ref_err (measured)"
done
film scenes/cornell.mcrt 512 >"$tmp/s.mcrt"
for i in 1 2 3; do
    "$MCRT" --quiet --spp 4 --threads "$THREADS" --denoise -o "$tmp/t.exr" --stats "$tmp/t.json" \
        "$tmp/s.mcrt" || exit 1
    stat "$tmp/t.json" denoise_seconds
done | sort -n | sed -n 2p | awk -v t="$THREADS" '{ printf "denoise 512x512, %d threads: %.2f s (median of 3)\n", t, $1 }'
