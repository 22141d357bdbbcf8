#!/usr/bin/env bash
# The sample tree's node server (--node-server): on 2 and 3 ranks (the last serves the store, the
# others render) the same files as the 1-rank out-of-core run of the same store; per frame the
# render ranks' shares of triangles and splats sum to the 1-rank counts (on 3 ranks both render
# ranks drew), the server drew nothing, and it served exactly the nodes and bytes the render
# ranks loaded (prefetch off, so every load happens inside its frame); with prefetch on, the same
# files, and the server served at least what the render ranks loaded.
# usage: mpi_node_server.sh LZB_BINARY WORK_DIR MPIEXEC [DATA_DIR]
set -euo pipefail
lzb="$1" work="$2" mpiexec="$3" data="${4:-}"
rm -rf "$work" && mkdir -p "$work"
scenes=("builtin:city?blocks=3" "builtin:sphereflake?depth=2")
[ -n "$data" ] && [ -s "$data/bunny00.off" ] && scenes+=("$data/bunny00.off")
i=0
for scene in "${scenes[@]}"; do
  store="$work/store_$i.lzbtree"
  "$lzb" build-tree "$scene" --out "$store" --leaf-triangles 8 --quiet >/dev/null
  args=(render "$scene" --method sampletree --tree "$store" --cache-mb 0.25 --splat 2
        --reference raycast --frames 2 --width 160 --height 120 --threads 1 --quiet)
  "$lzb" "${args[@]}" --cache-levels 0 --out "$work/one_$i" >/dev/null
  for n in 2 3; do
    timeout 300 "$mpiexec" -n "$n" --oversubscribe "$lzb" "${args[@]}" --cache-levels 0 \
      --node-server --out "$work/served${n}_$i" >/dev/null
  done
  timeout 300 "$mpiexec" -n 3 --oversubscribe "$lzb" "${args[@]}" --cache-levels 2 --node-server \
    --out "$work/prefetch_$i" >/dev/null
  for run in served2 served3 prefetch; do
    for f in frame_0000.png frame_0000.exr frame_0001.png frame_0001.exr; do
      cmp "$work/one_$i/$f" "$work/${run}_$i/$f" || { echo "FAIL: $scene $f differs ($run)"; exit 1; }
    done
  done
  python3 - "$work/one_$i/report.json" "$work/served2_$i/report.json" "$work/served3_$i/report.json" \
    "$work/prefetch_$i/report.json" <<'PY' || { echo "FAIL: $scene"; exit 1; }
import json, sys
one, two, three, prefetch = (json.load(open(p)) for p in sys.argv[1:])

def c(entry, key):
    return entry["counts"].get(key, 0)

for rep in (two, three, prefetch):
    assert rep["method_parameters"]["node_server"] is True
    served = loaded = 0
    for f, (a, b) in enumerate(zip(one["frames"], rep["frames"])):
        assert a["accuracy"] == b["accuracy"], ("accuracy differs", a["accuracy"], b["accuracy"])
        *render, server = b["ranks"]
        assert len(render) == rep["ranks"] - 1 >= 1
        for key in ("triangles_drawn", "splats_drawn", "nodes_drawn", "nodes_loaded"):
            assert c(server, key) == 0, ("the server drew or loaded", key, server["counts"])
        for key in ("triangles_drawn", "splats_drawn"):
            shares = [c(r, key) for r in render]
            assert sum(shares) == c(a, key), (key, shares, "sum to", sum(shares), "not", c(a, key))
            if len(render) > 1 and c(a, key) >= 1000:
                assert all(s > 0 for s in shares), ("a render rank drew no", key, shares)
        for r in render:
            assert c(r, "file_bytes_read") == 0, ("a render rank read the store", r["counts"])
            assert "remote_wait_seconds" in r["counts"], r["counts"]
        served += c(server, "served_nodes")
        loaded += sum(c(r, "nodes_loaded") for r in render)
        if rep is not prefetch:  # every load inside its frame: the counts match frame by frame
            assert c(server, "served_nodes") == sum(c(r, "nodes_loaded") for r in render), b["ranks"]
            assert c(server, "served_bytes") == sum(c(r, "bytes_read") for r in render), b["ranks"]
            if f == 0:  # a fresh cache loads each drawn node once
                assert c(server, "served_bytes") == 48 * c(b, "triangles_drawn"), b["ranks"]
        assert served >= loaded, ("loads the server did not serve", served, loaded)
    assert served > 0 and c(rep["frames"][0]["ranks"][-1], "file_bytes_read") > 0, "nothing served"
print("  3 ranks, frame 0: triangles_drawn",
      [c(r, "triangles_drawn") for r in three["frames"][0]["ranks"]], "served_nodes",
      [c(r, "served_nodes") for r in three["frames"][0]["ranks"]], "nodes_loaded",
      [c(r, "nodes_loaded") for r in three["frames"][0]["ranks"]])
PY
  echo "ok: $scene: --node-server on 2 and 3 ranks (prefetch 0 and 2) writes the 1-rank files, render ranks split the work, the server served the loads"
  i=$((i + 1))
done
