#!/usr/bin/env bash
# Installs every system dependency of l2scalib from Debian's packages, when missing.
# Safe to run again: it installs nothing when everything is there.
set -euo pipefail

packages=(
  build-essential cmake ninja-build ccache pkg-config
  mold  # the linker (cmake/L2sLinker.cmake): links the programs several times faster than ld.bfd
  libeigen3-dev libpcl-dev libopencv-dev libopencv-contrib-dev libyaml-cpp-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libbz2-dev liblz4-dev  # l2scalib::recording: ROS 1 bag chunks
  python3-rosbag  # ros1_bag_test: bags written by ROS's own writer
  clang libclang-rt-14-dev  # scripts/sanitize.sh and scripts/fuzz.sh: sanitizers and libFuzzer
  python3 python3-yaml python3-matplotlib  # dataset checker and the suite's plots
)

missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all dependencies present"
  exit 0
fi

echo "setup: installing ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "setup: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo_cmd=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done"
