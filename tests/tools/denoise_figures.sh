#!/bin/sh
# denoise_figures.sh: the README's denoiser figures (make denoise-figures), a measurement, not a
# test. scenes/cornell.mcrt with its film set to $SIZE² (default 160, the size of the README's
# denoiser table and of the OIDN figures in estimators-anchor.md §2), into $OUT (default
# build/figures):
#   - cornell-denoise-converge.png (and its .csv, .gp): `mcrt converge --spp 4,16,64 --compare
#     denoise=off,on` against a $REF_SPP (default 4096) spp reference of seed 1000003 (whose own
#     relMSE, about the raw 64 spp render's over 64, is in every true relMSE of the plot: the
#     converge default, 16 times the largest rung, would be comparable to the denoised error);
#   - cornell-denoise-crops.png: the window $WINDOW (x0,y0,x1,y1 of the film) of the raw 16 spp
#     image, the denoised one and the reference, each enlarged $SCALE times, side by side. The 16
#     spp render is converge's own rung (seed 1: rung 1 of seed 0), so the crops show the plot's
#     16 spp points.
# Then prints the CSV as a table. $MCRT is the binary (default build/mcrt), $THREADS the threads
# (default 0: all cores), $O the build folder with tests/crops.
O=${O:-build}
MCRT=${MCRT:-$O/mcrt}
SIZE=${SIZE:-160}
REF_SPP=${REF_SPP:-4096}
WINDOW=${WINDOW:-44,68,108,132}
SCALE=${SCALE:-3}
THREADS=${THREADS:-0}
OUT=${OUT:-$O/figures}
. tests/outputs.sh.inc
mkdir -p "$OUT" || exit 1
tmp=$(mktemp -d) || exit 1
trap 'rm -rf "$tmp"' EXIT

film_size scenes/cornell.mcrt "$SIZE" "$SIZE" >"$tmp/cornell-denoise.mcrt"
ref=$OUT/cornell-denoise-ref.exr
"$MCRT" --quiet --threads "$THREADS" --spp "$REF_SPP" --seed 1000003 -o "$ref" \
    --stats "$tmp/ref.json" "$tmp/cornell-denoise.mcrt" || exit 1
echo "reference: $REF_SPP spp, est. relMSE $(json_num "$tmp/ref.json" est_relmse)"
"$MCRT" converge --quiet --threads "$THREADS" --spp 4,16,64 --compare denoise=off,on \
    --ref "$ref" -o "$OUT" "$tmp/cornell-denoise.mcrt" || exit 1
"$MCRT" --quiet --threads "$THREADS" --spp 16 --seed 1 --denoise -o "$tmp/d16.exr" \
    "$tmp/cornell-denoise.mcrt" || exit 1
"$O/tests/crops" "$OUT/cornell-denoise-crops.png" "$WINDOW" "$SCALE" "$tmp/d16.exr:raw" \
    "$tmp/d16.exr" "$ref" || exit 1
echo "wrote $OUT/cornell-denoise-converge.png and $OUT/cornell-denoise-crops.png"
awk -F, '/^#/ || /^estimator/ { next }
    { printf "%-4s %3d spp %8.2f s  relMSE %.3g  est. %.3g\n", $3, $4, $5, $7, $8 }' \
    "$OUT/cornell-denoise-converge.csv"
