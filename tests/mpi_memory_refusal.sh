#!/usr/bin/env bash
# A rank whose estimated peak exceeds the memory it may use (ulimit -v here) refuses before it
# holds the scene, and the whole job ends with exit status 2, the estimate, and nothing written:
# one rank limited, every rank limited, and a data-mode share too large for its rank.
# usage: mpi_memory_refusal.sh LZB_BINARY WORK_DIR MPIEXEC
set -euo pipefail
lzb="$1" work="$2" mpiexec="$3"
rm -rf "$work" && mkdir -p "$work"
out="$work/out"
scene="builtin:landscape?objects=200000"  # 4.8 M triangles: the hybrid's estimate is 754 MiB
run=(render "$scene" --method hybrid --quiet --threads 1 --frames 1 --out "$out")
# Runs lzb under an address-space limit: limit.sh KIB ARGS...
cat >"$work/limit.sh" <<'SH'
#!/bin/sh
ulimit -v "$1"
shift
exec "$@"
SH
chmod +x "$work/limit.sh"
limit=("$work/limit.sh")

source "$(dirname "$0")/support/expect_job_exit2.sh"
expect_refusal() {  # name, what the message must say, then the mpiexec arguments
  local name="$1" says="$2"
  shift 2
  expect_job_exit2 "$name" "$out" "needs an estimated" "$says" -- "$@"
}

# 1.1 GiB of address space: the process starts, the whole scene's estimate does not fit (the
# limit less what is mapped, ~300 MiB, and less 256 MiB a run maps without touching).
one=("${limit[@]}" 1200000 "$lzb" "${run[@]}")
expect_refusal "rank 1 limited" "rank 1: error: $scene: every rank holding 4832768" \
  -n 1 "$lzb" "${run[@]}" : -n 1 "${one[@]}"
expect_refusal "every rank limited" "every rank holding" -n 2 "${one[@]}"
# Under data, each of 2 ranks would hold half (422 MiB); with 0.9 GiB that still does not fit.
share=("${limit[@]}" 950000 "$lzb" "${run[@]}" --distribute data)
expect_refusal "a data share too large" "rank 0 of 2 holding" -n 2 "${share[@]}"

# The capacity case: under 1.05 GiB a rank refuses raycast's whole 4.8 M triangles (670 MiB
# estimated, above what the limit leaves), so --distribute auto cuts the scene across 2 ranks
# (371 MiB each), each under the same limit, and the image is that of 1 rank without the limit.
exact=(render "$scene" --method raycast --quiet --threads 1 --frames 1 --width 160 --height 120)
"$lzb" "${exact[@]}" --out "$work/whole" >/dev/null
timeout 120 "$mpiexec" --oversubscribe -n 2 "${limit[@]}" 1100000 "$lzb" "${exact[@]}" \
  --distribute auto --out "$work/auto" >/dev/null
grep -q '"distribution": "data"' "$work/auto/report.json" || { echo "FAIL: auto did not cut"; exit 1; }
cmp "$work/whole/frame_0000.exr" "$work/auto/frame_0000.exr" ||
  { echo "FAIL: the cut scene's image differs"; exit 1; }
echo "ok: auto cut the scene across 2 limited ranks, the unlimited image"

# The same scene as a binary PLY: auto weighs it from its header alone, and the ranks read it in
# slices, each share weighed against what its rank could use before loading (the slice's load is
# freed before the build), the image that of 1 rank without the limit.
ply="$work/landscape.ply"
"$lzb" export "$scene" "$ply" --quiet
exact_ply=(render "$ply" --method raycast --quiet --threads 1 --frames 1 --width 160 --height 120)
"$lzb" "${exact_ply[@]}" --out "$work/whole_ply" >/dev/null
timeout 120 "$mpiexec" --oversubscribe -n 2 "${limit[@]}" 1100000 "$lzb" "${exact_ply[@]}" \
  --distribute auto --out "$work/auto_ply" >/dev/null
grep -q '"distribution": "data"' "$work/auto_ply/report.json" ||
  { echo "FAIL: auto did not cut the PLY"; exit 1; }
grep -q '"bytes_read"' "$work/auto_ply/report.json" || { echo "FAIL: the PLY not read in slices"; exit 1; }
cmp "$work/whole_ply/frame_0000.exr" "$work/auto_ply/frame_0000.exr" ||
  { echo "FAIL: the cut PLY's image differs"; exit 1; }
echo "ok: auto cut the PLY across 2 limited ranks (read in slices), the unlimited image"
