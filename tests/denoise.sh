#!/bin/sh
# denoise.sh: `mcrt render --denoise` and `mcrt denoise` (issue 16), on renders of scenes/.
#   - The denoised image's estimated relMSE (est_relmse of --stats) is within a factor 2 of its
#     true relMSE on cornell (160x160, 16 spp) and on dof (128x128, 16 spp: lamps out of focus),
#     and misses on cornell-spheres (96x96) by no more
#     than a factor 2 beyond what the raw image's own estimate misses (see below); the truth
#     measured against a 1024 spp render of another seed with the reference's own estimated
#     relMSE subtracted (independent errors: their mean squares add), as in tests/error.sh.
#   - The estimate's own standard deviation (est_relmse_sd) matches its scatter about the truth
#     over ten seeds of the Cornell box (128x128, 16 spp; see below).
#   - Energy: the denoised image's mean is within 1% of the raw's (same renders).
#   - Consistency: at 1024 spp (a 32x24 Cornell box), the denoised image equals the raw one within
#     the raw's own noise: their relMSE against each other at most twice the raw's est_relmse
#     (E[(D - R)^2] = Var(R) + MSE(D) - 2 Cov when D tends to the truth; 2 leaves room for
#     MSE(D) up to the raw's own error and for the estimate's own spread).
#   - 1 and 2 threads give the same file; `mcrt denoise` of the render's EXR gives the render's
#     denoised image exactly; the denoiser's SSE2 copy (test_denoise_sse) gives the same bits as
#     the one this processor runs (AVX2 where it has it) on test_denoise's flat image.
#   - Bad input to `mcrt denoise`: a PNG, an EXR without the layers, a missing file, a non-EXR
#     output, no -o: exit status 2 with a message, and an existing output left as it was.
. tests/harness.sh.inc

stat() { sed -n "s/^ *\"$2\": \\([^,]*\\),*\$/\\1/p" "$1"; }
# field KEY TEST REF: relMSE, MSE or bias of TEST against REF (whole image).
field() {
    "$MCRT" diff "$2" "$3" | sed -n "s/^whole image: .* $1 \\([^ ,]*\\).*/\\1/p"
}
film() { sed -E "s/^film \\{ *width [0-9]+ height [0-9]+/film { width $2 height $3/" "scenes/$1.mcrt"; }
# black W H FILE: an all-zero PFM, to read an image's mean as its bias against it.
black() {
    printf 'PF\n%d %d\n-1.0\n' "$1" "$2" >"$3"
    head -c $(($1 * $2 * 12)) /dev/zero >>"$3"
}

# error NAME SIZE SEEDS...: render NAME on a SIZE² film at 16 spp (raw and denoised) for each
# seed and its reference (seed 99); sets est (the denoised est_relmse), tru (its true relMSE),
# raw_est and raw_tru (the raw's), each the mean over the seeds, and leaves the last seed's
# images in d.pfm and raw.pfm.
error() {
    name=$1 size=$2
    shift 2
    film "$name" "$size" "$size" >"$tmp/$name.mcrt"
    black "$size" "$size" "$tmp/black.pfm"
    "$MCRT" --quiet --spp 1024 --seed 99 -o "$tmp/ref.pfm" --stats "$tmp/ref.json" \
        "$tmp/$name.mcrt" || return 1
    ref_est=$(stat "$tmp/ref.json" est_relmse)
    sums=
    for seed in "$@"; do
        "$MCRT" --quiet --spp 16 --seed "$seed" --denoise -o "$tmp/d.pfm" --stats "$tmp/d.json" \
            "$tmp/$name.mcrt" && "$MCRT" --quiet --spp 16 --seed "$seed" -o "$tmp/raw.pfm" \
            "$tmp/$name.mcrt" || return 1
        sums="$sums $(stat "$tmp/d.json" est_relmse) $(field relMSE "$tmp/d.pfm" "$tmp/ref.pfm")"
        sums="$sums $(stat "$tmp/d.json" est_relmse_raw) $(field relMSE "$tmp/raw.pfm" "$tmp/ref.pfm")"
    done
    set -- $(echo "$sums $ref_est" | awk '{ n = (NF - 1) / 4
        for (i = 0; i < n; i++) for (k = 1; k <= 4; k++) m[k] += $(4 * i + k) / n
        print m[1], m[2] - $NF, m[3], m[4] - $NF }')
    est=$1 tru=$2 raw_est=$3 raw_tru=$4
}
# energy NAME: the denoised image's mean within 1% of the raw's.
energy() {
    set -- "$1" $(field bias "$tmp/d.pfm" "$tmp/black.pfm") $(field bias "$tmp/raw.pfm" "$tmp/black.pfm")
    if echo "$2 $3" | awk '{ d = $1 - $2; exit !(d < 0.01 * $2 && -d < 0.01 * $2) }'; then
        ok "$1: denoised mean $2, raw $3: within 1%"
    else
        fail "$1" "denoised mean $2, raw $3: not within 1%"
    fi
}

# factor2 NAME SIZE: error() of NAME on a SIZE² film for seeds 1-3; the mean estimate within a
# factor 2 of the mean truth, and the energy kept.
factor2() {
    if error "$1" "$2" 1 2 3; then
        if echo "$est $tru" | awk '{ exit !($1 > $2 / 2 && $1 < $2 * 2) }'; then
            ok "$1: denoised est. relMSE $est vs true $tru (raw $raw_tru) at 16 spp, within a factor 2"
        else
            fail "$1" "denoised est. relMSE $est vs true $tru (raw $raw_tru) at 16 spp: not within a factor 2"
        fi
        energy "$1"
    else
        fail "$1" "a render failed"
    fi
}

# The Cornell box: the issue's factor 2, on the 160² film of its measurements (estimators-anchor.md
# §2), the mean over seeds 1-3: one render's estimate spreads widely (make bench-denoise, ten
# seeds: 0.77 of the truth in the mean at 16 spp, 0.30 to 1.15 seed by seed; the README's
# denoiser section says why).
factor2 cornell 160
# Five small lamps far out of focus (scenes/dof.mcrt, 128², 16 spp, seeds 1-3): their blur disks
# are light seen by one sample of 16 here and there, which the denoiser adds back unfiltered, and
# most of the denoised image's error. Each pixel's error must be divided by an estimate of its
# μ², not by its noisy value squared, hundreds of times larger there (nfor.h, mean_sq): that way
# the estimate read 0.18 of the truth (0.14 to 0.27 seed by seed); now 0.78 (0.56 to 1.26). The
# issue's factor 2, on the mean of the three seeds.
factor2 dof 128
# The estimate's own standard deviation (est_relmse_sd, the terms' variances summed): over ten
# seeds of the Cornell box at 128² and 16 spp, z = (est − true)/sd has a spread (the sample
# standard deviation of the ten) that ten draws of a unit normal exceed or fall short of with
# probability 0.001 each: (χ²₉ quantiles 0.001 and 0.999 over 9)^½ = 0.36 to 1.76. With the
# spread measured here (1.06), an sd half as large (2.1) or three times as large (0.35) fails;
# twice as large (0.53) would not. The mean of z is left free: the estimate's deficit at the
# light's edges (the README's denoiser section) shifts it (-0.90, with a spread of 1.07, over ten
# seeds of the 160² film of make bench-denoise). The truth has the reference's own estimated
# relMSE subtracted, as in error(); what is left of its noise is common to all seeds: it moves
# the mean, not the spread.
film cornell 128 128 >"$tmp/sd.mcrt"
if "$MCRT" --quiet --spp 1024 --seed 99 -o "$tmp/sdref.pfm" --stats "$tmp/sdref.json" \
    "$tmp/sd.mcrt"; then
    zs=$(stat "$tmp/sdref.json" est_relmse)
    for seed in 1 2 3 4 5 6 7 8 9 10; do
        "$MCRT" --quiet --spp 16 --seed "$seed" --denoise -o "$tmp/sd.pfm" --stats "$tmp/sd.json" \
            "$tmp/sd.mcrt" || break
        zs="$zs $(stat "$tmp/sd.json" est_relmse) $(stat "$tmp/sd.json" est_relmse_sd) $(field relMSE "$tmp/sd.pfm" "$tmp/sdref.pfm")"
    done
    set -- $(echo "$zs" | awk '{ for (i = 2; i + 2 <= NF; i += 3) { z = ($i - ($(i + 2) - $1)) / $(i + 1)
        s += z; ss += z * z; n++ }
        if (n < 10) { print "none"; exit } m = s / n; printf "%.2f %.2f\n", m, sqrt((ss - n * m * m) / (n - 1)) }')
    if [ "$1" != none ] && echo "$2" | awk '{ exit !($1 >= 0.36 && $1 <= 1.76) }'; then
        ok "est_relmse_sd: (est - true)/sd over ten seeds has mean $1 and spread $2, within 0.36-1.76"
    else
        fail "est_relmse_sd" "(est - true)/sd over ten seeds: mean ${1:-?}, spread ${2:-?}, not within 0.36-1.76"
    fi
else
    fail "est_relmse_sd" "the reference render failed"
fi

# The spheres: the caustic under the glass sphere is carried by paths so rare at 16 spp that
# both halves mostly miss them, so that the raw image's own estimate is 0.1 of its truth here
# (film.h; the README's error-estimate table). No estimate from the halves sees all of that
# error: checked is that the denoised estimate misses by no more than a factor 2 beyond the raw's
# miss, (est/true denoised) / (est/true raw) > 0.5, and is over
# the truth by no more than the issue's factor 2 (the denoised estimate, from each half's residual
# against its own result, sees far more than the raw's here: 1.17 of the truth against 0.11, the
# ratio of ratios 10.4). Each figure is the mean over three seeds: one render's caustic fireflies
# move either ratio by a factor 2 or more from seed to seed (on the 160² film of make
# bench-denoise the denoised estimate ranges from 0 to 2.7 times the truth over ten seeds).
if error cornell-spheres 96 1 2 3; then
    if echo "$est $tru $raw_est $raw_tru" | awk '{ r = ($1 / $2) / ($3 / $4); exit !(r > 0.5 && $1 < 2 * $2) }'; then
        ok "cornell-spheres: denoised est/true $est/$tru, raw $raw_est/$raw_tru: misses by at most 2x the raw's, over by at most 2x"
    else
        fail "cornell-spheres" "denoised est/true $est/$tru, raw $raw_est/$raw_tru: misses by over 2x the raw's miss, or is over 2x the truth"
    fi
    energy cornell-spheres
else
    fail cornell-spheres "a render failed"
fi

# Consistency at 1024 spp.
film cornell 32 24 >"$tmp/small.mcrt"
if "$MCRT" --quiet --spp 1024 --seed 3 --denoise -o "$tmp/d.pfm" --stats "$tmp/d.json" \
    "$tmp/small.mcrt" && "$MCRT" --quiet --spp 1024 --seed 3 -o "$tmp/raw.pfm" "$tmp/small.mcrt"; then
    d=$(field relMSE "$tmp/d.pfm" "$tmp/raw.pfm")
    est=$(stat "$tmp/d.json" est_relmse_raw)
    if echo "$d $est" | awk '{ exit !($1 <= 2 * $2) }'; then
        ok "consistency: denoised vs raw relMSE $d at 1024 spp, within twice the raw's est. $est"
    else
        fail "consistency" "denoised vs raw relMSE $d at 1024 spp, above twice the raw's est. $est"
    fi
else
    fail "consistency" "a render failed"
fi

# Threads, and mcrt denoise of the render's own layers.
film cornell-spheres 40 30 >"$tmp/t.mcrt"
"$MCRT" --quiet --spp 8 --threads 1 --denoise -o "$tmp/t1.exr" "$tmp/t.mcrt"
"$MCRT" --quiet --spp 8 --threads 2 --denoise -o "$tmp/t2.exr" "$tmp/t.mcrt"
if cmp -s "$tmp/t1.exr" "$tmp/t2.exr"; then
    ok "1 and 2 threads: the same denoised EXR"
else
    fail "threads" "1 and 2 threads gave different denoised EXRs"
fi
if "$O/tests/test_denoise" "$tmp/simd.bin" >/dev/null && "$O/tests/test_denoise_sse" "$tmp/sse.bin" >/dev/null \
    && cmp -s "$tmp/simd.bin" "$tmp/sse.bin"; then
    ok "the denoiser's SSE2 and run-time copies: the same bits"
else
    fail "simd" "test_denoise and test_denoise_sse failed or denoised differently"
fi
if "$MCRT" denoise --quiet --threads 2 "$tmp/t1.exr" -o "$tmp/again.exr" \
    && [ "$(field MSE "$tmp/again.exr" "$tmp/t1.exr")" = 0 ]; then
    ok "mcrt denoise of the render's EXR: the render's denoised image"
else
    fail "mcrt denoise" "its image differs from the render's denoised one"
fi

# Bad input: exit status 2, a message, the output untouched.
"$MCRT" --quiet --spp 2 -o "$tmp/plain.exr" "$tmp/t.mcrt"
"$MCRT" --quiet --spp 2 -o "$tmp/plain.png" "$tmp/t.mcrt" 2>/dev/null || cp "$tmp/t1.exr" "$tmp/plain.png"
echo keep >"$tmp/out.exr"
bad() {
    what=$1
    want=$2
    shift 2
    "$MCRT" denoise "$@" 2>"$tmp/err"
    code=$?
    if [ "$code" -eq 2 ] && grep -q "$want" "$tmp/err" && [ "$(cat "$tmp/out.exr")" = keep ]; then
        ok "mcrt denoise, $what: exit 2, '$(cat "$tmp/err")'"
    else
        fail "mcrt denoise, $what" "exit $code, '$(cat "$tmp/err")', output $(head -c 20 "$tmp/out.exr")"
    fi
}
bad "no layers" "no layer A" "$tmp/plain.exr" -o "$tmp/out.exr"
bad "a PNG" "EXR images only" "$tmp/plain.png" -o "$tmp/out.exr"
bad "a missing file" "$tmp/none.exr" "$tmp/none.exr" -o "$tmp/out.exr"
bad "no -o" "usage" "$tmp/t1.exr"
bad "a PNG output" "EXR images only" "$tmp/t1.exr" -o "$tmp/out.png"
[ -e "$tmp/out.png" ] && fail "mcrt denoise, a PNG output" "it was written"
finish
