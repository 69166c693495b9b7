#!/bin/sh
# compare_runs.sh - what changed between two results trees (e.g. results/ before and after a second
# `make reproduce`, or two `--out` folders of the same drivers). A rerun without code changes may
# change timing values only; this lists every other difference. `make compare-runs A=... B=...`
# runs it (without A: against the results/ committed at HEAD).
#
# Timing values are, by convention (experiments/common/exp_harness.h):
#   - CSV columns whose header names a time: it contains "ns", "ms", "us", "time", "(s)", "seconds",
#     "speed" or "overhead" as a word (e.g. "ns per pixel", "core-ns per block", "1024^2 on 2 cores (s)");
#   - columns of whitespace-separated .dat plot data named so by the file's "# ..." header line
#     (names separated by commas, or by blanks when the line has no comma); a .dat without such a
#     header has no timing columns;
#   - numbers.tex keys ending in -ns, -ms or -s, and figures computed from timings (an R^2 of a fit to
#     times, a speed ratio) in keys ending in -timing;
#   - everything drawn from those: the .md/.tex copies of a CSV table, a plot (.png/.pdf beside a
#     .gp) whose script reads a data file that differs in timing columns only, the gathered claims
#     table (CLAIMS.md, claims.tex) when only rows quoting a time differ, and the paper (sol.pdf).
# Anything else that differs is NOT TIMING: a non-timing column, a changed verdict, a .md/.tex table
# or a plot that differs although its data does not (a date, a rendering that is not
# reproducible), an image, EXR or DDS output, a file missing on one side.
# For each CSV/.dat that differs, the script names the columns that differ and marks those that are
# not timings; for claims.tsv and numbers.tex it prints the differing lines. Exit 0 if only timing
# values differ, 1 otherwise, 2 on bad usage.
# usage: sh experiments/common/compare_runs.sh DIR_A DIR_B
[ $# -eq 2 ] && [ -d "$1" ] && [ -d "$2" ] || { echo "usage: $0 DIR_A DIR_B (two results trees)" >&2; exit 2; }
a=$1 b=$2 bad=0
tmp=$(mktemp -d) || exit 2
trap 'rm -rf "$tmp"' EXIT
is_timing_header() {
  echo "$1" | grep -Eiq '(^|[^a-z])(ns|ms|us|time|seconds|speed|overhead|s\))([^a-z]|$)|core-ns|_ns$|_ms$|^ns|per s$'
}
# Prints the titles of the columns whose cells differ between two data files, one per line, or
# ROWCOUNT. $3 = csv: comma-separated, one header line per block (a file, or each block after a
# blank line); commas inside "quoted" cells are masked first, so a name such as "RGBM (RGBA8,
# range 8)" is one cell. $3 = dat: blank-separated (blanks inside "quoted" names masked the same
# way), titles from a leading "# ..." line, else "field N".
diff_columns() {
  awk -v fmt="$3" 'function mask(s, sep,   out, i, c, q) { for (i = 1; i <= length(s); i++) { c = substr(s, i, 1);
                        if (c == "\"") q = !q; out = out ((q && c ~ sep) ? "\001" : c) } return out }
    function cells(s, arr) { return fmt == "csv" ? split(mask(s, ","), arr, ",") : split(mask(s, "[ \t]"), arr, " ") }
    NR == FNR { row[FNR] = $0; n = FNR; next }
    fmt == "csv" && (FNR == 1 || blank) { blank = 0; nh = cells($0, head) }   # file or block header
    fmt == "dat" && FNR == 1 && /^#/ { h = substr($0, 2); nh = split(h, head, index(h, ",") ? "," : " ");
                                       for (i = 1; i <= nh; i++) gsub(/^ +| +$/, "", head[i]) }
    fmt == "csv" && $0 == "" { blank = 1 }
    { m = cells(row[FNR], o); k = cells($0, c); if (m > k) k = m
      for (i = 1; i <= k; i++) if (o[i] != c[i]) d[i] = (i <= nh && head[i] != "") ? head[i] : "field " i }
    END { if (FNR != n) print "ROWCOUNT"; for (i in d) print d[i] }' "$1" "$2" | sort -u
}
# 1. data files: every differing column named, timing or not; $tmp/status gets "<file> timing|other"
for f in $(cd "$a" && find . \( -name '*.csv' -o -name '*.dat' \) | sort); do
  [ -f "$b/$f" ] || { echo "$f: NOT TIMING: missing in $b"; continue; }
  cmp -s "$a/$f" "$b/$f" && continue
  case $f in *.csv) fmt=csv ;; *) fmt=dat ;; esac
  state=timing
  diff_columns "$a/$f" "$b/$f" $fmt > "$tmp/cols"
  while IFS= read -r c; do
    if [ "$c" = ROWCOUNT ]; then echo "$f: NOT TIMING: number of rows differs"; state=other
    elif is_timing_header "$c"; then echo "$f: timing column '$c' differs"
    else echo "$f: NOT TIMING: column '$c' differs"; state=other; fi
  done < "$tmp/cols"
  echo "$f $state" >> "$tmp/status"
done > "$tmp/out" 2>&1
touch "$tmp/status"
# 2. every other file: identical, or drawn from data that differs in timing columns only
data_state() { # prints timing, other or same for a data file (relative path)
  s=$(awk -v f="$1" '$1 == f { print $2 }' "$tmp/status")
  echo "${s:-same}"
}
for f in $(cd "$a" && find . -type f ! -name '*.csv' ! -name '*.dat' ! -name claims.tsv ! -name numbers.tex | sort); do
  [ -f "$b/$f" ] || { echo "$f: NOT TIMING: missing in $b"; continue; }
  cmp -s "$a/$f" "$b/$f" && continue
  dir=$(dirname "$f") base=${f%.*}
  case $f in
    ./sol.pdf) echo "$f: the paper differs (drawn from everything above)" ;;
    ./CLAIMS.md | ./claims.tex) echo "$f: gathered claims table differs (see the claims.tsv lines)" ;;
    *.md | *.tex)
      s=$(data_state "$base.csv")
      case $s in
        timing) echo "$f: timing (copy of $base.csv)" ;;
        other) echo "$f: copy of $base.csv, which differs beyond timing" ;;
        *) echo "$f: NOT TIMING: differs although $base.csv does not (or has no CSV)" ;;
      esac ;;
    *.png | *.pdf)
      if [ ! -f "$a/$base.gp" ]; then echo "$f: NOT TIMING: output image differs"; continue; fi
      if ! cmp -s "$a/$base.gp" "$b/$base.gp"; then echo "$f: NOT TIMING: its plot script $base.gp differs"; continue; fi
      states=$(for d in $(grep -o "['\"][^'\"]*\.\(csv\|dat\)['\"]" "$a/$base.gp" | tr -d "'\"" | sort -u); do
                 data_state "$dir/$d"; done | sort -u | tr '\n' ' ')
      case "$states" in
        *other*) echo "$f: plot of data that differs beyond timing" ;;
        *timing*) echo "$f: timing (plot of a timing column)" ;;
        *) echo "$f: NOT TIMING: plot differs although its data does not (a date or the renderer)" ;;
      esac ;;
    *) echo "$f: NOT TIMING: differs" ;;
  esac
done >> "$tmp/out" 2>&1
for f in $(cd "$b" && find . -type f | sort); do
  [ -f "$a/$f" ] || echo "$f: NOT TIMING: missing in $a"
done >> "$tmp/out"
cat "$tmp/out"
grep -q "NOT TIMING\|beyond timing" "$tmp/out" && bad=1
for f in $(cd "$a" && find . -name 'numbers.tex' | sort); do
  [ -f "$b/$f" ] || continue
  diff "$a/$f" "$b/$f" | grep '^[<>]' | grep -v -- '-\(ns\|ms\|s\|timing\)}{' | sed "s|^|$f: NOT TIMING: |" | grep . && bad=1
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
