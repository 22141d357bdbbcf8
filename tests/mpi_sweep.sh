#!/usr/bin/env bash
# `lzb sweep` on 2 MPI ranks gives the accuracy of the 1-rank run: the ranks composite the same
# image, so every accuracy column of sweep.csv must match exactly (times and cache counts may not).
# usage: mpi_sweep.sh LZB_BINARY WORK_DIR MPIEXEC
set -euo pipefail
lzb="$1" work="$2" mpiexec="$3"
rm -rf "$work" && mkdir -p "$work"
args=(sweep "builtin:city?blocks=3" --method rzb --param splat=1,2 --param eps=1.5,3
      --width 96 --height 72 --frames 2 --threads 1 --quiet)
"$lzb" "${args[@]}" --out "$work/one" >/dev/null
"$mpiexec" -n 2 --oversubscribe "$lzb" "${args[@]}" --out "$work/two" >/dev/null
python3 - "$work/one/sweep.csv" "$work/two/sweep.csv" <<'PY'
import csv, sys
def rows(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))
one, two = rows(sys.argv[1]), rows(sys.argv[2])
assert len(one) == len(two) == 4, (len(one), len(two))
columns = ["splat", "eps", "frames", "correct_rate_covered_min", "correct_rate_covered_median",
           "exact_id_rate_covered_median", "psnr_aa_median"]
for a, b in zip(one, two):
    for c in columns:
        assert a[c] == b[c], (c, a[c], b[c])
print("ok: 1 and 2 ranks give the same accuracy columns for", len(one), "combinations")
PY
