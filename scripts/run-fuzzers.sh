#!/usr/bin/env bash
# Runs each libFuzzer target of a LUMASLAM_FUZZ build (`make fuzz`, docs/testing.md) for
# SECONDS on its seeds: fuzz/corpus/<name>, the generated seeds and fuzz/regressions/<name>.
# New inputs go to BUILD/fuzz/work/<name>, crash/leak/timeout inputs to BUILD/fuzz/findings/<name>.
# Exits non-zero when any target found something; every target runs regardless.
# usage: scripts/run-fuzzers.sh BUILD SECONDS NAME...
set -uo pipefail
build=$1 seconds=$2
shift 2
source_dir=$(cd "$(dirname "$0")/.." && pwd)
"$build/fuzz/fuzz_seeds" "$build/fuzz/corpus" || exit 1
export ASAN_OPTIONS=detect_leaks=1:check_initialization_order=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
failed=()
for name in "$@"; do
  work=$build/fuzz/work/$name findings=$build/fuzz/findings/$name
  mkdir -p "$work" "$findings"
  seeds=()
  for dir in "$source_dir/fuzz/corpus/$name" "$build/fuzz/corpus/$name" \
             "$source_dir/fuzz/regressions/$name"; do
    [[ -d $dir ]] && seeds+=("$dir")
  done
  echo "== fuzz_$name: ${seconds}s"
  # -timeout: one input taking 10 s is a hang; -rss_limit_mb: a length field that makes the
  # parser allocate gigabytes is a finding too.
  if ! nice "$build/fuzz/fuzz_$name" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
      -max_len=65536 -artifact_prefix="$findings/" -print_final_stats=1 "$work" "${seeds[@]}" \
      2>"$build/fuzz/$name.log"; then
    failed+=("$name")
    tail -n 60 "$build/fuzz/$name.log"
  fi
  grep -E '^stat::(number_of_executed_units|average_exec_per_sec|peak_rss_mb)' \
    "$build/fuzz/$name.log" | tr '\n' ' '
  echo
done
if ((${#failed[@]})); then
  echo "fuzzing found problems in: ${failed[*]} (inputs in $build/fuzz/findings/)" >&2
  exit 1
fi
echo "no findings"
