#!/usr/bin/env bash
# Rebuilds the default place-recognition vocabulary data/vocabulary/lumaslam_orb_k8l5.bin
# (data/vocabulary/README.md) from the real images in the shared data folder.
#   scripts/train-default-vocabulary.sh [LUMASLAM_BINARY] [SHARED_DIR] [OUT]
# Environment: K=10 LEVELS=4 trains another shape, SEED=2 another seed, EXCLUDE=7scenes (or
# kitti, ...) leaves out the inputs whose path contains it (leave-one-out measurements in
# docs/place_recognition.md).
# Deterministic: the same binary, images and seed give the same bytes.
set -euo pipefail

here=$(cd "$(dirname "$0")/.." && pwd)
lumaslam=${1:-$here/build/lumaslam}
shared=${2:-$here/../shared}
out=${3:-$here/data/vocabulary/lumaslam_orb_k8l5.bin}
k=${K:-8}
levels=${LEVELS:-5}
data=$shared/data

# INPUT@N: every Nth frame. Sequences are thinned so that no one scene dominates: 7-Scenes
# (497 hand-held Kinect frames) every 4th, KITTI 07 (160 frames, car) every 2nd, the EuRoC
# excerpt (the MAV stands still) and the static-camera video sparsely; still images all.
inputs=(
  "tum:$data/7scenes_redkitchen@4"
  "kitti-mono:$data/kitti/odometry_07_first160/sequences/07@2"
  "$data/euroc/V1_01_easy_micro/mav0/cam0/data@10"
  "$data/euroc/V1_01_easy_micro/mav0/cam1/data@10"
  "video:$data/opencv_samples/vtest/vtest.avi@40"
  "$data/llvip/night_people_sample/visible/test"
  "$data/llvip/night_people_sample/visible/train"
  "$data/ultralytics_yolov5/data/images"
)
for scene in "$data"/mefb/exposure_pairs_43/input/*/; do
  inputs+=("${scene%/}")
done

selected=()
for input in "${inputs[@]}"; do
  [[ -n "${EXCLUDE:-}" && "$input" == *"$EXCLUDE"* ]] || selected+=("$input")
done

"$lumaslam" vocab train --k "$k" --levels "$levels" --features 1000 --seed "${SEED:-1}" --out "$out" \
  "${selected[@]}"
"$lumaslam" vocab info "$out"
sha256sum "$out"
