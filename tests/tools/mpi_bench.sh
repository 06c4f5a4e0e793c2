#!/bin/sh
# mpi_bench.sh (make bench): mcrt-mpi's speed-up on 2 ranks over 1, one thread each, and the cost
# of its per-pass exchange, on scenes/cornell.mcrt (512x512, PASSES passes of 1 spp, then LONG
# passes of 16 spp, where MPI's start-up matters less); then its two schedules side by side on an
# oversubscribed box (SCHED_PASSES passes of 1 spp: 3 and 4 ranks on this machine's cores, and 2
# ranks beside a competing busy loop). Each set of runs is interleaved, so that the load of a
# shared machine falls on all alike; medians of 3. Prints one line per measure. Not a test:
# skipped with a note when mcrt-mpi was not built.
MCRT=${MCRT:-build/mcrt}
MPI=$(dirname "$MCRT")/mcrt-mpi
PASSES=${PASSES:-8}
LONG=${LONG:-4}
SCHED_PASSES=${SCHED_PASSES:-12}
if [ ! -x "$MPI" ] || ! command -v mpirun >/dev/null 2>&1; then
    echo "mpi_bench: mcrt-mpi or mpirun missing (libopenmpi-dev, openmpi-bin): skipped"
    exit 0
fi
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
tmp=$(mktemp -d)
busy=
trap 'rm -rf "$tmp"; [ -z "$busy" ] || kill "$busy"' EXIT
scene="--seed 1 -o $tmp/x.exr scenes/cornell.mcrt"
# Seconds of wall-clock time of a command (its summary line goes to $tmp/last).
secs() {
    start=$(date +%s.%N)
    "$@" 2>"$tmp/last" >/dev/null
    end=$(date +%s.%N)
    echo "$start $end" | awk '{ printf "%.3f\n", $2 - $1 }'
}
# The seconds rank 0 spent taking the others' sums and adding them (with the static schedule,
# waiting for them and the round's broadcast too), from the summary line.
exch() { sed -n "s/.*(\([0-9.]*\) s in rank 0's exchanges).*/\1/p" "$tmp/last"; }
# The passes each rank rendered, "5+4+3".
by_rank() { sed -n 's/.* passes on [0-9]* ranks\{0,1\} (\([0-9+]*\), .*/\1/p' "$tmp/last"; }
median() { sort -n | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
mpi() { mpirun --oversubscribe "$@"; }

# speed-up PASSES SPP: mcrt, 1 rank and 2 ranks (static), 3 runs each, interleaved.
speed_up() {
    opts="--threads 1 --spp $2 --passes $1 $scene"
    rm -f "$tmp/one" "$tmp/np1" "$tmp/np2" "$tmp/x1" "$tmp/x2"
    for i in 1 2 3; do
        secs "$MCRT" --quiet $opts >>"$tmp/one"
        secs mpi -np 1 "$MPI" $opts >>"$tmp/np1"
        exch >>"$tmp/x1"
        secs mpi -np 2 "$MPI" $opts >>"$tmp/np2"
        exch >>"$tmp/x2"
    done
    one=$(median <"$tmp/one") np1=$(median <"$tmp/np1") np2=$(median <"$tmp/np2")
    x1=$(median <"$tmp/x1") x2=$(median <"$tmp/x2")
    echo "mcrt-mpi on cornell 512x512, $1 passes of $2 spp, 1 thread a rank, medians of 3 (wall-clock s):"
    echo "  mcrt (one process, no MPI)  $one"
    echo "  mpirun -np 1 mcrt-mpi       $np1"
    echo "  mpirun -np 2 mcrt-mpi       $np2"
    awk -v a="$np1" -v b="$np2" -v o="$one" -v p="$1" -v x1="$x1" -v x2="$x2" 'BEGIN {
        printf "  speed-up of 2 ranks over 1: %.2fx (over mcrt alone: %.2fx)\n", a / b, o / b
        printf "  rank 0 exchange per pass: %.1f ms on 1 rank (adding its own sums), %.1f ms per pass on 2 (waiting for rank 1 included)\n", 1000 * x1 / p, 1000 * x2 / p
        printf "  mpirun -np 1 over mcrt: %+.2f s (MPI start-up, a render per pass, the adds)\n", a - o
    }'
}
speed_up "$PASSES" 1
speed_up "$LONG" 16

# schedules LABEL MPIRUN-ARGS: static and dynamic, 3 runs each, interleaved.
schedules() {
    label=$1
    shift
    rm -f "$tmp/static" "$tmp/dynamic"
    for i in 1 2 3; do
        for s in static dynamic; do
            secs mpi "$@" "$MPI" --schedule $s --threads 1 --spp 1 --passes "$SCHED_PASSES" \
                $scene >>"$tmp/$s"
            eval "last_$s=\$(by_rank)"
        done
    done
    st=$(median <"$tmp/static") dy=$(median <"$tmp/dynamic")
    awk -v l="$label" -v s="$st" -v d="$dy" -v bs="$last_static" -v bd="$last_dynamic" 'BEGIN {
        printf "  %-28s static %6.3f s (%s)  dynamic %6.3f s (%s)  dynamic/static %.2f\n", l, s, bs, d, bd, d / s
    }'
}
cores=$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 2)
echo "mcrt-mpi's schedules, cornell 512x512, $SCHED_PASSES passes of 1 spp, 1 thread a rank, on $cores cores, medians of 3 (wall-clock s; passes by rank of the last run):"
schedules "-np $((cores + 1))" -np $((cores + 1))
schedules "-np $((2 * cores))" -np $((2 * cores))
sh -c 'while :; do :; done' &
busy=$!
schedules "-np $cores beside a busy loop" -np "$cores"
kill "$busy"
busy=
