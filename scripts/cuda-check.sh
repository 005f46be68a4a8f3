#!/usr/bin/env bash
# Checks and measures the CUDA backend on a GPU (docs/cuda.md, "On a device").
#
#   scripts/cuda-check.sh pack     on the build machine (nvcc, Debian's libraries): builds the cuda
#                                  preset and copies the programs, the shared libraries they need
#                                  that a bare CUDA machine lacks, and the kernels' resource report
#                                  into .device/ (ignored by git; about 20 MiB)
#   scripts/cuda-check.sh device   on the GPU machine, from the repository root, with .device/
#                                  carried along: the device tests, the haptic runtime on the GPU
#                                  and its replay, compute-sanitizer memcheck and racecheck on the
#                                  parity tests, and the benchmark; everything written to $OUT (at
#                                  most 8 files), a summary printed last
#   scripts/cuda-check.sh device [tests] [realtime] [sanitize] [bench] [tune] [--quick]
#                                  only those parts (default: all five, about 10 minutes at most:
#                                  leave out tune, or give --quick, to stay under the device's
#                                  10-minute limit for one command); --quick: a short benchmark sweep
#
# A device session: `scripts/cuda-check.sh pack` here, then one device call running
# `bash scripts/cuda-check.sh device` with carry [".device"]; copy $OUT/<gpu>.json and .txt into
# bench/results/ and commit them.
set -uo pipefail
cd "$(dirname "$0")/.."
mode="${1:-}"

pack() {
  set -e
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD/..}" CCACHE_DIR="${CCACHE_DIR:-$HOME/.cache/ccache}"
  cmake --preset cuda >/dev/null
  cmake --build --preset cuda -j2 --target dentsph test_cuda
  rm -rf .device && mkdir -p .device/bin .device/lib
  cp build/cuda/apps/cli/dentsph build/cuda/tests/test_cuda .device/bin/
  strip .device/bin/*
  # Every shared library the programs load except the C and C++ runtimes the GPU machine has.
  ldd .device/bin/* | awk '/=> \// {print $3}' | sort -u |
    grep -vE '/(libc|libm|libpthread|libdl|librt|ld-linux[^/]*|libstdc\+\+|libgcc_s)\.so' |
    xargs -r cp -L -t .device/lib
  # Registers, shared memory, spills of every kernel (ptxas's report; this machine has no cuobjdump).
  for f in src/backend/cuda/*.cu; do
    /usr/local/cuda/bin/nvcc -std=c++20 -arch=sm_90 -O3 -Isrc -Iinclude --resource-usage -c "$f" -o /dev/null 2>&1
  done | grep -E "Function properties|registers|spill" >.device/resource-usage.txt
  git rev-parse HEAD >.device/commit
  du -sh .device
  echo "packed: now run 'bash scripts/cuda-check.sh device' on the GPU machine with carry [\".device\"]"
}

device() {
  local quick="" parts=()
  for a in "$@"; do
    case "$a" in
      --quick) quick=--quick ;;
      tests | realtime | sanitize | bench | tune) parts+=("$a") ;;
      *) echo "unknown part '$a': choose tests, realtime, sanitize, bench, tune (and --quick)"; exit 2 ;;
    esac
  done
  [ ${#parts[@]} -eq 0 ] && parts=(tests realtime sanitize bench tune)
  want() { [[ " ${parts[*]} " == *" $1 "* ]]; }
  : "${OUT:=/tmp/dentsph-cuda-out}"
  mkdir -p "$OUT"
  export LD_LIBRARY_PATH="$PWD/.device/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  local bin=.device/bin summary="$OUT/summary.txt"
  [ -x "$bin/test_cuda" ] || { echo "no .device/bin/test_cuda: run 'scripts/cuda-check.sh pack' first and carry .device"; exit 2; }
  {
    echo "commit $(cat .device/commit 2>/dev/null)"
    nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.sm,clocks.max.sm,power.draw,power.limit --format=csv
    cat .device/resource-usage.txt
  } >"$OUT/gpu.txt" 2>&1
  local gpu slug
  gpu="$(nvidia-smi --query-gpu=name --format=csv,noheader | head -1)"
  slug="$(echo "${gpu:-unknown-gpu}" | tr 'A-Z' 'a-z' | tr -cs 'a-z0-9' '-' | sed 's/-$//')"
  echo "GPU: $gpu" | tee "$summary"

  local t0=$SECONDS
  if want tests; then
  # 1. The device tests (parity with the CPU reference, Fig. 2, overflow, emulation agreement).
  timeout 120 "$bin/test_cuda" --gtest_output="json:$OUT/test_cuda.json" >"$OUT/test_cuda.log" 2>&1
  local tests_rc=$?
  echo "device tests: exit $tests_rc ($((SECONDS - t0)) s); $(grep -E '^\[  (PASSED|FAILED|SKIPPED) +\] [0-9]+ test' "$OUT/test_cuda.log" | tr '\n' ' ')" | tee -a "$summary"
  grep -m1 -E 'skipped, no GPU|Failure' -A3 "$OUT/test_cuda.log" | tee -a "$summary"

  fi

  if want realtime; then
  # 1b. The haptic runtime stepping on the GPU (the built-in procedure, a scripted device, 0.5 s),
  # its recording replayed bit for bit on the GPU and within the parity tolerance on the CPU. Its
  # outputs stay in /tmp (the summary says what happened); about a minute at most.
  local rt=/tmp/dentsph-realtime
  t0=$SECONDS
  timeout 40 "$bin/dentsph" run --realtime --backend cuda --device scripted --duration 0.5 -q --out "$rt" \
    >"$rt.log" 2>&1
  echo "realtime on cuda: exit $? ($((SECONDS - t0)) s); $(grep -m1 '^simulation' "$rt.log")" | tee -a "$summary"
  for b in cuda cpu; do
    timeout 40 "$bin/dentsph" replay "$rt/recording" --backend "$b" >>"$rt.log" 2>&1
    echo "replay on $b: exit $? (0: bit for bit on cuda, within the parity tolerance on cpu); $(tail -1 "$rt.log")" |
      tee -a "$summary"
  done
  fi

  if want sanitize; then
  # 2. compute-sanitizer on parity tests of small scenes (the tools slow every launch down).
  local filter='Scenes/CudaParity.MatchesGridStepOver100Steps/side4_reach1_seed1:Cuda.BondOverflowCountedAsOnTheCpu'
  : >"$OUT/sanitizer.log"
  local tool rc
  for tool in memcheck racecheck; do
    t0=$SECONDS
    local extra=()
    [ "$tool" = memcheck ] && extra=(--leak-check full)
    timeout 100 compute-sanitizer --tool "$tool" "${extra[@]}" --error-exitcode 99 "$bin/test_cuda" --gtest_filter="$filter" \
      >>"$OUT/sanitizer.log" 2>&1
    rc=$?
    echo "compute-sanitizer $tool: exit $rc ($((SECONDS - t0)) s); $(grep -E 'ERROR SUMMARY|RACECHECK SUMMARY' "$OUT/sanitizer.log" | tail -1)" |
      tee -a "$summary"
  done

  fi

  if want bench; then
  # 3. The benchmark: the dental scene, the sweep to 2 million particles, stage times.
  t0=$SECONDS
  local args=(bench --backend cuda --json "$OUT/$slug.json")
  [ "$quick" = "--quick" ] && args+=(--quick)
  timeout 150 "$bin/dentsph" "${args[@]}" >"$OUT/$slug.txt" 2>&1
  echo "bench: exit $? ($((SECONDS - t0)) s), $OUT/$slug.json" | tee -a "$summary"
  grep -m1 '^error' "$OUT/$slug.txt" | tee -a "$summary"
  sed -n '/^machine/,$p' "$OUT/$slug.txt" | tee -a "$summary"

  fi

  if want tune; then
  # 4. Launch shapes of the neighbour passes, without a rebuild (short runs; compare, then set the
  # default in cuda_stepper.cpp).
  local b
  for b in 32 64 128 256; do
    echo "neighbour block $b: $(DENTSPH_CUDA_NEIGHBOUR_BLOCK=$b timeout 25 "$bin/dentsph" bench --backend cuda --quick --repeats 3 2>&1 |
      grep -E 'cuda: +[0-9]|^ +[0-9]+ .* cuda ' | awk '{printf "%s ", $0}')" | tee -a "$summary"
  done
  # Cells of h / 2 searched two deep: 42% fewer candidates, 125 cells instead of 27.
  echo "grid reach 2: $(timeout 25 "$bin/dentsph" bench --backend cuda --quick --repeats 3 --grid-reach 2 2>&1 |
    grep -E '^ +[0-9]+ .* cuda ' | awk '{printf "%s ", $0}')" | tee -a "$summary"
  fi
}

case "$mode" in
  pack) pack ;;
  device) shift; device "$@" ;;
  *) sed -n '2,18p' "$0"; exit 2 ;;
esac
