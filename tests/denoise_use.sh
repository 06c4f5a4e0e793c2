#!/bin/sh
# denoise_use.sh: --denoise beside the rest of mcrt (issue 16), on a 48x48 Cornell box:
#   - `mcrt converge --compare denoise=off,on`: one CSV row per (value, rung) in the denoise
#     column; the "on" rows are the denoised renders (their est_relmse is what `mcrt --denoise
#     --stats` gives for the rung's seed, to the CSV's 6 digits), their true relMSE is below the
#     raw rows' at every rung (measured 1.4 to 4 times below at 4 and 16 spp, seeds 0, 5, 9);
#     the reference is a raw render (a denoised one would carry the denoiser's bias into both
#     curves); the plot's script selects exactly each value's rows; a value other than off or on
#     is refused with exit status 2.
#   - --denoise with every sampler, every per-ray integrator, with --crop (against the reference's same crop), with
#     --passes, with --time and with --adaptive: the denoised image's relMSE against the
#     converge test's reference (256 spp, another seed) is below the raw image's, its mean
#     within 1% of the raw's (the issue's energy target) or, where the raw mean's own noise is
#     larger (bsdf sampling's fireflies: 3 standard errors of it were 1.7% of the mean, and the
#     shift measured 1.4, 1.1, -0.1, -1.3% for seeds 1 to 4, of both signs), within 3 standard
#     errors of it, and its est_relmse below the raw's (with --adaptive below the raw image's
#     true relMSE: there the raw estimate reads low, about 0.8 of the truth, as adaptive
#     sampling gives fewer samples to the pixels whose error came out low (render/adaptive.c),
#     where the denoised estimate, 0.6 to 1.5 of its truth, need not be below it);
#     the raw layer of the --passes render is the image of the same render without --denoise,
#     and `mcrt denoise` of the --time render's EXR (which holds the render state too) gives its
#     image again.
#   - Refused, with exit status 2 and the output untouched: --resume with --denoise (the state
#     keeps the film, not the features of the passes before) and --integrator sppm, whose halves
#     are not independent (api.c).
. tests/harness.sh.inc
. tests/outputs.sh.inc

film_size scenes/cornell.mcrt 48 48 >"$tmp/c.mcrt"

# csv_field VALUE SPP COLUMN: COLUMN (1-based) of the CSV row of denoise=VALUE at SPP.
csv_field() {
    awk -F, -v d="$1" -v s="$2" -v c="$3" '$3 == d && $4 == s { print $c }' "$tmp/c-converge.csv"
}
if "$MCRT" converge --quiet --spp 4,16 --compare denoise=off,on -o "$tmp" "$tmp/c.mcrt"; then
    rows=$(grep -c '^scene,scene,\(off\|on\),\(4\|16\),' "$tmp/c-converge.csv")
    "$MCRT" --quiet --spp 16 --seed 1 --denoise -o "$tmp/d.pfm" --stats "$tmp/d.json" "$tmp/c.mcrt"
    want=$(printf '%.6g' "$(json_num "$tmp/d.json" est_relmse)")
    got=$(csv_field on 16 8)
    if [ "$rows" -eq 4 ] && [ "$got" = "$want" ] &&
        head -1 "$tmp/c-converge.csv" | grep -q '^# reference: a render of 256 spp'; then
        ok "converge denoise=off,on: 4 rows, the 'on' rows denoised (est. relMSE $got at 16 spp)"
    else
        fail "converge denoise=off,on" "$rows rows, 'on' at 16 spp est. $got, --denoise gives $want: $(cat "$tmp/c-converge.csv")"
    fi
    for spp in 4 16; do
        off=$(csv_field off $spp 7)
        on=$(csv_field on $spp 7)
        if echo "$on $off" | awk '{ exit !($1 < $2) }'; then
            ok "converge, $spp spp: denoised relMSE $on below the raw $off"
        else
            fail "converge, $spp spp" "denoised relMSE $on not below the raw $off"
        fi
    done
    # The plot's data sources: each "< command" of the script, run, gives its value's rows.
    sed -n "s/^.*'< \\(.*\\)' using.*/\\1/p" "$tmp/c-converge.gp" >"$tmp/sources"
    i=0
    for value in off on; do
        i=$((i + 1))
        sh -c "$(sed -n "${i}p" "$tmp/sources")" >"$tmp/rows"
        if [ "$(wc -l <"$tmp/rows")" -eq 2 ] && [ "$(cut -d, -f3 "$tmp/rows" | sort -u)" = "$value" ]; then
            ok "converge plot: the '$value' curve reads its 2 rows"
        else
            fail "converge plot" "the '$value' curve reads: $(cat "$tmp/rows")"
        fi
    done
    check_plot "converge denoise plot" "$tmp/c-converge.png"
else
    fail "converge denoise=off,on" "exit status $?"
fi
"$MCRT" converge --quiet --spp 2 --compare denoise=off,maybe -o "$tmp" "$tmp/c.mcrt" 2>"$tmp/err"
code=$?
if [ "$code" -eq 2 ] && grep -q "denoise takes off or on, not 'maybe'" "$tmp/err"; then
    ok "converge denoise=maybe: exit 2, '$(cat "$tmp/err")'"
else
    fail "converge denoise=maybe" "exit $code, '$(cat "$tmp/err")'"
fi

# mode NAME OPTIONS...: render at seed 1 with --denoise, and the same without into raw.exr (with
# its variance layer), and check the claims above against $tmp/c-ref.pfm (or $ref when set).
mode() {
    name=$1
    shift
    "$MCRT" --quiet --seed 1 --denoise -o "$tmp/m.exr" --stats "$tmp/m.json" "$@" "$tmp/c.mcrt" &&
        "$MCRT" --quiet --seed 1 --aov variance -o "$tmp/raw.exr" "$@" "$tmp/c.mcrt" &&
        layer "$tmp/raw.exr" variance "$tmp/var.pfm" || {
        fail "$name" "a render failed"
        return
    }
    r=${ref:-$tmp/c-ref.pfm}
    set -- "$(diff_num relMSE "$tmp/m.exr" "$r")" "$(diff_num relMSE "$tmp/raw.exr" "$r")" \
        "$(diff_num bias "$tmp/m.exr" "$tmp/raw.exr")" "$(diff_num bias "$tmp/raw.exr" "$tmp/black.pfm")" \
        "$(json_num "$tmp/m.json" est_relmse)" "$(json_num "$tmp/m.json" est_relmse_raw)" \
        "$(diff_num bias "$tmp/var.pfm" "$tmp/black.pfm")"
    # The shift allowed: 1% of the mean, or 3 standard errors of the raw image's mean when that
    # is larger (its pixels independent: sqrt(mean variance / (pixels x 3 channels))).
    tol=$(echo "$4 $7 $W $H" | awk '{ e = 3 * sqrt($2 / ($3 * $4 * 3)); print (e > 0.01 * $1 ? e : 0.01 * $1) }')
    # The estimate's bound: the raw image's estimate, or ($est_bound = true) its true relMSE.
    bound=$6
    [ "${est_bound:-}" = true ] && bound=$2
    if echo "$@ $tol $bound" | awk '{ exit !($1 < $2 && $3 < $8 && -$3 < $8 && $5 < $9) }'; then
        ok "$name: denoised relMSE $1 < raw $2, mean shift $3 of $4 (at most $tol), est. $5 < $bound (raw est. $6)"
    else
        fail "$name" "denoised relMSE $1 vs raw $2, mean shift $3 of $4 (at most $tol), est. $5 vs $bound (raw est. $6)"
    fi
}
# black W H: $tmp/black.pfm, a black W x H image, to read an image's mean as its bias against
# it; W and H the size of the renders that follow.
black() {
    W=$1 H=$2
    printf 'PF\n%d %d\n-1.0\n' "$W" "$H" >"$tmp/black.pfm"
    head -c $((W * H * 12)) /dev/zero >>"$tmp/black.pfm"
}
# layer EXR NAME OUT: the layer NAME of EXR, a W x H image, as the image OUT (tests/tools/crops.c).
layer() { "$O/tests/crops" "$3" "0,0,$W,$H" 1 "$1:$2"; }
black 48 48
for sampler in $("$MCRT" --list sampler); do
    mode "--denoise --sampler $sampler" --spp 16 --sampler "$sampler"
done
# Every per-ray integrator (sppm is refused, below); direct's bias (no indirect light) is in the
# raw and the denoised relMSE alike.
for integrator in $("$MCRT" --list integrator | cut -f 1 | grep -vx sppm); do
    mode "--denoise --integrator $integrator" --spp 16 --integrator "$integrator"
done
mode "--denoise --passes 4" --spp 4 --passes 4
if layer "$tmp/m.exr" raw "$tmp/m-raw.pfm" &&
    [ "$(diff_num MSE "$tmp/m-raw.pfm" "$tmp/raw.exr")" = 0 ]; then
    ok "--denoise --passes 4: its raw layer is the render without --denoise"
else
    fail "--denoise --passes 4" "its raw layer differs from the render without --denoise"
fi
est_bound=true mode "--denoise --adaptive" --spp 16 --adaptive
# --time: the passes' count depends on the machine's speed, so the raw image is the EXR's own.
if "$MCRT" --quiet --seed 1 --denoise --spp 4 --time 1 -o "$tmp/t.exr" "$tmp/c.mcrt" &&
    layer "$tmp/t.exr" raw "$tmp/t-raw.pfm" &&
    "$MCRT" denoise --quiet "$tmp/t.exr" -o "$tmp/t2.exr"; then
    den=$(diff_num relMSE "$tmp/t.exr" "$tmp/c-ref.pfm")
    raw=$(diff_num relMSE "$tmp/t-raw.pfm" "$tmp/c-ref.pfm")
    if echo "$den $raw" | awk '{ exit !($1 < $2) }' &&
        [ "$(diff_num MSE "$tmp/t2.exr" "$tmp/t.exr")" = 0 ]; then
        ok "--denoise --time 1: denoised relMSE $den < raw $raw, mcrt denoise gives it again"
    else
        fail "--denoise --time 1" "denoised relMSE $den, raw $raw, or mcrt denoise differs"
    fi
    if ! command -v exrheader >/dev/null 2>&1; then
        skip "--denoise --time 1: state" "exrheader (OpenEXR's tools) not installed"
    elif exrheader "$tmp/t.exr" | grep -q 'mcrtState\.00'; then
        ok "--denoise --time 1: the EXR keeps the render state"
    else
        fail "--denoise --time 1" "the EXR has no render state"
    fi
else
    fail "--denoise --time 1" "a render or mcrt denoise failed"
fi
# --crop: against the reference's own crop (the same pixels as in the whole image).
"$MCRT" --quiet --spp 256 --seed 1000003 --crop 8,12,40,36 -o "$tmp/ref-crop.pfm" "$tmp/c.mcrt"
black 32 24
ref=$tmp/ref-crop.pfm mode "--denoise --crop 8,12,40,36" --spp 16 --crop 8,12,40,36

# refused NAME WANT OPTIONS...: exit 2, the message WANT, the output untouched.
refused() {
    name=$1
    want=$2
    shift 2
    echo keep >"$tmp/out.exr"
    "$MCRT" --quiet --denoise -o "$tmp/out.exr" "$@" "$tmp/c.mcrt" 2>"$tmp/err"
    code=$?
    if [ "$code" -eq 2 ] && grep -q "$want" "$tmp/err" && [ "$(cat "$tmp/out.exr")" = keep ]; then
        ok "$name: exit 2, '$(cat "$tmp/err")'"
    else
        fail "$name" "exit $code, '$(cat "$tmp/err")', output $(head -c 20 "$tmp/out.exr")"
    fi
}
"$MCRT" --quiet --spp 2 --passes 2 --state -o "$tmp/p.exr" "$tmp/c.mcrt"
refused "--denoise --resume" "which the denoiser needs" --spp 2 --passes 4 --resume "$tmp/p.exr"
refused "--denoise --integrator sppm" "no independent half images" --spp 2 --integrator sppm

finish
