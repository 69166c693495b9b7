#!/bin/sh
# compare_runs.sh - what changed between two results trees (e.g. results/ before and after a second
# `make reproduce`, or two `--out` folders of the same drivers). A rerun without code changes may
# change timing values only; this lists every other difference.
#
# Timing values are, by convention (experiments/common/exp_harness.h):
#   - CSV columns whose header names a time: it contains "ns", "ms", "us", "time", "(s)", "seconds",
#     "speed" or "overhead" as a word (e.g. "ns per pixel", "core-ns per block", "1024^2 on 2 cores (s)"),
#     or seconds as " s at" (d15's "Ceres s at K");
#   - numbers.tex keys ending in -ns, -ms or -s;
#   - everything drawn from those (the .md/.tex copies of such tables, plots whose script reads a
#     timing column, the paper).
# For each CSV that differs, the script names the columns that differ and marks those that are not
# timings; for claims.tsv and numbers.tex it prints the differing lines. Exit 0 if only timing
# values differ, 1 otherwise, 2 on bad usage.
# usage: sh experiments/common/compare_runs.sh DIR_A DIR_B
[ $# -eq 2 ] && [ -d "$1" ] && [ -d "$2" ] || { echo "usage: $0 DIR_A DIR_B (two results trees)" >&2; exit 2; }
a=$1 b=$2 bad=0
is_timing_header() {
  echo "$1" | grep -Eiq '(^|[^a-z])(ns|ms|us|time|seconds|speed|overhead|s\))([^a-z]|$)|core-ns|_ns$|_ms$|^ns|per s$| s at '
}
for f in $(cd "$a" && find . -name '*.csv' | sort); do
  [ -f "$b/$f" ] || { echo "$f: missing in $b"; bad=1; continue; }
  cmp -s "$a/$f" "$b/$f" && continue
  # columns whose cells differ (rows compared in order; a row-count change is reported as such)
  # (commas inside "quoted" cells are masked first, so a name such as "RGBM (RGBA8, range 8)" is one cell)
  cols=$(awk -F',' 'function mask(s,   out, i, c, q) { for (i = 1; i <= length(s); i++) { c = substr(s, i, 1);
                        if (c == "\"") q = !q; out = out ((q && c == ",") ? "\001" : c) } return out }
    { $0 = mask($0) }
    NR == FNR { row[FNR] = $0; n = FNR; next }
    FNR == 1 || blank { blank = 0; for (i = 1; i <= NF; i++) head[i] = $i }   # file or block header
    $0 == "" { blank = 1 }
    { split(row[FNR], o, ","); for (i = 1; i <= NF; i++) if (o[i] != $i) d[i] = head[i] }
    END { if (FNR != n) print "ROWCOUNT"; for (i in d) print d[i] }' "$a/$f" "$b/$f" | sort -u)
  echo "$cols" | while IFS= read -r c; do
    [ -z "$c" ] && continue
    if [ "$c" = ROWCOUNT ]; then echo "$f: NOT TIMING: number of rows differs"; continue; fi
    if is_timing_header "$c"; then echo "$f: timing column '$c' differs"; else echo "$f: NOT TIMING: column '$c' differs"; fi
  done
done > /tmp/compare_runs.$$ 2>&1
cat /tmp/compare_runs.$$
grep -q "NOT TIMING\|missing" /tmp/compare_runs.$$ && bad=1
rm -f /tmp/compare_runs.$$
for f in $(cd "$a" && find . -name 'numbers.tex' | sort); do
  [ -f "$b/$f" ] || continue
  diff "$a/$f" "$b/$f" | grep '^[<>]' | grep -v -- '-\(ns\|ms\|s\)}{' | sed "s|^|$f: NOT TIMING: |" | grep . && bad=1
done
for f in $(cd "$a" && find . -name 'claims.tsv' | sort); do
  [ -f "$b/$f" ] || continue
  # a figure may quote a time (T11's seconds, T13's overhead), but the verdicts must not move
  if [ "$(cut -f1,5 "$a/$f")" != "$(cut -f1,5 "$b/$f")" ]; then
    echo "$f: NOT TIMING: a verdict differs"; bad=1
  fi
  diff "$a/$f" "$b/$f" | grep '^[<>]' | cut -c1-200 | sed "s|^|$f: claims row differs (check it quotes a time): |"
done
exit $bad
