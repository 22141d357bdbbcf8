#!/usr/bin/env bash
# Renders the same frames on 1 process and on 2 MPI ranks and requires byte-identical images
# (with the sub-sample channels for the exact methods) and the same accuracy against a reference.
# usage: mpi_identical.sh LZB_BINARY WORK_DIR MPIEXEC METHOD
set -euo pipefail
lzb="$1" work="$2" mpiexec="$3" method="$4"
rm -rf "$work" && mkdir -p "$work"
scenes=("builtin:city?blocks=3" "builtin:sphereflake?depth=2" "builtin:forest?levels=1")
reference=raycast extra=()
case "$method" in
  zbuffer) extra=(--subsamples) ;;
  raycast) extra=(--subsamples) reference=zbuffer ;;
esac
i=0
for scene in "${scenes[@]}"; do
  args=(render "$scene" --method "$method" --reference "$reference" "${extra[@]}" --frames 2
        --width 160 --height 120 --quiet)
  "$lzb" "${args[@]}" --threads 2 --out "$work/one_$i" >/dev/null
  "$mpiexec" -n 2 --oversubscribe "$lzb" "${args[@]}" --threads 1 --out "$work/two_$i" >/dev/null
  for f in frame_0000.png frame_0000.exr frame_0001.png frame_0001.exr; do
    cmp "$work/one_$i/$f" "$work/two_$i/$f" || { echo "FAIL: $scene $method $f differs"; exit 1; }
  done
  python3 - "$work/one_$i/report.json" "$work/two_$i/report.json" <<'PY' || { echo "FAIL: $scene $method accuracy differs"; exit 1; }
import json, sys
one, two = (json.load(open(p))["frames"] for p in sys.argv[1:])
assert [f["accuracy"] for f in one] == [f["accuracy"] for f in two], (one, two)
PY
  echo "ok: $scene ($method) identical on 1 and 2 ranks, accuracy against $reference too"
  i=$((i + 1))
done
