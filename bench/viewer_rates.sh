#!/usr/bin/env bash
# Frames per second of dentsph-viewer under Xvfb (Mesa llvmpipe) on the built-in dental scene, and
# the simulation's steps per second with the viewer drawing against the same scene stepped without
# a window (`dentsph bench`'s dental scene on the same thread count), alternated so that both see
# the same machine. Medians of REPEATS.
# Usage: bench/viewer_rates.sh [BUILD_DIR] [REPEATS] [STEPS]
set -euo pipefail
build="${1:-build/release}"
repeats="${2:-3}"
steps="${3:-3000}"
threads="${THREADS:-1}"
viewer="$build/apps/viewer/dentsph-viewer"
cli="$build/apps/cli/dentsph"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
echo "{\"actions\": [{\"step\": $steps, \"action\": \"end\"}]}" > "$tmp/end.json"
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
for k in $(seq "$repeats"); do
  "$cli" bench --threads "$threads" --repeats 1 --quick --json "$tmp/b.json" > /dev/null 2>&1
  python3 -c "import json; print(json.load(open('$tmp/b.json'))['default_scene']['steps_per_second']['$threads'])" \
    >> "$tmp/offline"
  for fps in 60 0; do
    xvfb-run -a -s '-screen 0 1280x800x24' "$viewer" --threads "$threads" --max-fps "$fps" --frames 1 \
      --script "$tmp/end.json" --summary "$tmp/v.json" --timeout 600 > /dev/null
    python3 -c "import json; j = json.load(open('$tmp/v.json')); print(j['fps_median'], j['sim']['steps_per_second'])" \
      >> "$tmp/viewer_$fps"
  done
done
off=$(median < "$tmp/offline")
printf 'machine: %s, %s cores; %s runs of %s steps, %s simulation thread(s)\n' \
  "$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)" "$(nproc)" "$repeats" "$steps" "$threads"
printf '%-34s %12s %14s %10s\n' "configuration" "render fps" "sim steps/s" "vs offline"
printf '%-34s %12s %14.0f %10s\n' "no window (dentsph bench)" "-" "$off" "1.00"
for fps in 60 0; do
  f=$(cut -d' ' -f1 "$tmp/viewer_$fps" | median)
  s=$(cut -d' ' -f2 "$tmp/viewer_$fps" | median)
  label="viewer, frames capped at $fps"
  [ "$fps" = 0 ] && label="viewer, frames uncapped"
  printf '%-34s %12.1f %14.0f %10.2f\n' "$label" "$f" "$s" "$(awk -v a="$s" -v b="$off" 'BEGIN {print a / b}')"
done
