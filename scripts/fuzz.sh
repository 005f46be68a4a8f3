#!/usr/bin/env bash
# Runs each libFuzzer target (docs/fuzzing.md) for a given time: first over its seed corpus and the
# inputs of every defect found before (fuzz/corpus/<target>, fuzz/regressions/<target>), then
# fuzzing from them. A crash, a sanitizer's report, a timeout or memory past the limit fails the
# script; libFuzzer leaves the input as crash-*, timeout-* or oom-* in build/fuzz/findings/<target>/.
#
#   scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]     (default: 60 s, every target)
#
# The mutations start from a fixed seed (DENTSPH_FUZZ_SEED, default 1), so that the CI's minute
# repeats the same search on the same code; DENTSPH_FUZZ_SEED=0 lets libFuzzer pick one (a
# longer campaign, docs/fuzzing.md).
#
# Builds the fuzz preset first (clang-14: scripts/install-deps.sh --sanitizers installs it).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(scene procedure recording mesh protocol input_script)

cmake --preset fuzz > /dev/null
cmake --build build/fuzz -j"$(nproc)" --target $(printf 'fuzz_%s ' "${targets[@]}")

# A scene may take at most this much memory (dentsph/limits.hpp): large but legal scenes are
# refused before they are made instead of reaching libFuzzer's memory limit.
export DENTSPH_MEMORY_LIMIT_MB=256
export ASAN_OPTIONS="detect_leaks=1:allocator_may_return_null=1"
# assimp's own leaks (fuzz/lsan.supp says which): not dentsph's memory.
export LSAN_OPTIONS="suppressions=$PWD/fuzz/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
status=0
for t in "${targets[@]}"; do
  work="build/fuzz/corpus/$t"
  findings="build/fuzz/findings/$t"
  mkdir -p "$work" "$findings"
  regressions=()
  [ -d "fuzz/regressions/$t" ] && regressions=("fuzz/regressions/$t")
  echo "== fuzz_$t: the seeds and the regressions"
  if ! "build/fuzz/fuzz/fuzz_$t" -runs=0 -timeout=20 -rss_limit_mb=3072 "fuzz/corpus/$t" "${regressions[@]}"; then
    echo "fuzz_$t: a seed or a regression input fails"
    status=1
    continue
  fi
  echo "== fuzz_$t: ${seconds} s"
  if ! "build/fuzz/fuzz/fuzz_$t" -max_total_time="$seconds" -seed="${DENTSPH_FUZZ_SEED:-1}" -timeout=20 \
      -rss_limit_mb=3072 -max_len=8192 \
      -print_final_stats=1 -artifact_prefix="$findings/" "$work" "fuzz/corpus/$t"; then
    echo "fuzz_$t: found a defect; its input is in $findings/ (keep it in fuzz/regressions/$t/ once fixed)"
    status=1
  fi
done
exit $status
