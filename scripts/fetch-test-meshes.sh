#!/usr/bin/env bash
# Extracts real scanned meshes from the Debian package libcgal-demo's data archive into DIR
# (default build/data). They are never committed.
set -euo pipefail
dir="${1:-build/data}"
archive=/usr/share/doc/libcgal-dev/data.tar.gz
meshes=(bunny00.off armadillo.off elephant.off fandisk.off mannequin-devil.off ChineseDragon-10kv.off)
mkdir -p "$dir"
todo=()
for m in "${meshes[@]}"; do [ -s "$dir/$m" ] || todo+=("data/meshes/$m"); done
((${#todo[@]})) || exit 0
[ -f "$archive" ] || { echo "fetch-test-meshes: $archive missing (apt-get install libcgal-demo)" >&2; exit 1; }
tar -xzf "$archive" -C "$dir" --strip-components=2 "${todo[@]}"
