#!/usr/bin/env bash
# Error paths that root never reaches (root reads and writes regardless of permissions), run under
# an unprivileged identity: as root, a uid that owns nothing and has no account (setpriv), so
# nothing is added to or left on the machine; as any other user, that user. The GoogleTest cases
# that skip themselves as root must run and pass here, and lzb render must refuse an unreadable
# scene and an unwritable --out with exit status 2, naming them, and write nothing.
# usage: unprivileged.sh WORK_DIR SCENE_TEST IMAGE_TEST LZB_BINARY (WORK_DIR: used when not root)
set -euo pipefail
work="$1" scene_test="$2" image_test="$3" lzb="$4"
# As root the work folder is a fresh one in /tmp: the unprivileged uid must be able to walk every
# folder above it, which a checkout under a private (0700) folder, such as mktemp -d's, forbids.
if [ "$(id -u)" -eq 0 ]; then
  work=$(mktemp -d /tmp/lzb-unprivileged.XXXXXX)
  trap 'rm -rf "$work"' EXIT
else
  rm -rf "$work" && mkdir -p "$work"
fi
# The programs are copied into the work folder, where the unprivileged uid can run them.
cp "$scene_test" "$image_test" "$lzb" "$work/"
mkdir -p "$work/tmp"
chmod 755 "$work"
chmod 1777 "$work/tmp"
if [ "$(id -u)" -eq 0 ]; then
  uid=61000
  while getent passwd "$uid" >/dev/null || getent group "$uid" >/dev/null; do uid=$((uid + 1)); done
  as_user=(setpriv --reuid="$uid" --regid="$uid" --clear-groups)
  # No way to drop root (no setpriv, or no CAP_SETUID in this container): ctest's SKIP (77).
  if ! "${as_user[@]}" true 2>/dev/null; then
    echo "SKIP: cannot run as an unprivileged uid here (setpriv --reuid=$uid failed)"
    exit 77
  fi
  echo "running as uid $uid (no account)"
else
  as_user=()
fi
run() { env HOME="$work/tmp" TMPDIR="$work/tmp" "${as_user[@]}" "$@"; }

# The GoogleTest cases: they must run (not skip) and pass.
gtest_case() {  # program, filter
  local out status=0
  out=$(run "$work/$(basename "$1")" --gtest_filter="$2" 2>&1) || status=$?
  [ "$status" -eq 0 ] || { echo "FAIL: $2: $out"; exit 1; }
  grep -q "\[  PASSED  \] 1 test" <<<"$out" || { echo "FAIL: $2 did not run: $out"; exit 1; }
  ! grep -q "SKIPPED" <<<"$out" || { echo "FAIL: $2 skipped: $out"; exit 1; }
  echo "ok: $2"
}
gtest_case "$scene_test" "MeshFile.MissingDirectoryAndUnreadableFiles"
gtest_case "$image_test" "FrameIoTest.UnwritableDirectoryThrowsAndLeavesNothing"

# lzb render: exit status 2, the message names the culprit, nothing written.
refused() {  # name, what the message must name, folder that must stay absent, lzb arguments...
  local name="$1" names="$2" absent="$3" out status=0
  shift 3
  out=$(run "$work/$(basename "$lzb")" render "$@" --quiet 2>&1) || status=$?
  [ "$status" -eq 2 ] || { echo "FAIL: $name exited $status (want 2): $out"; exit 1; }
  grep -qF -- "$names" <<<"$out" || { echo "FAIL: $name does not name $names: $out"; exit 1; }
  [ ! -e "$absent" ] || { echo "FAIL: $name left $absent"; exit 1; }
  echo "ok: $name"
}
printf 'OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' >"$work/locked.off"
chmod 600 "$work/locked.off"  # the owner's (root's or the test user's own, then made unreadable)
[ "$(id -u)" -eq 0 ] || chmod 000 "$work/locked.off"
refused "unreadable mesh" "locked.off" "$work/tmp/out1" "$work/locked.off" --out "$work/tmp/out1"
mkdir -p "$work/sealed"
chmod 555 "$work/sealed"
refused "unwritable --out" "--out" "$work/sealed/out" "builtin:sphereflake?depth=1" \
  --width 32 --height 24 --out "$work/sealed/out"
refused "unwritable --out below" "--out" "$work/sealed/a" "builtin:sphereflake?depth=1" \
  --width 32 --height 24 --out "$work/sealed/a/b/c"
# The same identity renders where it may write (so the refusals above are about permissions).
status=0
out=$(run "$work/$(basename "$lzb")" render "builtin:sphereflake?depth=1" --width 32 --height 24 \
  --threads 1 --quiet --out "$work/tmp/ok" 2>&1) || status=$?
[ "$status" -eq 0 ] && [ -s "$work/tmp/ok/frame_0000.png" ] || { echo "FAIL: render: $out"; exit 1; }
echo "ok: renders into a folder it owns"
chmod -R u+rwX "$work"
