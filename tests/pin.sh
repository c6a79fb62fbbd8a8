#!/bin/sh
# tests/pin.sh: today's outputs, pinned (tests/data/pin/README.md).
#
#   sh tests/pin.sh           check: every case of tests/data/pin/cases
#                             against the stored references
#   sh tests/pin.sh record    write the references again (see the README:
#                             only with a commit that explains why)
#
# A case is one line of tests/data/pin/cases: NAME REF EXIT ARGUMENTS...
# (ARGUMENTS split at blanks, no globbing; @T@ is the output directory).
# It must exit with EXIT, its stdout must equal REF.tsv byte for byte
# (unless it writes @T@/NAME.tsv itself, with --text: then stdout must be
# empty), and every other file NAME.EXT it writes into @T@ must equal REF.EXT:
# byte for byte, or for .h5 files `archquake compare` exit 0, h5diff of the
# groups that compare does not read (/arches, /capacity, /histories,
# /waveforms, those the reference has) and /records without its timings (the
# reference's columns: a column added since is not a change).  Cases whose NAME is not their REF
# (the same job at another -j) are checked against the reference also when
# recording.  Stderr is not compared.  Last line: "N passed, N failed".
# AQ_BIN: the program (default ./archquake).  AQ_PIN_ONLY=SUBSTRING: only
# the cases whose name contains it.
set -u
BIN=${AQ_BIN:-./archquake}
D=tests/data/pin
MODE=${1:-check}
case $MODE in check|record) ;; *) echo "usage: sh tests/pin.sh [check|record]" >&2; exit 2 ;; esac
T=$(mktemp -d "${TMPDIR:-/tmp}/aqpin.XXXXXX")
trap 'rm -rf "$T"' EXIT
pass=0
fail=0
H5DIFF=$(command -v h5diff || true)

ok() { pass=$((pass + 1)); [ -n "${AQ_TEST_VERBOSE:-}" ] && echo "ok: $1"; return 0; }
bad() { fail=$((fail + 1)); echo "FAIL: $1"; }

# The /records table as text, every double to 17 digits, without its
# timing_* fields (which differ from run to run).  With a second argument, a
# file of column names one a line: only those columns (and their units_
# attributes), so that a column added since the reference is not a change.
records_text() {
  h5dump -m %.17g -d /records "$1" 2>/dev/null </dev/null | awk -v keep="${2:-}" '
    BEGIN { if (keep != "") while ((getline l <keep) > 0) want[l] = 1 }
    function kept(nm) { return keep == "" || (nm in want) }
    NR == 1 { next }
    !data && /^   DATA \{/ { data = 1; printf "%s", buf; buf = ""; print; next }
    !data {
      buf = buf $0 "\n"
      if (match($0, /"[^"]*";$/)) {
        n++; nm = substr($0, RSTART + 1, RLENGTH - 3)
        if (nm ~ /^timing_/ || !kept(nm)) skip[n] = 1
        if (kept(nm)) printf "%s", buf
        buf = ""
      }
      next
    }
    data == 1 && /^   \}/ { data = 2 }
    data == 1 && /^   \([0-9]+\): \{/ { k = 0; print; next }
    data == 1 && /^         [^ ]/ { k++; if (!skip[k]) print; next }
    data == 2 && /^   ATTRIBUTE "units_/ { nm = $2; gsub(/"/, "", nm); sub(/^units_/, "", nm); drop = !kept(nm) }
    drop { if ($0 ~ /^   \}$/) drop = 0; next }
    { print }'
}

# The /records table's column names, one a line.
records_cols() {
  h5dump -H -d /records "$1" 2>/dev/null </dev/null | sed -n 's/^      } *"\([^"]*\)";$/\1/p; s/^      H5T_[A-Z0-9_]* *"\([^"]*\)";$/\1/p'
}

# same_h5 REF NEW NAME: compare exit 0; h5diff of the groups that compare
# leaves out (those in REF); the /records table without its timings.
same_h5() {
  "$BIN" compare "$1" "$2" >"$T/cmp.out" 2>&1 </dev/null
  rc=$?
  if [ $rc -ne 0 ]; then
    bad "$3: archquake compare $1 $2: exit $rc: $(head -c 600 "$T/cmp.out")"
    return
  fi
  if [ -z "$H5DIFF" ]; then
    ok "$3: compare (h5diff not found: make deps-dev)"
    return
  fi
  for g in /arches /capacity /histories /waveforms; do
    if "$H5DIFF" -q "$1" "$1" "$g" >/dev/null 2>&1 </dev/null; then
      if "$H5DIFF" -q "$1" "$2" "$g" >/dev/null 2>&1 </dev/null; then :; else
        bad "$3: h5diff $1 $2 $g finds differences"
        return
      fi
    fi
  done
  records_cols "$1" >"$T/rec.cols"
  records_text "$1" "$T/rec.cols" >"$T/rec.ref"
  records_text "$2" "$T/rec.cols" >"$T/rec.new"
  if [ ! -s "$T/rec.ref" ] || ! cmp -s "$T/rec.ref" "$T/rec.new"; then
    bad "$3: /records differs: $(diff "$T/rec.ref" "$T/rec.new" | head -n 6)"
    return
  fi
  ok "$3: compare, h5diff and /records"
}

while read -r name ref want args; do
  case $name in ''|'#'*) continue ;; esac
  [ -n "${AQ_PIN_ONLY:-}" ] && case $name in *"$AQ_PIN_ONLY"*) ;; *) continue ;; esac
  rm -rf "$T/out" && mkdir "$T/out"
  set -f # the arguments split at blanks, unglobbed ('*.SAC=counts')
  # shellcheck disable=SC2086
  set -- $(printf '%s\n' "$args" | sed "s|@T@|$T/out|g")
  set +f
  case " $* " in
    *" $T/out/$name.tsv "*) "$BIN" "$@" >"$T/stdout" 2>"$T/stderr" </dev/null ;;
    *) "$BIN" "$@" >"$T/out/$name.tsv" 2>"$T/stderr" </dev/null ;;
  esac
  rc=$?
  if [ "$rc" != "$want" ]; then
    bad "$name: exit $rc, expected $want: $(head -c 600 "$T/stderr")"
    continue
  fi
  if [ -f "$T/stdout" ]; then
    [ -s "$T/stdout" ] && bad "$name: output on stdout beside --text"
    rm -f "$T/stdout"
  fi
  if [ "$MODE" = record ] && [ "$name" = "$ref" ]; then
    for f in "$T/out/$name".*; do cp "$f" "$D/$ref.${f##*/$name.}"; done
    ok "$name: recorded"
    continue
  fi
  for f in "$T/out/$name".*; do
    ext=${f##*/$name.}
    if [ ! -f "$D/$ref.$ext" ]; then
      bad "$name: $D/$ref.$ext: no such reference"
    elif [ "$ext" = h5 ]; then
      same_h5 "$D/$ref.$ext" "$f" "$name.$ext"
    elif cmp -s "$D/$ref.$ext" "$f"; then
      ok "$name.$ext: byte-identical"
    else
      bad "$name.$ext differs from $D/$ref.$ext: $(cmp "$D/$ref.$ext" "$f" 2>&1 | head -c 300)"
      diff "$D/$ref.$ext" "$f" 2>/dev/null | head -n 6 | cut -c 1-300
    fi
  done
done <"$D/cases"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
