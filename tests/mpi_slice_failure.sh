#!/usr/bin/env bash
# A rank killed while the ranks read a binary PLY in slices (reading, fetching vertices, cutting,
# exchanging triangles: src/regions/sliced_share.hpp) ends the whole job within 10 s, on 2 and 3
# ranks, with a failing status and no report: no rank waits forever in a collective for a peer
# that is gone.
# usage: mpi_slice_failure.sh LZB_BINARY WORK_DIR MPIEXEC
set -euo pipefail
lzb="$1" work="$2" mpiexec="$3"
# Set, lzb does not re-execute itself to set it (src/cli/omp_wait_policy.hpp): the ranks are the
# launcher's children under their own name.
export OMP_WAIT_POLICY=passive
rm -rf "$work" && mkdir -p "$work"
ply="$work/big.ply"
# 2.4 M triangles: a load of a second or more on 2 ranks.
"$lzb" export "builtin:landscape?objects=100000" "$ply" --quiet

for ranks in 2 3; do
  out="$work/out$ranks"
  "$mpiexec" --oversubscribe -n "$ranks" "$lzb" render "$ply" --method raycast --distribute data \
    --frames 2 --threads 1 --quiet --out "$out" >"$work/log$ranks" 2>&1 &
  launcher=$!
  for _ in $(seq 200); do
    [ "$(pgrep -P "$launcher" | wc -l)" -ge "$ranks" ] && break
    sleep 0.02
  done
  sleep 0.4  # MPI started, the slices being read
  victim=$(pgrep -P "$launcher" | tail -1 || true)
  if [ -z "$victim" ]; then
    echo "FAIL: $ranks ranks: no rank of the launcher found to kill"
    exit 1
  fi
  killed=$(date +%s%N)
  kill -9 "$victim"
  status=0
  wait "$launcher" || status=$?
  elapsed_ms=$((($(date +%s%N) - killed) / 1000000))
  if [ -e "$out/report.json" ]; then
    echo "FAIL: $ranks ranks: the job finished before the kill (make the file larger)"
    exit 1
  fi
  if [ "$status" -eq 0 ]; then
    echo "FAIL: $ranks ranks: exit status 0 after a rank was killed"
    exit 1
  fi
  if [ "$elapsed_ms" -gt 10000 ]; then
    echo "FAIL: $ranks ranks: the job ended $elapsed_ms ms after the kill"
    exit 1
  fi
  echo "ok: $ranks ranks: a rank killed while loading in slices ended the job in $elapsed_ms ms (status $status)"
done
