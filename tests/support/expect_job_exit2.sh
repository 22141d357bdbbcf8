# Sourced by the mpi_*.sh tests. expect_job_exit2 NAME OUT PATTERN... -- MPIEXEC_ARGS...: runs
# "$mpiexec" --oversubscribe MPIEXEC_ARGS and fails the test unless the whole job ends with exit
# status 2 within 30 s, its output holds every PATTERN, and OUT was not written.
expect_job_exit2() {
  local name="$1" written="$2" patterns=()
  shift 2
  while [ "$1" != "--" ]; do patterns+=("$1"); shift; done
  shift
  local start=$SECONDS status=0 msg
  msg=$(timeout 120 "$mpiexec" --oversubscribe "$@" 2>&1) || status=$?
  local took=$((SECONDS - start))
  [ "$status" -eq 2 ] || { echo "FAIL: $name exited $status (want 2): $msg"; exit 1; }
  [ "$took" -le 30 ] || { echo "FAIL: $name took $took s"; exit 1; }
  for p in "${patterns[@]}"; do
    grep -q -- "$p" <<<"$msg" || { echo "FAIL: $name does not say '$p': $msg"; exit 1; }
  done
  [ ! -e "$written" ] || { echo "FAIL: $name wrote $written"; exit 1; }
  echo "ok: $name exited 2 in $took s"
}
