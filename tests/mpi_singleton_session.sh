#!/usr/bin/env bash
# A process started without mpiexec keeps Open MPI's session files in a folder of its own and
# removes it (mpi/group.hpp): with Open MPI's shared session folder blocked by a file, lzb still
# starts, and it leaves nothing behind.
# usage: mpi_singleton_session.sh LZB_BINARY WORK_DIR
set -euo pipefail
lzb="$1" work="$2"
rm -rf "$work" && mkdir -p "$work/tmp"
for host in "$(hostname)" "$(hostname -s)"; do touch "$work/tmp/ompi.$host.$(id -u)"; done
TMPDIR="$work/tmp" "$lzb" info 'builtin:city?blocks=1' > "$work/info.txt" ||
  { echo "FAIL: lzb did not start beside a blocked shared session folder"; exit 1; }
left=$(find "$work/tmp" -mindepth 1 ! -name 'ompi.*')
[ -z "$left" ] || { echo "FAIL: left behind: $left"; exit 1; }
echo "ok: a singleton's session folder is its own and removed"
