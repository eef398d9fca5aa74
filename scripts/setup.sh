#!/usr/bin/env bash
# Installs what Wisp needs from Debian 12's packages (only what is missing) and builds it.
# Safe to run again: installed packages are skipped and the build is incremental.
#
#   scripts/setup.sh              Release build in build/
#   scripts/setup.sh --sanitize   Debug build with AddressSanitizer + UBSan in build-asan/
#   scripts/setup.sh --fuzz       the libFuzzer targets (clang, ASan + UBSan) in build-fuzz/
#                                 (scripts/fuzz.sh runs them)
#   WISP_MARCH=x86-64-v3 scripts/setup.sh [--sanitize]
#                                 builds everything for that CPU instead of the portable default
#                                 (x86-64-v2, the solver's SSE4/AVX2/AVX-512 kernels chosen at run
#                                 time): here AVX2 without AVX-512, as on an AVX2-only machine;
#                                 WISP_MARCH= goes back to the portable default
set -euo pipefail

cd "$(dirname "$0")/.."

packages=(
  build-essential cmake ninja-build pkg-config
  qt6-base-dev libqt6opengl6-dev libgl-dev libgl1-mesa-dri
  libglm-dev nlohmann-json3-dev libhwy-dev
  libgtest-dev libbenchmark-dev clang-format python3
  xvfb xauth
)
# Only the fuzz build uses clang (libFuzzer); every other build is g++.
if [ "${1:-}" = "--fuzz" ]; then packages+=(clang-14 libclang-rt-14-dev); fi
# The tests read the USD export back with an independent parser (npm tinyusdz): node and npm from
# Debian unless a node is already installed (a NodeSource node brings its own npm).
if [ "${1:-}" != "--fuzz" ] && ! command -v node > /dev/null; then packages+=(nodejs npm); fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "== installing: ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

build_dir=build
cmake_args=(-G Ninja -DCMAKE_BUILD_TYPE=Release)
if [ "${1:-}" = "--sanitize" ]; then
  build_dir=build-asan
  cmake_args=(-G Ninja -DCMAKE_BUILD_TYPE=Debug -DWISP_SANITIZE=ON)
elif [ "${1:-}" = "--fuzz" ]; then
  # Debug keeps assertions; WISP_FUZZ adds -O1 and the sanitizers, and builds only sim, io, fuzz/.
  build_dir=build-fuzz
  cmake_args=(-G Ninja -DCMAKE_BUILD_TYPE=Debug -DWISP_FUZZ=ON -DCMAKE_CXX_COMPILER=clang++-14)
fi

# Only when asked: an unset WISP_MARCH leaves the build folder's choice as it was.
if [ -n "${WISP_MARCH+set}" ]; then cmake_args+=("-DWISP_MARCH=$WISP_MARCH"); fi
cmake -S . -B "$build_dir" "${cmake_args[@]}" > /dev/null
cmake --build "$build_dir" -j"$(nproc)"
# The independent USD reader the tests use (npm tinyusdz, pinned), into the build folder.
if [ "${1:-}" != "--fuzz" ]; then tests/usd/install-tinyusdz.sh "$build_dir/tinyusdz" || true; fi
echo "== built in $build_dir/"
