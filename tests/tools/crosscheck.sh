#!/bin/sh
# crosscheck.sh (make crosscheck; needs Mitsuba 3 from PyPI, so never part of make test): every
# scene of scenes/, tests/crosscheck/ and $O/bench/scenes/ that `mcrt mitsuba` exports is rendered
# by mcrt and by Mitsuba 3 (scalar_rgb) at SPP samples per pixel, the film divided by SHRINK, and
# compared with `mcrt diff`. The tolerance is the two renders' own noise: mcrt's variance layer (of
# its pixel means) plus Mitsuba's, estimated from RENDERS independent renders of SPP/RENDERS samples
# each (their sample variance / RENDERS, RENDERS - 1 degrees of freedom: 15 by default), with
# Mitsuba's independent sampler (its stratified one is biased at 4 samples a render: cornell's green
# +1.1%). The verdict: the z-test (Sidak alpha 0.01, 99.75% agreeing) on the means of BLOCK x BLOCK
# pixel blocks, whose variance is the block's summed variance / BLOCK^4, and the image's mean
# difference within 4 standard errors of it (the square root of the summed variances over the pixel
# and channel count). The same z-test per pixel is printed too, but does not decide: a pixel's mean
# of a few samples of a path tracer is far from normal where rare paths carry much light (caustics
# of small lights through mirrors and glass: a Mitsuba render of 4 spp that draws none of them has a
# mean and a spread estimate both too low), and averaging blocks restores the normal limit the
# z-test assumes. A scene that disagrees is a finding: one renderer or the mapping (mcrt(1),
# `mcrt mitsuba`) is wrong, or a documented difference shows. Images, variances and z pictures go
# to OUT.
#   SPP=64 RENDERS=16 SHRINK=2 BLOCK=4 OUT=build/crosscheck CASES="cornell glossy" make crosscheck
O=${O:-build}
MCRT=$(cd "$O" && pwd)/mcrt
SPP=${SPP:-64}
RENDERS=${RENDERS:-16}
SHRINK=${SHRINK:-2}
BLOCK=${BLOCK:-4}
OUT=${OUT:-$O/crosscheck}
PY=$(pwd)/tests/tools/mitsuba_render.py
# Where both renders have no noise (a constant sky seen directly), they still differ by the
# rounding of float sums of the samples: 2^-24 relative per addition, 1e-6 for radiances up to 16.
FLOOR=1e-6
. tests/outputs.sh.inc

if ! python3 -c 'import mitsuba' 2>/dev/null; then
    echo "crosscheck: Mitsuba 3 is not installed: pip install mitsuba (its scalar_rgb variant needs no LLVM)"
    exit 1
fi
mkdir -p "$OUT"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
agree=0 disagree=0 refused=0
: >"$OUT/summary"
# The generated scenes of make bench-mitsuba too, when they have been written ($O/bench/scenes,
# by tests/tools/bench_scenes.c; make crosscheck writes them).
for scene in scenes/*.mcrt tests/crosscheck/*.mcrt "$O"/bench/scenes/*.mcrt; do
    [ -f "$scene" ] || continue
    name=$(basename "$scene" .mcrt)
    if [ -n "$CASES" ] && ! echo " $CASES " | grep -q " $name "; then continue; fi
    # The scene with its film shrunk, in a copy of the scene folders so that the meshes and
    # maps it names resolve as from its own.
    dir=$(dirname "$scene")
    rm -rf "$tmp/root" && mkdir -p "$tmp/root/scenes" "$tmp/root/tests/crosscheck" &&
        cp -R scenes/. "$tmp/root/scenes/" && cp -R tests/crosscheck/. "$tmp/root/tests/crosscheck/" &&
        mkdir -p "$tmp/root/$dir" && cp -R "$dir/." "$tmp/root/$dir/"
    film_shrink "$scene" "$SHRINK" >"$tmp/root/$dir/$name.cc.mcrt"
    src=$tmp/root/$dir/$name.cc.mcrt
    if ! "$MCRT" mitsuba "$src" -o "$tmp/$name.xml" 2>"$tmp/err"; then
        echo "$name: not exported: $(sed 's|.*/||' "$tmp/err")" | tee -a "$OUT/summary"
        refused=$((refused + 1))
        continue
    fi
    start=$(date +%s)
    "$MCRT" --quiet --spp "$SPP" --aov variance -o "$tmp/mc.exr" "$src" || exit 1
    mid=$(date +%s)
    bound=$(python3 "$PY" "$tmp/$name.xml" "$OUT/$name-mitsuba.exr" --spp $((SPP / RENDERS)) \
        --renders "$RENDERS" --independent --variance "$OUT/$name-var.exr" --add-variance "$tmp/mc.exr" \
        --blocks "$BLOCK" "$OUT/$name-blocks") || exit 1
    end=$(date +%s)
    cp "$tmp/mc.exr" "$OUT/$name-mcrt.exr"
    rm -f "$OUT/$name"-*.z.png
    "$MCRT" diff "$OUT/$name-mcrt.exr" "$OUT/$name-mitsuba.exr" --variance "$OUT/$name-var.exr" \
        --floor "$FLOOR" >"$tmp/pixels" 2>&1
    if "$MCRT" diff "$OUT/$name-blocks-mcrt.exr" "$OUT/$name-blocks-mitsuba.exr" \
        --variance "$OUT/$name-blocks-var.exr" --floor "$FLOOR" --max-bias "$bound" >"$tmp/diff" 2>&1; then
        verdict=agree agree=$((agree + 1))
    else
        verdict=DISAGREE disagree=$((disagree + 1))
    fi
    echo "$name: $verdict (mcrt $((mid - start)) s, Mitsuba $((end - mid)) s; bias bound $bound)" | tee -a "$OUT/summary"
    sed 's/^/    blocks: /' "$tmp/diff" | tee -a "$OUT/summary"
    sed -n 's/^z-test/    pixels: z-test/p' "$tmp/pixels" | tee -a "$OUT/summary"
done
echo "$agree agree, $disagree disagree, $refused not exported (SPP=$SPP RENDERS=$RENDERS SHRINK=$SHRINK BLOCK=$BLOCK; images in $OUT)"
