#!/usr/bin/env bash
# Mutation check (issue 22): break one thing on purpose, rebuild, run the accuracy tests, and
# list which fail; every mutation must be caught by at least one test. Works in its own git
# worktree of HEAD (your checkout and build are not touched) and prints a Markdown table,
# also written to $STRENGTH_DIR/test-strength.md.
#   scripts/test-strength.sh            # every mutation
#   scripts/test-strength.sh motion-model local-ba   # some of them
#   scripts/test-strength.sh --check   # only that every mutation still matches its file
#                                      # (a ctest: code moves, mutations must follow)
# Environment: STRENGTH_DIR (default build-strength), SHARED (default ../shared), JOBS,
# CMAKE_FLAGS (e.g. -DCMAKE_CXX_COMPILER_LAUNCHER=ccache).
# STRENGTH_IN_PLACE=build: mutate this checkout instead and rebuild its existing build folder
# `build` (no fresh worktree build, minutes instead of half an hour); each mutated file is
# restored on exit, and a file with uncommitted changes is refused.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
strength_dir=$(realpath -m "${STRENGTH_DIR:-$root/build-strength}")
shared=$(realpath -m "${SHARED:-$root/../shared}")
jobs=${JOBS:-$(nproc)}
in_place=${STRENGTH_IN_PLACE:-}
if [[ -n $in_place ]]; then
  tree=$root
  build=$(realpath -m "$in_place")
  [[ -f $build/CMakeCache.txt ]] || { echo "test-strength: $build is not a build folder" >&2; exit 1; }
else
  tree=$strength_dir/tree
  build=$tree/build
fi

# name | file | perl substitution (applied once; the script fails if it matches nothing)
mutations=(
  "half-orb-features|src/lumaslam/feature/orb_extractor.cpp|s/budget_\(levels_\.featureBudget\(settings_\.nFeatures\)\)/budget_(levels_.featureBudget(settings_.nFeatures \/ 2))/"
  "motion-model|src/lumaslam/track/tracker.cpp|s/\(velocity_ && trackWithMotionModel\(\)\)/(false \&\& velocity_ \&\& trackWithMotionModel())/"
  "local-ba|src/lumaslam/mapping/local_mapper.cpp|s/if \(params_\.bundle_adjustment && /if (false \&\& params_.bundle_adjustment \&\& /"
  "rgb-bgr|src/lumaslam/core/gray_image.cpp|s/cv::COLOR_BGR2GRAY/cv::COLOR_RGB2GRAY/"
  "camera-rgb-ignored|src/lumaslam/system.cpp|s/return core::inBgrOrder\(image, settings\.camera\.rgb\);/return image;/"
  "dynamic-removal|src/lumaslam/pipeline.cpp|s/  if \(result\.dynamic_boxes\.empty\(\)\) return;/  return;/"
  "motion-first-pose|src/lumaslam/track/tracker.cpp|s/if \(count < params_\.min_confirmed_points\) \{/if (true) {/"
)
# The tests that guard accuracy, and the executables they need.
test_regex='^System(Rgbd|Stereo|Mono|Handheld|Dynamic|DynamicMemory|DynamicRpy|LowLight|MotionEvidence)\.|RealRgbd|^CliRun\.|^GrayImage\.|^TrackingSteps\.|^ApiColourOrder\.'
targets=(lumaslam_cli test_system_rgbd test_system_stereo test_system_mono test_system_real_rgbd
         test_system_handheld test_system_dynamic test_system_dynamic_memory
         test_system_dynamic_rpy test_system_low_light test_cli_run_real_rgbd test_cli_run
         test_core_gray_image test_system_real_rgbd test_system_tracking_steps
         test_system_motion_evidence test_api_colour_order)

# apply_mutation SUBSTITUTION FILE: edits FILE once; fails when the substitution matches nothing.
apply_mutation() { perl -0pi -e "\$n = ($1); END { exit(\$n ? 0 : 3) }" "$2"; }

# Applies each substitution to a copy of its file; fails naming the ones that match nothing.
check_mutations_apply() {
  local entry name file substitution copy stale=0
  copy=$(mktemp)
  for entry in "${mutations[@]}"; do
    IFS='|' read -r name file substitution <<<"$entry"
    if [[ ! -f $root/$file ]]; then
      echo "test-strength: mutation $name: $file does not exist" >&2
      stale=$((stale + 1))
      continue
    fi
    cp "$root/$file" "$copy"
    if ! apply_mutation "$substitution" "$copy"; then
      echo "test-strength: mutation $name matched nothing in $file" >&2
      stale=$((stale + 1))
    fi
  done
  rm -f "$copy"
  [[ $stale -eq 0 ]] && echo "test-strength: all ${#mutations[@]} mutations apply"
  return "$stale"
}

if [[ ${1:-} == --check ]]; then
  check_mutations_apply
  exit
fi

selected=("$@")
wanted() {
  [[ ${#selected[@]} -eq 0 ]] && return 0
  local name
  for name in "${selected[@]}"; do [[ $name == "$1" ]] && return 0; done
  return 1
}

mkdir -p "$strength_dir"
if [[ -n $in_place ]]; then
  for entry in "${mutations[@]}"; do
    IFS='|' read -r name file substitution <<<"$entry"
    git -C "$root" diff --quiet HEAD -- "$file" ||
      { echo "test-strength: $file has uncommitted changes; commit or stash them" >&2; exit 1; }
  done
else
  if [[ ! -d $tree ]]; then
    git -C "$root" worktree add --detach "$tree" HEAD >/dev/null
  else
    git -C "$tree" checkout --detach -q "$(git -C "$root" rev-parse HEAD)"
  fi
  cmake -S "$tree" -B "$build" -DCMAKE_BUILD_TYPE=Release -DLUMASLAM_SHARED_DIR="$shared" \
    ${CMAKE_FLAGS:-} >/dev/null
fi
mutated=""
restore_mutated() { [[ -z $mutated ]] || git -C "$tree" checkout -q -- "$mutated"; }
trap restore_mutated EXIT

run_tests() {  # prints the failing tests, one per line
  cmake --build "$build" -j "$jobs" --target "${targets[@]}" >"$strength_dir/build.log" 2>&1
  (cd "$build" && ctest -j "$jobs" -R "$test_regex" >"$strength_dir/ctest.log" 2>&1) || true
  sed -n '/The following tests FAILED:/,$p' "$strength_dir/ctest.log" |
    sed -n 's/^[[:space:]]*[0-9]* - \([^ ]*\) .*/\1/p'
}

echo "baseline (no mutation)" >&2
baseline=$(run_tests)
if [[ -n $baseline ]]; then
  echo "test-strength: the unmutated tree fails: $baseline" >&2
  exit 1
fi

report=$strength_dir/test-strength.md
{
  echo "| mutation | file | failing tests |"
  echo "|---|---|---|"
} >"$report"
missed=0
for entry in "${mutations[@]}"; do
  IFS='|' read -r name file substitution <<<"$entry"
  wanted "$name" || continue
  echo "mutation $name ($file)" >&2
  mutated=$file
  apply_mutation "$substitution" "$tree/$file" || {
    echo "test-strength: mutation $name matched nothing in $file" >&2
    exit 1
  }
  failing=$(run_tests)
  git -C "$tree" checkout -q -- "$file"
  mutated=""
  if [[ -z $failing ]]; then
    missed=$((missed + 1))
    echo "| $name | $file | **none: not caught** |" >>"$report"
  else
    echo "| $name | $file | $(echo "$failing" | paste -sd, | sed 's/,/, /g') |" >>"$report"
  fi
done
cmake --build "$build" -j "$jobs" --target "${targets[@]}" >/dev/null 2>&1 || true  # unmutated again
cat "$report"
[[ $missed -eq 0 ]] || { echo "test-strength: $missed mutation(s) not caught" >&2; exit 1; }
