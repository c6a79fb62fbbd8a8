#!/bin/sh
# bench/mpi.sh: archquake-mpi throughput at N = 1, 2, 3 ranks (make bench).
#
# One suite (test records x 4 arches x 4 factors x both polarities)
# run REPS times at each N, interleaved (N=1, 2, 3, 1, 2, 3...) so that the
# machine's load falls on all alike; medians of the wall time, runs per
# second, and each N's ratio to N=1.  N=1 runs the suite in rank 0 with
# -j 1; N>1 has N-1 followers, each one record at a time, rank 0 writing.
set -u
MPIBIN=${AQ_MPI_BIN:-./archquake-mpi}
MPIRUN="mpirun --oversubscribe --allow-run-as-root"
REPS=${AQ_BENCH_REPS:-3}
R=tests/data/records
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
# 20 records (two copies of ten: a suite runs each file once) x 4 arches
# x 4 factors (large: the arches rock) x 2 polarities, the ODE model: 640
# runs, seconds each suite, so that mpirun's start (about half a second)
# does not dominate.
RECS=""
for c in 1 2; do
  for f in ARL360.at2 CHY028-N.AT2 IELC180.AT2 TCU052-N.AT2 RSN1616_DUZCE_362-E.AT2 \
           RSN4013_SANSIMEO_36258021.AT2 RSN763_LOMAP_GIL067.AT2 RSN763_LOMAP_GIL337.AT2 \
           RSN4843_CHUETSU_65006NS.AT2 RSN77_SFERN_PUL164-hor1.AT2; do
    cp "$R/$f" "$T/$c-$f"
    RECS="$RECS $T/$c-$f"
  done
done
ARGS="--arch arches/oppenheim.cfg --arch arches/thin.cfg --arch arches/thick.cfg
      --arch arches/segmental.cfg --scale 2,3,5,8 --polarity both --model ode -j 1"
RUNS=640

echo "== bench/mpi.sh: $RUNS runs per suite, median of $REPS (wall s)"
for rep in $(seq "$REPS"); do
  for n in 1 2 3; do
    s=$(date +%s.%N)
    # shellcheck disable=SC2086
    $MPIRUN -n $n "$MPIBIN" $RECS $ARGS >/dev/null 2>&1
    rc=$?
    e=$(date +%s.%N)
    if [ $rc -ne 0 ]; then echo "bench/mpi.sh: N=$n exited $rc" >&2; exit 1; fi
    echo "$n $s $e" | awk '{ print $1, $3 - $2 }' >>"$T/times"
  done
done
awk -v runs=$RUNS '
  { t[$1, ++k[$1]] = $2 }
  END {
    for (n = 1; n <= 3; n++) {
      m = k[n]
      for (i = 1; i <= m; i++) v[i] = t[n, i]
      for (i = 1; i <= m; i++) for (j = i + 1; j <= m; j++) if (v[j] < v[i]) { x = v[i]; v[i] = v[j]; v[j] = x }
      med[n] = m % 2 ? v[(m + 1) / 2] : (v[m / 2] + v[m / 2 + 1]) / 2
    }
    printf "%-6s %10s %10s %14s\n", "ranks", "median_s", "runs/s", "speedup_vs_N1"
    for (n = 1; n <= 3; n++)
      printf "%-6d %10.3f %10.1f %14.2f\n", n, med[n], runs / med[n], med[1] / med[n]
  }' "$T/times"
