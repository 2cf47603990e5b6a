#!/usr/bin/env bash
# Configures and builds l2scalib (Release) into build/. Extra arguments go to cmake.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/build_env.sh
build_dir=${L2S_BUILD_DIR:-build}
jobs=${L2S_JOBS:-$(nproc)}
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$build_dir" -j "$jobs"
