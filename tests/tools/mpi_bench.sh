#!/bin/sh
# mpi_bench.sh (make bench): the speed-up of mcrt-mpi on 2 ranks over 1, one thread each, and the
# cost of its per-pass exchange, on scenes/cornell.mcrt (512x512, PASSES passes of 1 spp). Three
# runs of each, interleaved so that the load of a shared machine falls on all alike; medians.
# Prints one line per measure. Not a test: skipped with a note when mcrt-mpi was not built.
MCRT=${MCRT:-build/mcrt}
MPI=$(dirname "$MCRT")/mcrt-mpi
PASSES=${PASSES:-8}
if [ ! -x "$MPI" ] || ! command -v mpirun >/dev/null 2>&1; then
    echo "mpi_bench: mcrt-mpi or mpirun missing (libopenmpi-dev, openmpi-bin): skipped"
    exit 0
fi
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
opts="--threads 1 --spp 1 --passes $PASSES --seed 1 -o $tmp/x.exr scenes/cornell.mcrt"
# Seconds of wall-clock time of a command (its summary line goes to $tmp/last).
secs() {
    start=$(date +%s.%N)
    "$@" 2>"$tmp/last" >/dev/null
    end=$(date +%s.%N)
    echo "$start $end" | awk '{ printf "%.3f\n", $2 - $1 }'
}
# The seconds rank 0 spent after its own pass of each round (taking the others' sums, adding
# them, the round's broadcast), from the summary line.
exch() { sed -n "s/.*(\([0-9.]*\) s in rank 0's exchanges).*/\1/p" "$tmp/last"; }
median() { sort -n | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
for i in 1 2 3; do
    secs "$MCRT" --quiet $opts >>"$tmp/one"
    secs mpirun --oversubscribe -np 1 "$MPI" $opts >>"$tmp/np1"
    exch >>"$tmp/x1"
    secs mpirun --oversubscribe -np 2 "$MPI" $opts >>"$tmp/np2"
    exch >>"$tmp/x2"
done
one=$(median <"$tmp/one") np1=$(median <"$tmp/np1") np2=$(median <"$tmp/np2")
x1=$(median <"$tmp/x1") x2=$(median <"$tmp/x2")
echo "mcrt-mpi on cornell 512x512, $PASSES passes of 1 spp, 1 thread a rank, medians of 3 (wall-clock s):"
echo "  mcrt (one process, no MPI)  $one"
echo "  mpirun -np 1 mcrt-mpi       $np1"
echo "  mpirun -np 2 mcrt-mpi       $np2"
awk -v a="$np1" -v b="$np2" -v o="$one" -v p="$PASSES" -v x1="$x1" -v x2="$x2" 'BEGIN {
    printf "  speed-up of 2 ranks over 1: %.2fx (over mcrt alone: %.2fx)\n", a / b, o / b
    printf "  rank 0 exchange per pass: %.1f ms on 1 rank (adding its own sums), %.1f ms per pass on 2 (waiting for rank 1 included)\n", 1000 * x1 / p, 1000 * x2 / p
    printf "  mpirun -np 1 over mcrt: %+.2f s (MPI start-up, a render per pass, the adds)\n", a - o
}'
