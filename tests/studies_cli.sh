#!/usr/bin/env bash
# The benchmark studies (runs/*/*.py) answer -h / --help with their usage and leave their CSVs and
# plots alone, and refuse an unknown argument with status 2 before running anything.
# usage: studies_cli.sh REPOSITORY_ROOT
set -euo pipefail
cd "$1"
stamp() { find runs -name '*.csv' -o -name '*.png' | sort | xargs stat -c '%n %Y %s'; }
before=$(stamp)
studies=(runs/*/run.py runs/lzb/far_rays.py runs/speedup/tiles.py)
for study in "${studies[@]}"; do
  for flag in -h --help; do
    out=$(timeout 20 python3 "$study" "$flag")
    grep -qi usage <<<"$out" || { echo "$study $flag: no usage in: $out" >&2; exit 1; }
  done
done
bad_args=("runs/rzb/run.py bogus_study" "runs/lzb/run.py bogus_study" "runs/peers/run.py --scene=city"
          "runs/sampletree/run.py --only")
for study in "${studies[@]}"; do bad_args+=("$study --qiuck"); done
for bad in "${bad_args[@]}"; do
  set +e
  err=$(timeout 20 python3 $bad 2>&1 >/dev/null)
  rc=$?
  set -e
  [[ $rc == 2 && $err == *unknown* ]] || { echo "$bad: status $rc, '$err'" >&2; exit 1; }
done
[[ "$(stamp)" == "$before" ]] || { echo "a study wrote its results" >&2; exit 1; }
echo "studies: usage printed, unknown arguments refused, nothing written"
