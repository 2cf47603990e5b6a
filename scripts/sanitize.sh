#!/usr/bin/env bash
# Sanitizer runs (clang, Debian's compiler-rt):
#   asan  the unit tests of the core library (every test that needs no
#         simulator, viz or PCL) under AddressSanitizer +
#         UndefinedBehaviorSanitizer. The build holds the core library, those
#         tests and the fuzz targets only (scripts/fuzz.sh builds in the same
#         folder, build-asan/): static, with libFuzzer coverage. The simulator
#         and the end-to-end tests stay out: a cold compile of them would
#         double the step, and they run the same library code.
#   tsan  the concurrency tests (ctest -L threads) under ThreadSanitizer:
#         build-tsan/, the core, the simulator and concurrency_test only.
# Usage: scripts/sanitize.sh [asan|tsan|all]   (default all). Any report fails the run.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/build_env.sh
what=${1:-all}
jobs=${L2S_JOBS:-$(nproc)}
scripts/setup.sh

# Reports stop the process (-fno-sanitize-recover) and fail the test.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export TSAN_OPTIONS=${TSAN_OPTIONS:-halt_on_error=1:second_deadlock_stack=1:suppressions=$(pwd)/scripts/tsan.supp}

# No precompiled headers here: clang rejects one whose options differ in the
# least from a source's, and these builds are compiled once, in CI.
configure() {  # configure BUILD_DIR SANITIZERS [cmake args...]
  local dir=$1 sanitizers=$2
  shift 2
  CC=clang CXX=clang++ cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DL2SCALIB_BUILD_SHARED=OFF -DL2SCALIB_SANITIZE="$sanitizers" -DL2SCALIB_PRECOMPILE_HEADERS=OFF \
    -DL2SCALIB_BUILD_BENCHMARKS=OFF -DL2SCALIB_BUILD_EXAMPLES=OFF "$@" >/dev/null
}

if [ "$what" = asan ] || [ "$what" = all ]; then
  configure build-asan "address;undefined" $(scripts/fuzz.sh options)
  cmake --build build-asan -j "$jobs"
  (cd build-asan && ctest -LE slow --output-on-failure -j "$jobs")
  echo "sanitize: unit tests clean under ASan+UBSan"
fi

if [ "$what" = tsan ] || [ "$what" = all ]; then
  configure build-tsan thread -DL2SCALIB_BUILD_TOOLS=OFF -DL2SCALIB_BUILD_PCL=OFF -DL2SCALIB_BUILD_VIZ=OFF
  cmake --build build-tsan -j "$jobs" --target concurrency_test
  (cd build-tsan && ctest -L threads --output-on-failure)
  echo "sanitize: concurrency tests clean under TSan"
fi
