#!/bin/sh
# denoise_bench.sh: what `mcrt render --denoise` gains (issue 16), a benchmark for the README and
# the notes (make bench-denoise), not a test. For scenes/cornell.mcrt and scenes/cornell-spheres
# .mcrt with their films set to $SIZE² (default 160, the size of the OIDN figures in
# estimators-anchor.md §2), at 16 and 64 spp: the true relMSE of the raw and of the denoised
# image against a $REF_SPP (default 2048) spp render of another seed, the reference's own
# estimated relMSE subtracted (independent errors: their mean squares add), the reduction, the
# denoised image's estimated relMSE over its true one, the shift of the mean (denoised minus
# raw, absolute) and the denoiser's seconds. Then the equal-time
# ratio (raw 64 spp over denoised 16 spp, true relMSE) and the seconds the denoiser takes for a
# 512² image on $THREADS threads (default 2; the median of 3 runs). $MCRT is the binary
# (default build/mcrt).
MCRT=${MCRT:-build/mcrt}
SIZE=${SIZE:-160}
REF_SPP=${REF_SPP:-2048}
THREADS=${THREADS:-2}
tmp=$(mktemp -d) || exit 2
trap 'rm -rf "$tmp"' EXIT
stat() { sed -n "s/^ *\"$2\": \\([^,]*\\),*\$/\\1/p" "$1"; }
# diffstat IMAGE REF: the relMSE and the bias of IMAGE against REF.
diffstat() {
    "$MCRT" diff "$1" "$2" |
        sed -n "s/^whole image: .*relMSE \\([^,]*\\),.*bias \\([^ ]*\\) .*/\\1 \\2/p"
}
film() { sed -E "s/^film \\{ *width [0-9]+ height [0-9]+/film { width $2 height $2/" "$1"; }

printf '%-16s %4s %10s %10s %7s %10s %9s %9s\n' scene spp raw denoised gain est/true \
    "d_mean" "seconds"
for name in cornell cornell-spheres; do
    film "scenes/$name.mcrt" "$SIZE" >"$tmp/s.mcrt"
    "$MCRT" --quiet --spp "$REF_SPP" --seed 9999 --threads "$THREADS" -o "$tmp/ref.exr" \
        --stats "$tmp/ref.json" "$tmp/s.mcrt" || exit 1
    ref_est=$(stat "$tmp/ref.json" est_relmse)
    for spp in 16 64; do
        # The raw image is the same render without the denoiser (same seed, same pixels).
        "$MCRT" --quiet --spp "$spp" --seed 1 --threads "$THREADS" -o "$tmp/raw.exr" \
            "$tmp/s.mcrt" || exit 1
        "$MCRT" --quiet --spp "$spp" --seed 1 --threads "$THREADS" --denoise -o "$tmp/t.exr" \
            --stats "$tmp/t.json" "$tmp/s.mcrt" || exit 1
        set -- $(diffstat "$tmp/raw.exr" "$tmp/ref.exr") $(diffstat "$tmp/t.exr" "$tmp/ref.exr")
        echo "$name $spp $1 $2 $3 $4 $ref_est $(stat "$tmp/t.json" est_relmse) \
            $(stat "$tmp/t.json" denoise_seconds)" | awk '{
            raw = $3 - $7; den = $5 - $7
            printf "%-16s %4d %10.3e %10.3e %6.1fx %10.2f %+9.2e %9.2f\n", $1, $2, raw, den,
                raw / den, $8 / den, $6 - $4, $9 }'
        eval "raw_$spp=\$(echo $1 $ref_est | awk '{ print \$1 - \$2 }')"
        eval "den_$spp=\$(echo $3 $ref_est | awk '{ print \$1 - \$2 }')"
    done
    echo "$name equal time: raw 64 spp / denoised 16 spp = $(echo "$raw_64 $den_16" |
        awk '{ printf "%.2f", $1 / $2 }')"
done
film scenes/cornell.mcrt 512 >"$tmp/s.mcrt"
for i in 1 2 3; do
    "$MCRT" --quiet --spp 4 --threads "$THREADS" --denoise -o "$tmp/t.exr" --stats "$tmp/t.json" \
        "$tmp/s.mcrt" || exit 1
    stat "$tmp/t.json" denoise_seconds
done | sort -n | sed -n 2p | awk -v t="$THREADS" '{ printf "denoise 512x512, %d threads: %.2f s (median of 3)\n", t, $1 }'
