#!/usr/bin/env bash
# Installs the Debian 12 packages lzb builds and runs with; idempotent, quiet when all are present.
# --test adds what the tests fetch their real meshes from (libcgal-demo, assimp-testmodels);
# --bench adds gnuplot for the benchmark plots; --fuzz adds clang 14 with libFuzzer and the
# sanitizer runtimes (scripts/fuzz.sh). The ASan + UBSan build (scripts/sanitize.sh) needs only
# g++'s own runtimes, which build-essential brings.
set -euo pipefail
packages=(
  build-essential cmake pkg-config git ccache
  libopenmpi-dev openmpi-bin
  libglm-dev libembree-dev libosmesa6-dev libopenexr-dev libpng-dev libopenimageio-dev
  openimageio-tools  # OpenImageIO's CMake config fails without its tools' files
  libassimp-dev libcli11-dev nlohmann-json3-dev libtomlplusplus-dev librandom123-dev
  libabsl-dev
  libgtest-dev
)
for arg in "$@"; do
  case "$arg" in
    --test) packages+=(libcgal-demo assimp-testmodels) ;;
    --bench) packages+=(gnuplot-nox libcgal-demo) ;;
    --fuzz) packages+=(clang-14 libclang-rt-14-dev libomp-14-dev) ;;
    *) echo "install-deps: unknown option $arg" >&2; exit 2 ;;
  esac
done
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "install-deps: installing ${missing[*]}"
  sudo_cmd=""
  [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo_cmd apt-get update -qq
  $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
