#!/bin/sh
# denoise_use.sh: --denoise beside the rest of mcrt (issue 16), on a 48x48 Cornell box:
#   - `mcrt converge --compare denoise=off,on`: one CSV row per (value, rung) in the denoise
#     column; the "on" rows are the denoised renders (their est_relmse is what `mcrt --denoise
#     --stats` gives for the rung's seed, to the CSV's 6 digits), their true relMSE is below the
#     raw rows' at every rung (measured 1.4 to 4 times below at 4 and 16 spp, seeds 0, 5, 9);
#     the reference is a raw render (a denoised one would carry the denoiser's bias into both
#     curves); the plot's script selects exactly each value's rows; a value other than off or on
#     is refused with exit status 2.
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

finish
