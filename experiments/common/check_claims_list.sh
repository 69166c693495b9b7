#!/bin/sh
# check_claims_list.sh - every claim of experiments/claims_list.tsv names the experiment(s) that
# measure it (folders of experiments/, comma-separated) and the library entry point it exercises
# (a function declared in a public header src/<module>/sol_<module>.h), so claim ID -> experiment ->
# function is one step. Prints every problem and exits 1 if there is one.
# usage: sh experiments/common/check_claims_list.sh [experiments/claims_list.tsv]
list=${1:-experiments/claims_list.tsv}
[ -r "$list" ] || { echo "$list: cannot read" >&2; exit 2; }
awk -F'\t' 'NR > 1 { print NR "|" $1 "|" $4 "|" $5 "|" NF }' "$list" | {
  bad=0
  while IFS="|" read -r line id experiments entry fields; do
    if [ "$fields" -ne 5 ]; then
      echo "$list:$line: claim $id has $fields fields, want 5 (id, claim, talk_figure, experiment, entry_point)" >&2
      bad=1; continue
    fi
    if [ -z "$experiments" ]; then echo "$list:$line: claim $id: experiment is empty" >&2; bad=1; fi
    for e in $(echo "$experiments" | tr ',' ' '); do
      [ -f "experiments/$e/main.c" ] || { echo "$list:$line: claim $id: experiment '$e' has no experiments/$e/main.c" >&2; bad=1; }
    done
    if [ -z "$entry" ]; then
      echo "$list:$line: claim $id: entry_point is empty" >&2; bad=1
    elif ! grep -q "\\b$entry(" src/*/sol_*.h; then
      echo "$list:$line: claim $id: entry_point '$entry' is not declared in any src/*/sol_*.h" >&2; bad=1
    fi
  done
  exit $bad
}
