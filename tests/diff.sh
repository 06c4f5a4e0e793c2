#!/bin/sh
# diff.sh: `mcrt diff` as a user meets it, and the render's own error estimate: an image against
# itself is exactly zero; a render passes the z-test against an independent longer render of the
# same scene using its variance layer (--aov variance), and a render with a light 10% too bright
# fails it and gets a z image; --max-relmse and --max-bias set the exit status; bad input exits 2.
# Run from the repository root after the build; $O is the build folder. Prints "ok ..." or
# "FAIL ...: why" per check, then "N passed, N failed"; exits 1 if any failed.
. tests/harness.sh.inc

# run ARGS...: mcrt in $tmp; stdout in $tmp/out, stderr in $tmp/err, exit status in $rc.
run() {
    (cd "$tmp" && "$MCRT" "$@" >out 2>err)
    rc=$?
}

# check NAME STATUS: the last run exited with STATUS.
check() {
    if [ "$rc" -eq "$2" ]; then ok "$1"; else fail "$1" "exit $rc, expected $2: $(head -c 400 "$tmp/err")"; fi
}

# A small scene with a soft shadow, an area light and the independent "random" sampler, for which
# the per-pixel variance is an unbiased estimate of the variance of the mean (stratified samples
# are correlated and would make the z-test conservative).
scene() {
    printf 'film { width 40 height 30 spp 16 sampler random }\n'
    printf 'camera { eye 0 3 6  look 0 0.5 0  fov 40 }\n'
    printf 'material m { diffuse 0.7 }\n'
    printf 'quad { corner -4 0 4  edge1 8 0 0  edge2 0 0 -8  material m }\n'
    printf 'sphere { center 0 0.7 0  radius 0.7  material m }\n'
    printf 'quad { corner -0.5 3 -0.5  edge1 1 0 0  edge2 0 0 1  emit %s }\n' "$1"
}
scene 20 >"$tmp/s.mcrt"
scene 22 >"$tmp/bright.mcrt"

run --quiet --spp 8 -o a.pfm s.mcrt
run diff a.pfm a.pfm
if [ "$rc" -eq 0 ] && grep -q 'MSE 0, relMSE 0, PSNR inf dB, max error 0, bias 0 ' "$tmp/out"; then
    ok "an image against itself: exactly zero, exit 0"
else
    fail "an image against itself" "exit $rc: $(cat "$tmp/out" "$tmp/err")"
fi
run diff --crop 0,0,50,10 a.pfm a.pfm
check "a crop outside the image is bad input" 2
run diff --crop 5,5,5,9 a.pfm a.pfm
check "an empty crop is bad input" 2
run diff a.pfm missing.pfm
check "a missing reference is bad input" 2
printf 'film { width 8 height 8 spp 1 }\nsphere { }\n' >"$tmp/small.mcrt"
run --quiet -o small.pfm small.mcrt
run diff a.pfm small.pfm
check "images of different sizes are bad input" 2

if ! "$MCRT" --version | grep -q ' exr'; then
    skip "z-test" "this mcrt was built without OpenEXR"
else
    # 64 spp against 1024 spp: the reference's own variance is 1/16 of the test's, which raises
    # z by sqrt(1 + 1/16) = 3%, covered by the 0.25% of pixels allowed to disagree. Floor 1e-3:
    # pixels whose 64 samples happen to agree have sample variance 0 but not true variance 0.
    run --quiet --spp 64 --seed 1 --aov variance -o t.exr s.mcrt
    run --quiet --spp 1024 --seed 2 -o ref.exr s.mcrt
    run diff --variance t.exr --floor 1e-3 t.exr ref.exr
    if [ "$rc" -eq 0 ] && grep -q '^z-test: .*: pass$' "$tmp/out" && [ ! -e "$tmp/t.z.png" ]; then
        ok "z-test: a correct render passes ($(grep -o '[0-9.]*% of [0-9]* pixels agree' "$tmp/out"))"
    else
        fail "z-test of a correct render" "exit $rc: $(cat "$tmp/out" "$tmp/err")"
    fi
    # The light 10% brighter: every lit pixel is off by 10%, against a standard deviation of the
    # 64-spp mean of about 3% (relMSE of the test, printed), so z ~ 3 on most pixels.
    run --quiet --spp 64 --seed 1 --aov variance -o b.exr bright.mcrt
    run diff --variance b.exr --floor 1e-3 b.exr ref.exr
    if [ "$rc" -eq 1 ] && grep -q 'FAIL$' "$tmp/out" && grep -q 'z image in .*b\.z\.png' "$tmp/err" &&
        [ -s "$tmp/b.z.png" ]; then
        ok "z-test: a light 10% too bright fails and writes b.z.png ($(grep -o '[0-9.]*% of [0-9]* pixels agree' "$tmp/out"))"
    else
        fail "z-test of a wrong render" "exit $rc: $(cat "$tmp/out" "$tmp/err")"
    fi
    # The image-mean bias of the bright render is about +10% of the mean radiance; of the correct
    # one, noise only: the mean of 1200 pixels' errors, far below 0.01.
    run diff --max-bias 0.01 t.exr ref.exr
    check "--max-bias: a correct render is within 0.01" 0
    run diff --max-bias 0.01 b.exr ref.exr
    check "--max-bias: the bright render is not" 1
    run diff --max-relmse 1e-6 t.exr ref.exr
    check "--max-relmse 1e-6 is exceeded by a 64 spp render" 1
    run diff --max-relmse 1 --crop 10,10,30,20 t.exr ref.exr
    if [ "$rc" -eq 0 ] && grep -q '^crop: 200 pixels' "$tmp/out"; then
        ok "--crop reports the 20x10 window"
    else
        fail "--crop" "exit $rc: $(cat "$tmp/out" "$tmp/err")"
    fi
    run diff --layer variance t.exr t.exr
    check "--layer compares a named layer" 0
    run diff --layer albedo t.exr t.exr
    check "--layer of a missing layer is bad input" 2
fi

finish
