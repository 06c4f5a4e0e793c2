#!/bin/sh
# tsan.sh: run by `make tsan` on a ThreadSanitizer build ($O/mcrt): renders every scene in scenes/
# and tests/stiff/ with 4 threads (more threads than cores, so tiles interleave) at 2 spp, the
# caustic scene with every integrator and a small Cornell box denoised, runs
# test_tiles (the progress callback), and fails on any ThreadSanitizer report or failed render.
# Not part of `make test` (it needs its own build). Prints "ok ..." or "FAIL ...: why" per scene,
# then "N passed, N failed".
O=${O:-build-tsan}
. tests/harness.sh.inc
# halt_on_error: the first race ends the run with exitcode 66, so a race cannot pass unnoticed.
TSAN_OPTIONS="halt_on_error=1 exitcode=66 ${TSAN_OPTIONS:-}"
export TSAN_OPTIONS
# render NAME ARGS...: mcrt ARGS (stderr to err), ok NAME when it succeeds with no
# ThreadSanitizer report, else fail NAME and show the report.
render() {
    name=$1
    shift
    "$MCRT" "$@" 2>"$tmp/err"
    rc=$?
    if [ "$rc" -eq 0 ] && ! grep -q "ThreadSanitizer" "$tmp/err"; then
        ok "$name"
    else
        fail "$name" "exit status $rc"
        head -n 30 "$tmp/err"
    fi
}
for scene in scenes/*.mcrt tests/stiff/*.mcrt; do
    render "$scene" "$scene" --spp 2 --threads 4 -o "$tmp/out.pfm"
done
# Every integrator of the table on the caustic scene (photon mapping's chunks and gather are
# threaded differently from the per-ray integrators' tiles).
for integrator in $("$MCRT" --list integrator | cut -f1); do
    render "integrator $integrator" scenes/cornell-spheres.mcrt --integrator "$integrator" \
        --spp 2 --threads 4 -o "$tmp/out.pfm"
done
# The denoiser's NL-means and regression passes (their bands run on the same tiles runner, each
# writing its own sums; src/denoise/nfor.c), on a small film so that TSan's slowdown stays small.
sed -E "s/^film \{ *width [0-9]+ height [0-9]+/film { width 48 height 40/" scenes/cornell.mcrt \
    >"$tmp/small.mcrt"
render denoise "$tmp/small.mcrt" --spp 4 --threads 4 --denoise -o "$tmp/out.pfm"
# The command line shows no progress bar without a terminal: the progress callback's threads
# are exercised by test_tiles (2 threads, a slow callback).
if "$O/tests/test_tiles" >"$tmp/out" 2>"$tmp/err" && ! grep -q "ThreadSanitizer" "$tmp/err"; then
    ok "test_tiles"
else
    fail "test_tiles" "$(tail -n 1 "$tmp/out")"
    head -n 30 "$tmp/err"
fi
finish
