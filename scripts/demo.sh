#!/usr/bin/env bash
# Quick start (1): set up, build, simulate the default dataset and calibrate it.
# Prints the estimate, the ground truth, e_t and e_r.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
dataset=${1:-demo_dataset}
build/l2s simulate --setting 1 --lidar vlp16 --frames 30 --noise 1 --seed 1 --overwrite "$dataset"
build/l2s calibrate "$dataset"
