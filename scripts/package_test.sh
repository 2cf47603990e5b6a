#!/usr/bin/env bash
# The installed package consumed the four ways an outside project does, each
# with a tiny consumer (tests/package) that is built and run:
#   shared      find_package(l2scalib) of the shared install; the consumer
#               needs libl2scalib only (OpenCV and yaml-cpp stay inside it)
#   static      find_package(l2scalib) of a static install of the core
#               library alone (build-static/); the consumer needs no
#               libl2scalib at run time
#   components  find_package(l2scalib COMPONENTS sim pcl recording), and the examples
#               built outside (03 feeds pcl::PointCloud sweeps to the Calibrator)
#   subproject  add_subdirectory of the source tree (the core alone), which
#               must leave its parent's settings alone and build no tests,
#               tools or examples
# Usage: scripts/package_test.sh [SHARED_BUILD_DIR]   (default build/, built already)
# Build folders sit beside build/ so ccache finds their objects (same depth).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/build_env.sh
root=$(pwd)
shared_build=${1:-build}
jobs=${L2S_JOBS:-$(nproc)}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)

consumer() {  # consumer NAME [cmake args...]: configure, build and run tests/package
  local name=$1
  shift
  cmake -S tests/package -B "build-consumer-$name" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" "$@" >/dev/null
  cmake --build "build-consumer-$name" -j "$jobs" >/dev/null
  for program in build-consumer-"$name"/consumer*; do
    [ -x "$program" ] && "$program" "$work"
  done
}

needed() { readelf -d "$1" | sed -n 's/.*Shared library: \[\(.*\)\]/\1/p'; }

echo "package: shared"
cmake --install "$shared_build" --prefix "$work/shared" >/dev/null
consumer shared -DCMAKE_PREFIX_PATH="$work/shared"
needed build-consumer-shared/consumer | grep -q '^libl2scalib\.so' ||
  { echo "package: the shared consumer does not load libl2scalib" >&2; exit 1; }
if needed build-consumer-shared/consumer | grep -Eq 'opencv|yaml-cpp'; then
  echo "package: OpenCV or yaml-cpp leaked into the shared consumer's link" >&2
  exit 1
fi

echo "package: static"
# The core library only: the components' packaging is checked on the shared
# install, and each component more would be another cold compile in CI.
cmake -S . -B build-static -DCMAKE_BUILD_TYPE=Release -DL2SCALIB_BUILD_SHARED=OFF \
  -DL2SCALIB_BUILD_TESTS=OFF -DL2SCALIB_BUILD_BENCHMARKS=OFF -DL2SCALIB_BUILD_EXAMPLES=OFF \
  -DL2SCALIB_BUILD_TOOLS=OFF -DL2SCALIB_BUILD_SIM=OFF -DL2SCALIB_BUILD_VIZ=OFF \
  -DL2SCALIB_BUILD_PCL=OFF -DL2SCALIB_BUILD_RECORDING=OFF >/dev/null
cmake --build build-static -j "$jobs" >/dev/null
cmake --install build-static --prefix "$work/static" >/dev/null
consumer static -DCMAKE_PREFIX_PATH="$work/static"
if needed build-consumer-static/consumer | grep -q l2scalib; then
  echo "package: the static consumer still loads a shared l2scalib" >&2
  exit 1
fi

echo "package: components sim pcl recording, and the examples outside"
consumer components -DCMAKE_PREFIX_PATH="$work/shared" -DL2S_COMPONENTS="sim;pcl;recording"
cmake -S examples -B build-examples-outside -DCMAKE_PREFIX_PATH="$work/shared" -DCMAKE_BUILD_TYPE=Release \
  "${launcher[@]}" >/dev/null
cmake --build build-examples-outside -j "$jobs" >/dev/null
[ -x build-examples-outside/03_calibrate_pcl_clouds ] ||
  { echo "package: example 03 (pcl component) was not built" >&2; exit 1; }

echo "package: subproject"
consumer subproject -DL2S_CONSUME=subproject -DL2S_SOURCE_DIR="$root" \
  -DL2S_SUBPROJECT_BINARY_DIR="$root/build-consumer-subproject-l2s"

# The prefix of the shared install, for callers that go on using it.
echo "package: all four ways passed"
