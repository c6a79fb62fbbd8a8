#!/bin/sh
# bench/mpi.sh: archquake-mpi throughput at N = 1, 2, 3 ranks (make bench),
# for the main job and for capacity.
#
# Each case runs REPS times at each N, interleaved (N=1, 2, 3, 1, 2, 3...)
# so that the machine's load falls on all alike; medians of the wall time,
# work per second, and each N's ratio to N=1.  Every rank runs -j 1: one
# worker thread each, rank 0's included (its main thread only exchanges
# messages and sleeps), so N = 3 puts three workers on 2 cores.  mpirun's own
# start (the `--version` row: MPI and the libraries loading in every rank)
# is inside every figure.  AQ_MPI_BIN_BEFORE=path adds the main job of
# another build (e.g. the previous one) to the same interleaved run, for a
# before/after comparison on equal terms.
set -u
MPIBIN=${AQ_MPI_BIN:-./archquake-mpi}
BEFORE=${AQ_MPI_BIN_BEFORE:-}
MPIRUN="mpirun --oversubscribe --allow-run-as-root"
REPS=${AQ_BENCH_REPS:-5}
R=tests/data/records
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
# Main job: 60 records (six copies of ten: a suite runs each file once) x 4
# arches x 4 factors (large: the arches rock) x 2 polarities, the ODE
# model: 1920 runs, a few seconds a suite.
RECS=""
for c in 1 2 3 4 5 6; do
  for f in ARL360.at2 CHY028-N.AT2 IELC180.AT2 TCU052-N.AT2 RSN1616_DUZCE_362-E.AT2 \
           RSN4013_SANSIMEO_36258021.AT2 RSN763_LOMAP_GIL067.AT2 RSN763_LOMAP_GIL337.AT2 \
           RSN4843_CHUETSU_65006NS.AT2 RSN77_SFERN_PUL164-hor1.AT2; do
    cp "$R/$f" "$T/$c-$f"
    RECS="$RECS $T/$c-$f"
  done
done
ARGS="--arch arches/oppenheim.cfg --arch arches/thin.cfg --arch arches/thick.cfg
      --arch arches/segmental.cfg --scale 2,3,5,8 --polarity both --model ode -j 1"
RUNS=1920
# Capacity: 6 records x 2 arches x 2 polarities, scans of ratio 1.02: 24
# scans of a few hundred runs, some several times longer than others.
CRECS="$R/ARL360.at2 $R/CHY028-N.AT2 $R/IELC180.AT2 $R/TCU052-N.AT2
       $R/RSN1616_DUZCE_362-E.AT2 $R/RSN4013_SANSIMEO_36258021.AT2"
CARGS="--arch arches/oppenheim.cfg --arch arches/thin.cfg --resolution 0.02 -j 1"
PAIRS=24

# one timed run: label n command...
timed() {
  label=$1
  n=$2
  shift 2
  s=$(date +%s.%N)
  "$@" >/dev/null 2>&1
  rc=$?
  e=$(date +%s.%N)
  if [ $rc -ne 0 ]; then echo "bench/mpi.sh: $label N=$n exited $rc" >&2; exit 1; fi
  echo "$label $n $s $e" | awk '{ print $1, $2, $4 - $3 }' >>"$T/times"
}

echo "== bench/mpi.sh: median of $REPS (wall s), -j 1 in every rank"
for rep in $(seq "$REPS"); do
  for n in 1 2 3; do
    # shellcheck disable=SC2086
    timed start $n $MPIRUN -n $n "$MPIBIN" --version
    # shellcheck disable=SC2086
    timed main $n $MPIRUN -n $n "$MPIBIN" $RECS $ARGS
    # shellcheck disable=SC2086
    [ -n "$BEFORE" ] && timed before $n $MPIRUN -n $n "$BEFORE" $RECS $ARGS
    # shellcheck disable=SC2086
    timed capacity $n $MPIRUN -n $n "$MPIBIN" capacity $CRECS $CARGS
  done
done
awk -v runs=$RUNS -v pairs=$PAIRS '
  { t[$1, $2, ++k[$1, $2]] = $3; seen[$1] = 1 }
  function median(label, n,   m, i, j, x, v) {
    m = k[label, n]
    for (i = 1; i <= m; i++) v[i] = t[label, n, i]
    for (i = 1; i <= m; i++) for (j = i + 1; j <= m; j++) if (v[j] < v[i]) { x = v[i]; v[i] = v[j]; v[j] = x }
    return m % 2 ? v[(m + 1) / 2] : (v[m / 2] + v[m / 2 + 1]) / 2
  }
  END {
    printf "%-9s %-6s %10s %12s %14s\n", "case", "ranks", "median_s", "work/s", "speedup_vs_N1"
    split("start main before capacity", order, " ")
    for (c = 1; c <= 4; c++) {
      label = order[c]
      if (!seen[label]) continue
      w = label == "capacity" ? pairs : label == "start" ? 0 : runs
      for (n = 1; n <= 3; n++) {
        med[n] = median(label, n)
        printf "%-9s %-6d %10.3f %12s %14.2f\n", label, n, med[n],
               w ? sprintf("%.1f", w / med[n]) : "-", med[1] / med[n]
      }
    }
    print "(work/s: runs/s for main and before, (record, arch, polarity) scans/s for capacity)"
  }' "$T/times"
