#!/usr/bin/env bash
# Quick start (2): set up, build, and run the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
cd "${L2S_BUILD_DIR:-build}"
ctest --output-on-failure -j "${L2S_JOBS:-$(nproc)}"
