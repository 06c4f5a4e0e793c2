#!/bin/sh
# farm.sh: render states, --resume and mcrt merge (mcrt(1), RENDER FARMS): a resumed render is
# byte-identical to one render of the same passes; crops assemble into the whole image byte for
# byte; renders of other pass ranges merge into the samples of one render, the error estimate
# included; bad inputs are refused with "file: what is wrong", exit 2, and leave the output
# alone. Run from the repository root after the build; $O is the build folder. Prints "ok ..." or
# "FAIL ...: why" per check, then "N passed, N failed[, N skipped]"; exits 1 if any failed.
. tests/harness.sh.inc

if ! "$MCRT" --version | grep -q ' exr'; then
    skip "render states" "this mcrt was built without OpenEXR (libopenexr-dev)"
    finish
    exit
fi

printf 'film { width 32 height 24 spp 2 }\ncamera { eye 0 3 6  look 0 0.5 0  fov 40 }\n%s\n%s\n%s\n' \
    'quad { corner -4 0 4  edge1 8 0 0  edge2 0 0 -8 }' 'sphere { center 0 0.7 0  radius 0.7 }' \
    'quad { corner -0.5 3 -0.5  edge1 1 0 0  edge2 0 0 1  emit 20 }' >"$tmp/s.mcrt"
run() { "$MCRT" --quiet --seed 3 "$@" "$tmp/s.mcrt"; }
# est. relMSE as mcrt merge prints it (6 digits).
est() { sed -n 's/.*est\. relMSE \([0-9.e+-]*\).*/\1/p' "$1"; }

run --passes 4 --state -o "$tmp/full.exr"
for sampler in stratified random; do
    run --passes 4 --state --sampler $sampler -o "$tmp/full_$sampler.exr"
    run --passes 1 --state --sampler $sampler -o "$tmp/one.exr"
    run --resume "$tmp/one.exr" --passes 2 --sampler $sampler --state -o "$tmp/two.exr"
    run --resume "$tmp/two.exr" --passes 4 --sampler $sampler --state -o "$tmp/four.exr"
    if cmp -s "$tmp/four.exr" "$tmp/full_$sampler.exr"; then
        ok "--resume 1 + 1 + 2 passes ($sampler) is byte-identical to a 4-pass render"
    else
        fail "--resume ($sampler)" "the EXRs differ"
    fi
done

# --time writes the state too; resuming it with --passes continues its passes.
run --time 0.2 -o "$tmp/t.exr" 2>"$tmp/err"
if run --resume "$tmp/t.exr" --time 0.1 -o "$tmp/t2.exr" 2>"$tmp/err"; then
    ok "a --time render's EXR carries a state that --resume continues"
else
    fail "--time state" "$(cat "$tmp/err")"
fi

# Stopped by Ctrl-C and continued: the passes the state says it holds, plus 5 more, are the
# render of them all in one go.
"$MCRT" --seed 3 --time 60 -o "$tmp/int.exr" "$tmp/s.mcrt" 2>"$tmp/err" &
pid=$!
sleep 1
kill -INT $pid
wait $pid
held=$(sed -n 's/.*with the \([0-9]*\) complete pass.*/\1/p' "$tmp/err")
if [ -n "$held" ] && run --resume "$tmp/int.exr" --passes $((held + 5)) --state -o "$tmp/r.exr" &&
    run --passes $((held + 5)) --state -o "$tmp/d.exr" && cmp -s "$tmp/r.exr" "$tmp/d.exr"; then
    ok "Ctrl-C after $held passes, --resume to $((held + 5)): byte-identical to one render"
else
    fail "Ctrl-C and --resume" "$(cat "$tmp/err")"
fi

# Refusals: another seed, spp, scene; too few passes; a state that is not there.
check_refusal() { # name, expected message part, command...
    name=$1 want=$2
    shift 2
    echo keep >"$tmp/keep.exr"
    "$@" -o "$tmp/keep.exr" 2>"$tmp/err"
    rc=$?
    if [ "$rc" -eq 2 ] && grep -q "$want" "$tmp/err" && [ "$(cat "$tmp/keep.exr")" = keep ]; then
        ok "$name: exit 2, '$(head -1 "$tmp/err")', output untouched"
    else
        fail "$name" "exit $rc: $(cat "$tmp/err")"
    fi
}
run --passes 2 --state -o "$tmp/half.exr"
check_refusal "--resume with another seed" "half.exr: cannot resume: another --seed" \
    "$MCRT" --resume "$tmp/half.exr" --passes 4 --seed 4 "$tmp/s.mcrt"
check_refusal "--resume with another spp" "half.exr: cannot resume: another --spp" \
    run --resume "$tmp/half.exr" --passes 4 --spp 4
check_refusal "--resume with fewer passes" "half.exr: cannot resume: more passes" \
    run --resume "$tmp/half.exr" --passes 2
sed 's/radius 0.7/radius 0.6/' "$tmp/s.mcrt" >"$tmp/other.mcrt"
check_refusal "--resume of another scene" "half.exr: cannot resume: a render of another scene" \
    "$MCRT" --resume "$tmp/half.exr" --passes 4 --seed 3 "$tmp/other.mcrt"
# The hash covers the files the scene reads: the same text with an edited mesh is another scene.
mkdir "$tmp/m"
printf 'v -1 0 -1\nv 1 0 -1\nv 0 1.5 -1\nf 1 2 3\n' >"$tmp/m/tri.obj"
{ cat "$tmp/s.mcrt"; echo 'mesh { file "tri.obj" }'; } >"$tmp/m/s.mcrt"
"$MCRT" --quiet --seed 3 --passes 2 --state -o "$tmp/mesh.exr" "$tmp/m/s.mcrt"
printf 'v -1 0 -1\nv 1 0 -1\nv 0 1.4 -1\nf 1 2 3\n' >"$tmp/m/tri.obj"
check_refusal "--resume with the scene's OBJ file edited" \
    "mesh.exr: cannot resume: a render of another scene" \
    "$MCRT" --resume "$tmp/mesh.exr" --passes 4 --seed 3 "$tmp/m/s.mcrt"
run --passes 2 -o "$tmp/plain.exr"
check_refusal "--resume of an EXR without a state" "plain.exr.*no render state" \
    run --resume "$tmp/plain.exr" --passes 4

# Crops that tile the image assemble into it, byte for byte (the state included).
run --passes 4 --state --crop 0,0,20,10 -o "$tmp/c1.exr"
run --passes 4 --state --crop 20,0,32,10 -o "$tmp/c2.exr"
run --passes 4 --state --crop 0,10,32,24 -o "$tmp/c3.exr"
if "$MCRT" merge --quiet "$tmp/c2.exr" "$tmp/c1.exr" "$tmp/c3.exr" -o "$tmp/tiled.exr" &&
    cmp -s "$tmp/tiled.exr" "$tmp/full.exr"; then
    ok "mcrt merge of three crops is byte-identical to the whole render"
else
    fail "mcrt merge of crops" "differs from the whole render"
fi

# Passes 0-1 and 2-3 merge into the samples of the 4-pass render: the image differs only by
# rounding (Chan's update groups the sums otherwise), and so does the error estimate, whose
# 6 printed digits must agree (the sampler's halves and the random sampler's pooled variance).
for sampler in stratified random; do
    run --passes 2 --state --sampler $sampler -o "$tmp/a.exr"
    run --passes 2 --first-pass 2 --state --sampler $sampler -o "$tmp/b.exr"
    "$MCRT" merge "$tmp/a.exr" "$tmp/b.exr" -o "$tmp/m.exr" 2>"$tmp/merged"
    "$MCRT" merge "$tmp/full_$sampler.exr" -o "$tmp/m1.exr" 2>"$tmp/single"
    max=$("$MCRT" diff "$tmp/m.exr" "$tmp/full_$sampler.exr" | sed -n 's/^whole image:.*max error \([^,]*\),.*/\1/p')
    if [ -n "$(est "$tmp/merged")" ] && [ "$(est "$tmp/merged")" = "$(est "$tmp/single")" ] &&
        echo "$max" | awk '{ exit !($1 < 1e-5) }'; then
        ok "merge of passes 0-1 and 2-3 ($sampler): est. relMSE $(est "$tmp/merged") as the 4-pass render's, max pixel difference $max"
    else
        fail "merge of pass ranges ($sampler)" "est. $(est "$tmp/merged") vs $(est "$tmp/single"), max error $max"
    fi
done

# Other seeds: twice the samples; the estimate of the merge is that of its pooled samples, near
# half of each input's (at 8 spp the estimate's own noise is a few per cent: 40% is far outside).
run --passes 4 --state -o "$tmp/s3.exr"
"$MCRT" --quiet --seed 9 --passes 4 --state -o "$tmp/s9.exr" "$tmp/s.mcrt"
"$MCRT" merge "$tmp/s3.exr" "$tmp/s9.exr" -o "$tmp/seeds.exr" 2>"$tmp/merged"
"$MCRT" merge "$tmp/s3.exr" -o "$tmp/x.exr" 2>"$tmp/a"
"$MCRT" merge "$tmp/s9.exr" -o "$tmp/x.exr" 2>"$tmp/b"
if awk -v m="$(est "$tmp/merged")" -v a="$(est "$tmp/a")" -v b="$(est "$tmp/b")" \
    'BEGIN { r = m / ((a + b) / 4); exit !(r > 0.6 && r < 1.4) }'; then
    ok "merge of seeds 3 and 9: est. relMSE $(est "$tmp/merged") against $(est "$tmp/a") and $(est "$tmp/b") alone"
else
    fail "merge of seeds" "est. $(est "$tmp/merged") against $(est "$tmp/a"), $(est "$tmp/b")"
fi
check_refusal "--resume of a merge of seeds" "cannot resume: a merge" \
    run --resume "$tmp/seeds.exr" --passes 9

# Bad inputs to merge.
merge_refusal() { # name, expected message, inputs...
    name=$1 want=$2
    shift 2
    check_refusal "$name" "$want" "$MCRT" merge "$@"
}
"$MCRT" --quiet --passes 2 --state -o "$tmp/o.exr" "$tmp/other.mcrt"
merge_refusal "merge of another scene" "o.exr: a render of another scene than .*half.exr" \
    "$tmp/half.exr" "$tmp/o.exr"
run --passes 2 --state --spp 3 -o "$tmp/spp3.exr"
merge_refusal "merge of other options" "spp3.exr: another --spp than" "$tmp/half.exr" "$tmp/spp3.exr"
run --passes 4 --state --crop 10,0,32,10 -o "$tmp/c4.exr"
merge_refusal "merge of overlapping crops" "c4.exr: its crop 10,0,32,10 overlaps the crop 0,0,20,10" \
    "$tmp/c1.exr" "$tmp/c4.exr" "$tmp/c3.exr"
merge_refusal "merge of crops with a gap" "the crops leave pixels" "$tmp/c1.exr" "$tmp/c3.exr"
size=$(wc -c <"$tmp/half.exr")
head -c $((size - 100)) "$tmp/half.exr" >"$tmp/cut.exr"
merge_refusal "merge of a truncated EXR" "cut.exr" "$tmp/half.exr" "$tmp/cut.exr"
merge_refusal "merge of an EXR without a state" "plain.exr.*no render state" "$tmp/plain.exr"
finish
