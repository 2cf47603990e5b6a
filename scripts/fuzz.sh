#!/usr/bin/env bash
# libFuzzer targets (fuzz/): build them in build-asan/ (see sanitize.sh), then
#   scripts/fuzz.sh replay            run every target over its seed corpus once
#   scripts/fuzz.sh run [SECONDS]     fuzz each target in turn (default 30 s each)
#   scripts/fuzz.sh run SECONDS NAME  fuzz one target (e.g. pcd_binary_compressed)
#   scripts/fuzz.sh options           print the cmake options of build-asan/
# New inputs go to build-asan/fuzz-corpus/<target>/ (the seeds in fuzz/corpus
# are read, never changed); crashes to build-asan/fuzz-findings/<target>/.
# One target at a time: libFuzzer uses one core per job.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/build_env.sh
mode=${1:-replay}
seconds=${2:-30}
only=${3:-}
build=build-asan
targets=(pcd_ascii pcd_binary pcd_binary_compressed camera_info target_yaml params_yaml transform_yaml calibrator_add
         ros1_bag ros_messages)

dictionary() {
  case $1 in
    pcd_*) echo "-dict=fuzz/dict/pcd.dict" ;;
    calibrator_add) echo "-max_len=200000" ;;
    ros1_bag) echo "-max_len=20000 -dict=fuzz/dict/ros1_bag.dict" ;;
    ros_messages) echo "-max_len=5000" ;;
    *) echo "-dict=fuzz/dict/yaml.dict" ;;
  esac
}

# The fuzz targets link the core library only: no simulator, viz, PCL or tools.
options=(-DL2SCALIB_BUILD_FUZZERS=ON -DL2SCALIB_BUILD_SIM=OFF -DL2SCALIB_BUILD_VIZ=OFF
         -DL2SCALIB_BUILD_PCL=OFF -DL2SCALIB_BUILD_TOOLS=OFF)
if [ "$mode" = options ]; then
  echo "${options[@]}"
  exit 0
fi
if [ ! -d "$build" ]; then
  CC=clang CXX=clang++ cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DL2SCALIB_BUILD_SHARED=OFF \
    -DL2SCALIB_SANITIZE="address;undefined" -DL2SCALIB_PRECOMPILE_HEADERS=OFF -DL2SCALIB_BUILD_BENCHMARKS=OFF -DL2SCALIB_BUILD_EXAMPLES=OFF \
    "${options[@]}" >/dev/null
fi
cmake --build "$build" -j "${L2S_JOBS:-$(nproc)}" --target fuzzers

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
for target in "${targets[@]}"; do
  [ -n "$only" ] && [ "$only" != "$target" ] && continue
  binary=$build/fuzz/fuzz_$target
  seeds=fuzz/corpus/$target
  if [ "$mode" = replay ]; then
    "$binary" -runs=0 $(dictionary "$target") "$seeds" 2>&1 | tail -1
  else
    corpus=$build/fuzz-corpus/$target findings=$build/fuzz-findings/$target
    mkdir -p "$corpus" "$findings"
    echo "fuzz: $target for $seconds s"
    "$binary" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=20 -print_final_stats=1 \
      -artifact_prefix="$findings/" $(dictionary "$target") "$corpus" "$seeds" 2>&1 | tail -12
  fi
done
echo "fuzz: $mode done"
