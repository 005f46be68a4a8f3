#!/usr/bin/env bash
# Two builds of dentsph under the hand, alternated (A B A B ...): `dentsph run --realtime --device
# scripted` on a procedure (default: the built-in one, whole), ROUNDS rounds. Prints each run's
# haptic-loop period p99 and max, deadline misses, force in air p95, the hard contact's field
# rebuilds, the simulation's real-time factor and the fill; then the medians of each build and
# B over A. The baseline for every number is the other build, measured in the same rounds.
# Usage: bench/realtime_ab.sh A_BUILD_DIR B_BUILD_DIR
#        ROUNDS=3 PROCEDURE=scenes/uncured_procedure.json DURATION=10 bench/realtime_ab.sh build-a build-b
# Run on an idle machine: each run takes every core.
set -euo pipefail
a="$1"
b="$2"
rounds="${ROUNDS:-2}"
args=()
[[ -n "${PROCEDURE:-}" ]] && args+=(--procedure "$PROCEDURE")
[[ -n "${DURATION:-}" ]] && args+=(--duration "$DURATION")
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

# one NAME BUILD: a run into $tmp/NAME; prints its numbers on one line.
one() {
  local name="$1" build="$2"
  "$build/apps/cli/dentsph" run --realtime --device scripted "${args[@]}" --out "$tmp/$name" -q >/dev/null
  python3 - "$tmp/$name/summary.json" "$name" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
def deep(d, key):  # the first value of `key` anywhere in the summary
    if isinstance(d, dict):
        if key in d: return d[key]
        for v in d.values():
            r = deep(v, key)
            if r is not None: return r
    return None
h = s["haptic"]
row = {
  "period_p99_us": h["period_p99_us"], "period_max_us": h["period_max_us"],
  "deadline_misses": h["deadline_misses"], "ticks": h["ticks"],
  "force_in_air_p95_N": h["free_air"]["free_p95_N"],
  "field_rebuilds": h.get("hard_contact", {}).get("rebuilds", 0),
  "realtime_factor": s["sim"]["realtime_factor"],
  "fill": deep(s, "fill_fraction"),
}
print(sys.argv[2], json.dumps(row))
PY
}

for r in $(seq 1 "$rounds"); do
  one "A-$r" "$a" | tee -a "$tmp/rows"
  one "B-$r" "$b" | tee -a "$tmp/rows"
done
python3 - "$tmp/rows" <<'PY'
import json, statistics, sys
rows = {"A": [], "B": []}
for line in open(sys.argv[1]):
    name, js = line.split(" ", 1)
    rows[name[0]].append(json.loads(js))
print("\nmedians (A, B, B/A):")
for k in rows["A"][0]:
    ma = statistics.median(r[k] for r in rows["A"])
    mb = statistics.median(r[k] for r in rows["B"])
    print(f"  {k:22s} {ma:12.4g} {mb:12.4g} {mb / ma if ma else float('nan'):8.3f}")
PY
