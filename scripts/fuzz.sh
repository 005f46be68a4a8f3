#!/usr/bin/env bash
# Runs each libFuzzer target (docs/fuzzing.md) for a given time: first over its seed corpus and the
# inputs of every defect found before (fuzz/corpus/<target>, fuzz/regressions/<target>), then
# fuzzing from them. A crash, a sanitizer's report, a timeout or memory past the limit fails the
# script; libFuzzer leaves the input as crash-*, timeout-* or oom-* in build/fuzz/findings/<target>/.
#
#   scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]     (default: 60 s, every target)
#
# The mutations start from a fixed seed (DENTSPH_FUZZ_SEED, default 1) and run a fixed count of
# inputs (the seconds' worth on the project's machine), so that the CI's minute repeats the same
# search on the same code as a run here; DENTSPH_FUZZ_SEED=0 lets libFuzzer pick one and fuzzes for
# the time (a longer campaign, docs/fuzzing.md).
#
# Builds the fuzz preset first (clang-14: scripts/install-deps.sh --sanitizers installs it).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(scene procedure recording mesh protocol store_address input_script report_folder realtime_options)

cmake --preset fuzz > /dev/null
cmake --build build/fuzz -j"$(nproc)" --target $(printf 'fuzz_%s ' "${targets[@]}")

# A scene may take at most this much memory (dentsph/limits.hpp): large but legal scenes are
# refused before they are made instead of reaching libFuzzer's memory limit.
export DENTSPH_MEMORY_LIMIT_MB=256
export ASAN_OPTIONS="detect_leaks=1:allocator_may_return_null=1"
# assimp's own leaks (fuzz/lsan.supp says which): not dentsph's memory.
export LSAN_OPTIONS="suppressions=$PWD/fuzz/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# Runs a second of each target on the project's 2-core machine (idle, 150 s runs from the seeds).
declare -A runs_per_s=([scene]=190 [procedure]=1300 [recording]=1350 [mesh]=1300 [protocol]=1400 [store_address]=50000 [input_script]=25000 [report_folder]=1500 [realtime_options]=25000)
# The longest an input may take before libFuzzer calls it a hang (s). A legal dental scene file is
# built whole (the tooth lined, and for the iisph solver, the dental default, its wall field): a
# Class II cavity takes 0.5 s natively and 17 to 26 s under ASan and coverage, so the scene target
# gets 60 s; the others 20 s.
declare -A timeout_s=([scene]=60)
status=0
failed=()
for t in "${targets[@]}"; do
  work="build/fuzz/corpus/$t"
  findings="build/fuzz/findings/$t"
  mkdir -p "$work" "$findings"
  regressions=()
  [ -d "fuzz/regressions/$t" ] && regressions=("fuzz/regressions/$t")
  echo "== fuzz_$t: the seeds and the regressions"
  timeout="${timeout_s[$t]:-20}"
  if ! "build/fuzz/fuzz/fuzz_$t" -runs=0 -timeout="$timeout" -rss_limit_mb=3072 "fuzz/corpus/$t" "${regressions[@]}"; then
    echo "fuzz_$t: a seed or a regression input fails"
    status=1
    failed+=("$t (a seed or a regression)")
    continue
  fi
  # With the fixed seed, a count of runs (the target's rate on the project's machine times the
  # seconds) rather than a time: the same mutations, so the same search, on any machine that
  # reaches the count in time; a machine three times slower stops at the time (3 x SECONDS).
  seed="${DENTSPH_FUZZ_SEED:-1}"
  limit=(-max_total_time="$seconds")
  if [ "$seed" != 0 ]; then
    limit=(-runs=$((runs_per_s[$t] * seconds)) -max_total_time=$((3 * seconds)))
  fi
  echo "== fuzz_$t: ${seconds} s (${limit[*]})"
  if ! "build/fuzz/fuzz/fuzz_$t" "${limit[@]}" -seed="$seed" -timeout="$timeout" \
      -rss_limit_mb=3072 -max_len=8192 \
      -print_final_stats=1 -artifact_prefix="$findings/" "$work" "fuzz/corpus/$t"; then
    echo "fuzz_$t: found a defect; its input is in $findings/ (keep it in fuzz/regressions/$t/ once fixed)"
    status=1
    failed+=("$t")
  fi
done
# What failed, last, where a log's tail shows it: each finding's name and its bytes (base64, up to
# 4 KiB), so that a run elsewhere can be reproduced from the log alone.
if [ ${#failed[@]} -gt 0 ]; then
  echo "== fuzz: failed: ${failed[*]}"
  for t in "${targets[@]}"; do
    for f in "build/fuzz/findings/$t"/*; do
      [ -f "$f" ] || continue
      echo "== $f ($(stat -c %s "$f") bytes), base64:"
      head -c 4096 "$f" | base64 -w 0
      echo
    done
  done
else
  echo "== fuzz: every target clean"
fi
exit $status
