#!/usr/bin/env bash
# Real time under the hand, both solvers, alternated: `dentsph run --realtime --device scripted` on
# a procedure (default: scenes/uncured_procedure.json, the built-in filling before it cured: its
# first seconds are all handling), ROUNDS rounds of
#   paced  iisph  (never ahead of the wall clock: the real-time factor a user gets, at most 1)
#   paper         (the paper's step; slower than real time, so paced and free-running alike)
#   free   iisph  (--free-run: as fast as the step goes)
# each DURATION wall seconds. Prints each run's haptic and simulation lines, then per round the
# simulated seconds per wall second of each and their ratio, measured two ways:
#   whole run:   each run's own simulated span over its wall time. Not the same work: in 5 wall
#                seconds the paper's step gets through the procedure's first 1.4 s (one increment
#                and the next one's start), the free-running iisph solver through 7 to 9 s (every
#                increment, three times the paste);
#   same window: over the simulated span both runs covered (the paper run's), from the recordings'
#                per-step wall times (recording/steps.csv): the same paste, dispensed by simulated
#                time, on both. (The hand follows the wall clock, so the instrument is elsewhere in
#                its path at a given simulated time in the two runs.)
# Usage: bench/realtime_solvers.sh [BUILD_DIR]     (default: build/release)
#        ROUNDS=3 DURATION=5 PROCEDURE=scenes/uncured_procedure.json bench/realtime_solvers.sh
# Run on an idle machine: the runs take every core.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build/release}"
cli="$build/apps/cli/dentsph"
rounds="${ROUNDS:-3}"
duration="${DURATION:-5}"
procedure="${PROCEDURE:-scenes/uncured_procedure.json}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

# run NAME ARGS...: one realtime run into $tmp/NAME, its summary lines printed.
run() {
  local name="$1"
  shift
  echo "== $name"
  "$cli" run --realtime --device scripted --procedure "$procedure" --duration "$duration" --out "$tmp/$name" -q "$@" |
    grep -E "^(haptic loop|force|simulation)"
}

# sim_rate DIR [T]: simulated seconds per wall second over the run's first T simulated seconds
# (all of it without T), from the recording's wall time at the start of each step.
sim_rate() {
  local dir="$1" window="${2:-}"
  local sim steps
  sim=$(grep -m1 '"sim_time_s"' "$dir/summary.json" | sed 's/.*: *//; s/,$//')
  steps=$(awk -F, 'NR > 1 { n = $1 } END { print n + 1 }' "$dir/recording/steps.csv")
  awk -F, -v sim="$sim" -v steps="$steps" -v window="$window" '
    NR == 2 { t0 = $2 }
    NR > 1 { dt = sim / steps; k = $1; if (window == "" || k * dt <= window + 1e-12) { t = $2; last = k } }
    END { printf "%.4f %.4f\n", last * dt / (t - t0), last * dt }' "$dir/recording/steps.csv"
}

for r in $(seq 1 "$rounds"); do
  run "paced-iisph-$r" --solver iisph
  run "paper-$r" --solver paper
  run "free-iisph-$r" --solver iisph --free-run
done

echo
echo "# round | paced iisph | paper | free iisph (sim s per wall s, whole run) | ratio | same window (s simulated): paper, free iisph, ratio"
for r in $(seq 1 "$rounds"); do
  read -r paced _ < <(sim_rate "$tmp/paced-iisph-$r")
  read -r paper span < <(sim_rate "$tmp/paper-$r")
  read -r free _ < <(sim_rate "$tmp/free-iisph-$r")
  read -r free_window _ < <(sim_rate "$tmp/free-iisph-$r" "$span")
  awk -v r="$r" -v a="$paced" -v p="$paper" -v f="$free" -v fw="$free_window" -v s="$span" \
    'BEGIN { printf "%d | %.3f | %.3f | %.3f | %.1f x | %.2f s: %.3f, %.3f, %.1f x\n", r, a, p, f, f / p, s, p, fw, fw / p }'
done
