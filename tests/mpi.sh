#!/bin/sh
# mpi.sh: mcrt-mpi across processes of one machine (mpirun --oversubscribe), with each schedule
# of its table (the names mcrt-mpi --help lists): three ranks make the image of one process byte
# for byte (the EXR with its state), whichever rank renders which pass, and the passes each rank
# rendered add up; --target-error stops the ranks at the pass one process stops at; and a rank
# that cannot read the scene's mesh ends the job with its message on rank 0, exit 2, the output
# untouched. An unknown schedule is refused. Skipped when mcrt-mpi was not built (no MPI) or
# mpirun is missing. Prints "ok ..." or "FAIL ...: why" per check, then
# "N passed, N failed[, N skipped]"; exits 1 if any failed.
. tests/harness.sh.inc

MPI=$(dirname "$MCRT")/mcrt-mpi
if [ ! -x "$MPI" ] || ! command -v mpirun >/dev/null 2>&1; then
    for c in "3 ranks equal one process" "--target-error across ranks" "a failing rank" \
        "an unknown schedule"; do
        skip "$c" "mcrt-mpi or mpirun missing (install libopenmpi-dev openmpi-bin, rebuild)"
    done
    finish
    exit
fi
if ! "$MCRT" --version | grep -q ' exr'; then
    skip "mcrt-mpi" "this mcrt was built without OpenEXR (libopenexr-dev)"
    finish
    exit
fi
# OpenMPI refuses root without these; they change nothing else.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mpi() { timeout 300 mpirun --oversubscribe "$@"; }
# Under make check, LeakSanitizer finds OpenMPI's own allocations (in its plugins, unloaded and so
# unnamed) when mcrt-mpi leaves early (--help, a bad option, a failing rank); it then exits with its
# own status before stdio is flushed, so --help would print nothing and exit 2 would read 1. Those
# runs go without leak checks; the renders below keep checking mcrt-mpi's own memory.
no_leak_check() { ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0 "$@"; }

printf 'v -1 0 -1\nv 1 0 -1\nv 0 1.5 -1\nf 1 2 3\n' >"$tmp/tri.obj"
printf 'film { width 32 height 24 spp 2 }\ncamera { eye 0 3 6  look 0 0.5 0  fov 40 }\n%s\n%s\n%s\n%s\n' \
    'quad { corner -4 0 4  edge1 8 0 0  edge2 0 0 -8 }' 'sphere { center 0 0.7 0  radius 0.7 }' \
    'quad { corner -0.5 3 -0.5  edge1 1 0 0  edge2 0 0 1  emit 20 }' 'mesh { file "tri.obj" }' \
    >"$tmp/s.mcrt"
cd "$tmp" || exit 1

"$MCRT" --quiet --seed 5 --passes 7 --state -o "$tmp/one.exr" s.mcrt
"$MCRT" --quiet --seed 5 --target-error 0.005 -o "$tmp/ot.exr" s.mcrt
mkdir "$tmp/elsewhere" # rank 2 runs there, without the mesh: as a machine whose file system lacks it
echo keep >"$tmp/keep.exr"
schedules=$(no_leak_check "$MPI" --help | sed -n 's/^      \([a-z]*\)  .*/\1/p')
[ -n "$schedules" ] || fail "mcrt-mpi --help lists no schedule"
for s in $schedules; do
    mpi -np 3 "$MPI" --schedule "$s" --threads 1 --seed 5 --passes 7 --state -o "$tmp/mpi.exr" \
        s.mcrt 2>"$tmp/err"
    # The passes each rank rendered, from "7 passes on 3 ranks (3+2+2, static)".
    by_rank=$(sed -n 's/.* 7 passes on 3 ranks (\([0-9+]*\), .*/\1/p' "$tmp/err")
    if cmp -s "$tmp/mpi.exr" "$tmp/one.exr" && [ -n "$by_rank" ] && [ $(($by_rank)) -eq 7 ]; then
        ok "--schedule $s, mpirun -np 3, 7 passes ($by_rank): byte-identical to one process (image and state)"
    else
        fail "--schedule $s, mpirun -np 3" "differs from one process: $(cat "$tmp/err")"
    fi

    mpi -np 3 "$MPI" --schedule "$s" --threads 1 --seed 5 --target-error 0.005 -o "$tmp/mt.exr" \
        s.mcrt 2>"$tmp/err"
    if cmp -s "$tmp/mt.exr" "$tmp/ot.exr" && grep -q 'est. relMSE 0.00[0-4]' "$tmp/err"; then
        ok "--schedule $s, --target-error 0.005 on 3 ranks: $(grep -oE '[0-9]+ passes' "$tmp/err"), as one process"
    else
        fail "--schedule $s, --target-error across ranks" "$(cat "$tmp/err")"
    fi

    no_leak_check mpi -np 2 --wdir "$tmp" "$MPI" --schedule "$s" --threads 1 --passes 6 -o "$tmp/keep.exr" \
        "$tmp/s.mcrt" : -np 1 --wdir "$tmp/elsewhere" "$MPI" --schedule "$s" --threads 1 \
        --passes 6 -o "$tmp/keep.exr" "$tmp/s.mcrt" 2>"$tmp/err"
    rc=$?
    if [ "$rc" -eq 2 ] && grep -q '^mcrt-mpi: rank 2: .*tri\.obj' "$tmp/err" &&
        [ "$(cat "$tmp/keep.exr")" = keep ]; then
        ok "--schedule $s, a rank without the mesh: exit 2, '$(grep '^mcrt-mpi: rank 2' "$tmp/err")', output untouched"
    else
        fail "--schedule $s, a failing rank" "exit $rc: $(cat "$tmp/err")"
    fi
done

no_leak_check mpi -np 1 "$MPI" --schedule round-robin --passes 1 -o "$tmp/keep.exr" s.mcrt 2>"$tmp/err"
rc=$?
if [ "$rc" -eq 2 ] && grep -q "^mcrt-mpi: --schedule: expected .*, got 'round-robin'" "$tmp/err" &&
    [ "$(cat "$tmp/keep.exr")" = keep ]; then
    ok "an unknown schedule: exit 2, '$(head -1 "$tmp/err")'"
else
    fail "an unknown schedule" "exit $rc: $(cat "$tmp/err")"
fi
finish
