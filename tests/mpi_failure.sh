#!/usr/bin/env bash
# A rank that fails never hangs the job: bad input on rank 1 only, on rank 0 only, on every rank,
# and on a rank whose peer is still busy building, must end the whole job within seconds with
# exit status 2, the message, and nothing written.
# usage: mpi_failure.sh LZB_BINARY WORK_DIR MPIEXEC
set -euo pipefail
lzb="$1" work="$2" mpiexec="$3"
rm -rf "$work" && mkdir -p "$work"
out="$work/out"
good=(render "builtin:city?blocks=2" --quiet --threads 1 --out "$out")
missing=(render "$work/missing.ply" --quiet --threads 1 --out "$out")
busy=(render "builtin:city?blocks=40" --method lzb --quiet --threads 1 --out "$out")

source "$(dirname "$0")/support/expect_job_exit2.sh"
expect_failure() {  # name, then the mpiexec arguments
  local name="$1"
  shift
  expect_job_exit2 "$name" "$out" "missing.ply" -- "$@"
}

expect_failure "rank 1 fails" -n 1 "$lzb" "${good[@]}" : -n 1 "$lzb" "${missing[@]}"
expect_failure "rank 0 fails" -n 1 "$lzb" "${missing[@]}" : -n 1 "$lzb" "${good[@]}"
expect_failure "every rank fails" -n 2 "$lzb" "${missing[@]}"
expect_failure "rank 1 fails while rank 0 builds" -n 1 "$lzb" "${busy[@]}" : -n 1 "$lzb" "${missing[@]}"
# Every rank failing alike prints the message once.
msg=$("$mpiexec" --oversubscribe -n 3 "$lzb" "${missing[@]}" 2>&1 || true)
[ "$(grep -c "missing.ply" <<<"$msg")" -eq 1 ] || { echo "FAIL: message not printed once: $msg"; exit 1; }
echo "ok: one message for 3 ranks failing alike"
