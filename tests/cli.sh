#!/bin/sh
# cli.sh: the mcrt command as a user meets it: --help and --version; bad options, numbers and
# scenes refused with one line on stderr and exit status 2, leaving existing files alone; images
# of the right size in every built-in format; --stats; the same bytes with 1 and 2 threads;
# --quiet. Run from the repository root after the build; $O is the build folder. Prints "ok ..."
# or "FAIL ...: why" per check, then "N passed, N failed"; exits 1 if any failed.
. tests/harness.sh.inc

# run ARGS...: mcrt in $tmp; stdout in $tmp/out, stderr in $tmp/err, exit status in $rc. A run
# that hangs (say, rendering what should have been refused) is stopped and fails with status 124.
limit=""
command -v timeout >/dev/null 2>&1 && limit="timeout 60"
run() {
    (cd "$tmp" && $limit "$MCRT" "$@" >out 2>err)
    rc=$?
}

# expect NAME STATUS REGEX ARGS...: mcrt exits with STATUS and prints exactly one line on stderr,
# matching the extended regular expression REGEX.
expect() {
    name=$1 status=$2 regex=$3
    shift 3
    run "$@"
    if [ "$rc" -ne "$status" ]; then
        fail "$name" "exit status $rc, expected $status; stderr: $(head -c 300 "$tmp/err")"
    elif [ "$(wc -l <"$tmp/err")" -ne 1 ] || ! grep -qE -- "$regex" "$tmp/err"; then
        fail "$name" "stderr should be one line matching /$regex/, was: $(head -c 300 "$tmp/err")"
    else
        ok "$name"
    fi
}

# The first N bytes of a file as decimal numbers separated by single spaces.
bytes() { od -An -tu1 -N"$2" "$1" | tr -s ' \n' '  ' | sed 's/^ //; s/ $//'; }

if [ ! -x "$MCRT" ]; then
    fail "mcrt built" "$O/mcrt not found (run make first)"
    echo "$passed passed, $failed failed"
    exit 1
fi

# A tiny scene, and a noisy one (area light, shadows) for determinism.
printf 'film { width 16 height 12 spp 4 }\nsphere { }\n' >"$tmp/tiny.mcrt"
cat >"$tmp/noisy.mcrt" <<'EOF'
film { width 24 height 16 spp 4 }
sphere { }
quad { corner -5 -1 -5  edge1 0 0 10  edge2 10 0 0 }
quad { corner -0.5 3 -0.5  edge1 1 0 0  edge2 0 0 1  emit 10 10 10 }
EOF
# Would take minutes to render: refusals known in advance must come before any rendering.
printf 'film { width 4000 height 4000 spp 4096 }\nsphere { }\n' >"$tmp/slow.mcrt"

# ---- help and version ----
run --help
missing=""
for o in -o --spp --threads --seed --integrator --stats --quiet --help --version "exit status"; do
    grep -qe "$o" "$tmp/out" || missing="$missing $o"
done
if [ "$rc" -eq 0 ] && [ ! -s "$tmp/err" ] && grep -q '^usage: mcrt' "$tmp/out" && [ -z "$missing" ]; then
    ok "--help: usage with every option and the exit statuses on stdout, status 0"
else
    fail "--help" "status $rc, missing:$missing"
fi
run --version
formats=$(sed -n 's/^image formats: //p' "$tmp/out")
if [ "$rc" -eq 0 ] && [ "$(head -n 1 "$tmp/out")" = "mcrt 0.1.0" ] && echo " $formats " | grep -q ' pfm '; then
    ok "--version: 'mcrt 0.1.0' and the image formats ($formats)"
else
    fail "--version" "status $rc, output: $(cat "$tmp/out")"
fi
has() { echo " $formats " | grep -q " $1 "; }

# ---- bad options ----
expect "unknown option" 2 "^mcrt: unknown option '--bogus'" --bogus tiny.mcrt
expect "unknown short option" 2 "^mcrt: unknown option '-x'" -x tiny.mcrt
expect "no scene" 2 "^mcrt: no scene file given" --spp 4
expect "two scenes" 2 "^mcrt: more than one scene" tiny.mcrt noisy.mcrt
expect "missing value" 2 "^mcrt: --spp needs a value" tiny.mcrt --spp
expect "flag given a value" 2 "^mcrt: --quiet takes no value" --quiet=1 tiny.mcrt
expect "--spp 12x" 2 "^mcrt: --spp: expected a positive integer, got '12x'$" --spp 12x tiny.mcrt
expect "--spp=12x" 2 "^mcrt: --spp: expected a positive integer, got '12x'$" --spp=12x tiny.mcrt
expect "--spp 0" 2 "^mcrt: --spp: expected a positive integer, got '0'$" --spp 0 tiny.mcrt
expect "--spp -3" 2 "^mcrt: --spp: expected a positive integer, got '-3'$" --spp -3 tiny.mcrt
expect "--spp empty" 2 "^mcrt: --spp: expected a positive integer, got ''$" --spp= tiny.mcrt
expect "--spp ' 4'" 2 "^mcrt: --spp: expected" --spp " 4" tiny.mcrt
expect "--spp overflow" 2 "^mcrt: --spp: 99999999999 is too large" --spp 99999999999 tiny.mcrt
expect "--threads x" 2 "^mcrt: --threads: expected a non-negative integer, got 'x'$" --threads x tiny.mcrt
expect "--seed -1" 2 "^mcrt: --seed: expected an integer from 0 to 18446744073709551615, got '-1'$" \
    --seed -1 tiny.mcrt
expect "--seed 2^64" 2 "^mcrt: --seed: expected an integer" --seed 18446744073709551616 tiny.mcrt
expect "--seed 0x10" 2 "^mcrt: --seed: expected an integer" --seed 0x10 tiny.mcrt
expect "--integrator foo" 2 "^mcrt: --integrator: expected path, direct, mis, bsdf, light or sppm, got 'foo'$" \
    --integrator foo tiny.mcrt

# ---- bad scenes: nothing is created or touched ----
printf 'precious' >"$tmp/keep"
printf 'film { width 16 height 12 spp 4 }\nsphere { radius oops }\n' >"$tmp/bad.mcrt"
cp "$tmp/keep" "$tmp/bad.png"
expect "malformed scene: file:line:col on stderr" 2 '^bad\.mcrt:2:[0-9]+: ' bad.mcrt
if cmp -s "$tmp/keep" "$tmp/bad.png"; then ok "malformed scene: existing output untouched"; else
    fail "malformed scene" "bad.png was changed"; fi
run bad.mcrt -o bad.pfm
if [ "$rc" -eq 2 ] && [ ! -e "$tmp/bad.pfm" ]; then ok "malformed scene: no output created"; else
    fail "malformed scene" "status $rc, bad.pfm exists: $(ls "$tmp"/bad.pfm 2>/dev/null)"; fi
expect "missing scene: file-prefixed message" 2 '^nothere\.mcrt: .*No such file or directory$' nothere.mcrt
mkdir "$tmp/sub"
expect "scene is a folder" 2 '^sub: ' sub

# ---- output problems found before rendering (the slow scene would take minutes) ----
expect "unknown image suffix, before rendering" 2 \
    "^mcrt: cannot write 'x\.jpg': unknown image format '\.jpg' \(use \.png, \.exr or \.pfm\)$" \
    slow.mcrt -o x.jpg
expect "no image suffix, before rendering" 2 "^mcrt: cannot write 'x': no image suffix" slow.mcrt -o x
expect "missing output folder, before rendering" 2 \
    "^mcrt: cannot write 'no/x\.pfm': No such file or directory$" slow.mcrt -o no/x.pfm
expect "missing --stats folder, before rendering" 2 \
    "^mcrt: cannot write 'no/s\.json': No such file or directory$" slow.mcrt -o x.pfm --stats no/s.json
for f in png exr; do
    has $f || expect "$f not built in, before rendering" 2 "built without .*and rebuild\)$" slow.mcrt -o "x.$f"
done
if [ -e "$tmp/x.jpg" ] || [ -e "$tmp/x" ] || [ -e "$tmp/x.pfm" ]; then fail "refusals" "an output file was created"; else
    ok "refusals create no file"; fi

# ---- rendering ----
run tiny.mcrt -o t.pfm
printf 'PF\n16 12\n-1.0\n' >"$tmp/header"
if [ "$rc" -eq 0 ] && head -c 14 "$tmp/t.pfm" | cmp -s - "$tmp/header" &&
    [ "$(wc -c <"$tmp/t.pfm")" -eq $((14 + 16 * 12 * 12)) ]; then
    ok "PFM: header 'PF 16 12 -1.0' and 16x12x3 floats"
else
    fail "PFM" "status $rc, $(head -c 300 "$tmp/err"), size $(wc -c <"$tmp/t.pfm" 2>/dev/null)"
fi
if [ "$(wc -l <"$tmp/err")" -eq 1 ] && grep -qE '^t\.pfm: 16x12, 4 spp, [0-9]+ threads?, [0-9.]+ s, [0-9.]+ Mrays/s, 0 NaN samples, est\. relMSE [0-9.e+-]+ \([0-9e+-]+ in [0-9.e+-]+ s\), efficiency [0-9.e+-]+$' "$tmp/err" &&
    ! grep -q "$(printf '\r')" "$tmp/err"; then
    ok "summary line on stderr, no progress bar when stderr is not a terminal"
else
    fail "summary line" "$(cat "$tmp/err")"
fi
if has png; then
    run tiny.mcrt -o t.png
    # PNG signature, then IHDR: length 13, "IHDR", width 16, height 12, depth 8, colour type 2.
    want="137 80 78 71 13 10 26 10 0 0 0 13 73 72 68 82 0 0 0 16 0 0 0 12 8 2"
    if [ "$rc" -eq 0 ] && [ "$(bytes "$tmp/t.png" 26)" = "$want" ]; then ok "PNG: 16x12 8-bit RGB"; else
        fail "PNG" "status $rc, first bytes $(bytes "$tmp/t.png" 26)"; fi
else
    skip "PNG: 16x12 8-bit RGB" "this mcrt was built without libpng"
fi
if has exr; then
    run tiny.mcrt -o t.exr
    if [ "$rc" -eq 0 ] && [ "$(bytes "$tmp/t.exr" 4)" = "118 47 49 1" ]; then ok "EXR: written"; else
        fail "EXR" "status $rc, first bytes $(bytes "$tmp/t.exr" 4)"; fi
    if ! command -v exrheader >/dev/null 2>&1; then
        skip "EXR: 16x12 per exrheader" "exrheader not installed (apt-get install openexr)"
    elif exrheader "$tmp/t.exr" | grep -q 'dataWindow.*(0 0) - (15 11)'; then ok "EXR: 16x12 per exrheader"; else
        fail "EXR" "exrheader: $(exrheader "$tmp/t.exr" 2>&1 | grep -i window)"; fi
else
    skip "EXR: written" "this mcrt was built without OpenEXR"
fi
default=tiny.png
has png || default=tiny.pfm
mkdir -p "$tmp/scenes"
cp "$tmp/tiny.mcrt" "$tmp/scenes/tiny.mcrt"
run scenes/tiny.mcrt
if [ "$rc" -eq 0 ] && [ -s "$tmp/$default" ] && grep -q "^$default: " "$tmp/err"; then
    ok "default output: $default in the current folder, named in the summary"
else
    fail "default output" "status $rc, $(cat "$tmp/err")"
fi
cp "$tmp/tiny.mcrt" "$tmp/same.${default#*.}"
expect "refuses to overwrite the scene with the image" 2 "overwrite the scene" "same.${default#*.}"
run render tiny.mcrt -o r.pfm
if [ "$rc" -eq 0 ] && cmp -s "$tmp/r.pfm" "$tmp/t.pfm"; then ok "'mcrt render SCENE' is 'mcrt SCENE'"; else
    fail "render command" "status $rc"; fi
if ls -a "$tmp" | grep -q '\.tmp-'; then fail "temporary files" "$(ls -a "$tmp")"; else
    ok "no temporary files left"; fi

# ---- --stats ----
run tiny.mcrt -o s.pfm --spp 2 --threads 1 --stats s.json
keys=""
for k in width height spp threads seconds rays nan_count; do
    grep -qE "^  \"$k\": [0-9.e+-]+,?$" "$tmp/s.json" 2>/dev/null || keys="$keys $k"
done
if [ "$rc" -eq 0 ] && [ -z "$keys" ] && grep -q '"width": 16,' "$tmp/s.json" &&
    grep -q '"height": 12,' "$tmp/s.json" && grep -q '"spp": 2,' "$tmp/s.json" &&
    grep -q '"threads": 1,' "$tmp/s.json"; then
    ok "--stats: JSON with width 16, height 12, spp 2 (overridden), threads 1, seconds, rays, nan_count"
else
    fail "--stats" "status $rc, keys missing:$keys; $(cat "$tmp/s.json" 2>/dev/null)"
fi
# A pipe (like --stats /dev/stdout) is written in place, not replaced by a renamed file.
if mkfifo "$tmp/pipe" 2>/dev/null; then
    cat "$tmp/pipe" >"$tmp/piped" &
    reader=$!
    run tiny.mcrt -o p.pfm --spp 1 --stats pipe
    # The reader ends at the writer's end of file; if mcrt never wrote through the pipe (it failed,
    # or renamed a file over it), nothing will, so stop the reader instead of waiting forever.
    if [ "$rc" -eq 0 ] && [ -p "$tmp/pipe" ]; then wait "$reader"; else kill "$reader"; fi
    if [ "$rc" -eq 0 ] && [ -p "$tmp/pipe" ] && grep -q '"nan_count": 0,' "$tmp/piped"; then
        ok "--stats to a pipe: written through it, the pipe is still a pipe"
    else
        fail "--stats to a pipe" "status $rc; $(ls -l "$tmp/pipe" 2>&1); $(cat "$tmp/piped")"
    fi
else
    skip "--stats to a pipe" "mkfifo cannot make a pipe in $tmp"
fi
# A symbolic link (like /dev/stdout -> /proc/self/fd/1 with the output redirected to a file) is
# written through, for the statistics and for images: renaming over it would replace the link.
printf 'old' >"$tmp/linked.json"
printf 'old' >"$tmp/linked.pfm"
ln -s linked.json "$tmp/link.json" && ln -s linked.pfm "$tmp/link.pfm"
run tiny.mcrt -o link.pfm --spp 1 --stats link.json
if [ "$rc" -eq 0 ] && [ -L "$tmp/link.json" ] && [ -L "$tmp/link.pfm" ] &&
    grep -q '"nan_count": 0,' "$tmp/linked.json" && [ "$(head -c 2 "$tmp/linked.pfm")" = PF ]; then
    ok "--stats and -o to symbolic links: written through them, the links stay links"
else
    fail "--stats and -o to symbolic links" "status $rc; $(ls -l "$tmp"/link* 2>&1)"
fi
if ! command -v python3 >/dev/null 2>&1; then
    skip "--stats: valid JSON (python3)" "python3 not installed"
elif python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); assert d["rays"] > 0' "$tmp/s.json"; then
    ok "--stats: valid JSON (python3), rays > 0"
else
    fail "--stats" "python3 could not load it"
fi

# ---- determinism: the image is a function of scene, options and seed only ----
run noisy.mcrt -o a.pfm --threads 1 --seed 7
rc1=$rc
run noisy.mcrt -o b.pfm --threads 2 --seed 7
if [ "$rc1" -eq 0 ] && [ "$rc" -eq 0 ] && cmp -s "$tmp/a.pfm" "$tmp/b.pfm"; then
    ok "--threads 1 and --threads 2 give the same bytes"
else
    fail "determinism" "status $rc1/$rc, files differ: $(cmp "$tmp/a.pfm" "$tmp/b.pfm" 2>&1)"
fi
run noisy.mcrt -o c.pfm --threads 2 --seed 8
if [ "$rc" -eq 0 ] && ! cmp -s "$tmp/a.pfm" "$tmp/c.pfm"; then ok "another seed gives another image"; else
    fail "seed" "status $rc; --seed 8 gave the same bytes as --seed 7"; fi
# Adaptive passes: the counts come from the image so far, which is itself thread-independent.
run noisy.mcrt -o d.pfm --threads 1 --seed 7 --spp 16 --adaptive --sampler sobol
rc1=$rc
run noisy.mcrt -o e.pfm --threads 2 --seed 7 --spp 16 --adaptive --sampler sobol
if [ "$rc1" -eq 0 ] && [ "$rc" -eq 0 ] && cmp -s "$tmp/d.pfm" "$tmp/e.pfm" &&
    grep -qE ', [0-9]+ passes, adaptive \([0-9]+ to [0-9]+ spp\)$' "$tmp/err"; then
    ok "--adaptive --sampler sobol: the same bytes with 1 and 2 threads; $(grep -oE 'adaptive .*' "$tmp/err")"
else
    fail "adaptive determinism" "status $rc1/$rc: $(cat "$tmp/err"); $(cmp "$tmp/d.pfm" "$tmp/e.pfm" 2>&1)"
fi
expect "--sampler x" 2 "^mcrt: --sampler: expected random, stratified or sobol, got 'x'$" --sampler x tiny.mcrt

# ---- --quiet ----
run tiny.mcrt -o q.pfm --quiet
if [ "$rc" -eq 0 ] && [ ! -s "$tmp/out" ] && [ ! -s "$tmp/err" ] && [ -s "$tmp/q.pfm" ]; then
    ok "--quiet: nothing printed on success"
else
    fail "--quiet" "status $rc, printed: $(cat "$tmp/out" "$tmp/err")"
fi

# ---- the progress bar, on a terminal (script(1) provides one, where installed) ----
if command -v script >/dev/null 2>&1 && script -qec true /dev/null >/dev/null 2>&1; then
    (cd "$tmp" && script -qec "'$MCRT' noisy.mcrt -o p.pfm" /dev/null >tty.txt 2>&1)
    (cd "$tmp" && script -qec "'$MCRT' noisy.mcrt -o p.pfm --quiet" /dev/null >quiet.txt 2>&1)
    cr=$(printf '\r')
    # Any elapsed time: under load (the tests run in parallel) the tiny render may pass 0:00.
    if grep -q "${cr}\[#*  *\]  *[0-9]*%  [0-9]*:[0-9][0-9] elapsed" "$tmp/tty.txt" && grep -q '100%' "$tmp/tty.txt"; then
        ok "progress bar on a terminal"
    else
        fail "progress bar" "$(od -c "$tmp/tty.txt" | head -5)"
    fi
    if [ ! -s "$tmp/quiet.txt" ]; then ok "--quiet: no progress bar on a terminal"; else
        fail "--quiet on a terminal" "$(od -c "$tmp/quiet.txt" | head -5)"; fi
else
    for check in "progress bar on a terminal" "--quiet: no progress bar on a terminal"; do
        skip "$check" "script(1) is not installed or cannot make a terminal here"
    done
fi

# ---- environment maps (man/mcrt.5): a bad pixel or a missing file refused at load time, exit 2;
# a constant map of 1 is the white furnace: a white diffuse sphere (albedo 1) reflects 1, every
# pixel 1 in expectation. The image's mean error has a standard error sqrt(MSE/pixels) = 4.3e-4
# at 64 spp (MSE 7e-5 over 384 pixels, measured), so the bias may be at most 0.002 (4.6 of them).
gen="$O/tests/envmap_gen"
"$gen" nan 4 2 "$tmp/nan.pfm" && "$gen" constant 16 8 "$tmp/one_map.pfm" \
    && "$gen" constant 24 16 "$tmp/ones.pfm"
printf 'environment { map "nan.pfm" }\n' >"$tmp/nanmap.mcrt"
printf 'environment { map "absent.pfm" }\n' >"$tmp/absent.mcrt"
expect "environment map with a NaN pixel" 2 "nan.pfm: pixel \(1, 0\) has a NaN value" nanmap.mcrt -o e.pfm
expect "missing environment map" 2 "absent.pfm" absent.mcrt -o e.pfm
printf '%s\n' 'film { width 24 height 16 spp 64 }' 'material white { diffuse 1 }' \
    'sphere { material white }' 'environment { map "one_map.pfm" }' >"$tmp/furnace_map.mcrt"
run furnace_map.mcrt -o fm.pfm --quiet
if [ "$rc" -eq 0 ] && (cd "$tmp" && "$MCRT" diff fm.pfm ones.pfm --max-bias 0.002 >diff.txt 2>&1); then
    ok "constant environment map: white furnace ($(sed -n 's/.*\(bias [^ ]*\).*/\1/p' "$tmp/diff.txt"))"
else
    fail "constant environment map: white furnace" "status $rc: $(cat "$tmp/err" "$tmp/diff.txt")"
fi

# ---- OBJ materials (man/mcrt.5): a bad MTL file is one file:line:col line and exit 2, the output
# untouched; a statement mcrt ignores is one warning on stderr (none with --quiet), the render
# going on.
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nmtllib tri.mtl\nusemtl a\nf 1 2 3\n' >"$tmp/tri.obj"
printf 'camera { eye 0.3 0.3 2 look 0.3 0.3 0 }\nfilm { width 8 height 8 spp 1 }\nmesh { file "tri.obj" }\n' \
    >"$tmp/tri.mcrt"
printf 'newmtl a\nKd 0.5\nNs x\n' >"$tmp/tri.mtl"
printf 'keep' >"$tmp/kept.pfm"
expect "malformed MTL file" 2 "^\./tri\.mtl:3:4: malformed number 'x'$" tri.mcrt -o kept.pfm
if [ "$(cat "$tmp/kept.pfm")" = keep ]; then ok "malformed MTL file: output untouched"; else
    fail "malformed MTL file: output untouched" "it changed"; fi
printf 'newmtl a\nKd 0.5\nmap_Ks spec.png\nmap_Ks spec2.png\n' >"$tmp/tri.mtl"
run tri.mcrt -o tri.pfm
if [ "$rc" -eq 0 ] && [ "$(grep -c warning "$tmp/err")" -eq 1 ] &&
    grep -q "^\./tri\.mtl:3:1: warning: 'map_Ks' is ignored" "$tmp/err"; then
    ok "ignored MTL statement: one warning, the render done"
else
    fail "ignored MTL statement: one warning, the render done" "status $rc: $(cat "$tmp/err")"
fi
run tri.mcrt -o tri.pfm --quiet
if [ "$rc" -eq 0 ] && [ ! -s "$tmp/err" ]; then ok "--quiet: no warnings"; else
    fail "--quiet: no warnings" "status $rc: $(cat "$tmp/err")"; fi

finish
