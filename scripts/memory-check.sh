#!/usr/bin/env bash
# Runs each command of the program under an address-space limit (ulimit -v, default 2 GiB) on its
# largest documented input (docs/limits.md), and checks that each ends with a result
# (exit 0) or a refusal (exit 2), never std::bad_alloc, an abort or a signal.
#
#   scripts/memory-check.sh [BUILD_DIR] [LIMIT_MB]      (default: build/release, 2048)
#
# Writes its inputs and outputs under a temporary folder; prints a line a command and a summary.
set -uo pipefail
cd "$(dirname "$0")/.."
bin="${1:-build/release}/apps/cli/dentsph"
limit_mb="${2:-2048}"
[ -x "$bin" ] || { echo "no $bin: build it first (cmake --preset release && cmake --build build/release)"; exit 2; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
failed=0

# check NAME EXPECTED_CODES PATTERN COMMAND...: runs COMMAND under the limit; it must exit with one
# of EXPECTED_CODES, print a line matching PATTERN (the result or the refusal expected: an exit 2
# for another reason, a mistyped option, fails), and never run out of memory.
check() {
  local name="$1" want="$2" pattern="$3"
  shift 3
  local out="$work/$name.log" t0=$SECONDS
  (ulimit -v $((limit_mb * 1024)); timeout 600 "$@") >"$out" 2>&1
  local rc=$?
  local verdict=ok
  if [[ " $want " != *" $rc "* ]] || ! grep -qE "$pattern" "$out" ||
    grep -qE "bad_alloc|terminate called|Aborted|Segmentation" "$out"; then
    verdict=FAILED
    failed=$((failed + 1))
  fi
  printf '%-24s exit %3d (%3d s) %s: %s\n' "$name" "$rc" $((SECONDS - t0)) "$verdict" \
    "$( (grep -m1 -E "$pattern" "$out" || tail -1 "$out") | cut -c1-150)"
}

# The main job (the built-in dental procedure), briefly.
check run-default "0" "^wrote" "$bin" run --duration 0.05 -q --out "$work/run"
# A scene file of the largest scene the limits allow (9.9 million particles in one block, under
# the 10 million): refused before it is made for the memory it needs.
python3 - "$work/big_scene.json" <<'PY'
import json, sys
d = json.load(open("scenes/blob_on_plate.json"))
# h is 0.02 m: the finest spacing allowed is h / 10; a box of 215^3 particles at it.
d["blocks"][1] = {"role": "material", "shape": "box", "min": [-0.214, -0.214, 0.0], "max": [0.214, 0.214, 0.428], "spacing": 0.002}
json.dump(d, open(sys.argv[1], "w"))
PY
check validate-10M "2" "the scene needs about [0-9.]+ GiB" "$bin" validate "$work/big_scene.json"
check run-10M "2" "the scene needs about [0-9.]+ GiB" "$bin" run "$work/big_scene.json" --steps 1 -q --out "$work/big"
# A tooth mesh at the triangle limit: a closed sphere 10 mm across of 1 million triangles (a
# binary STL), and one over the limit (2 million, the header alone: a sparse file).
python3 - "$work" <<'PY'
import math, struct, sys, os
rings, segments = 501, 1000  # 2 * segments * (rings - 1) = 1,000,000 triangles
r = 5.0
def p(i, j):
    th, ph = math.pi * i / rings, 2 * math.pi * j / segments
    return (r * math.sin(th) * math.cos(ph), r * math.sin(th) * math.sin(ph), r * math.cos(th))
tris = []
for j in range(segments):
    j1 = (j + 1) % segments
    tris.append(((0, 0, r), p(1, j), p(1, j1)))
    tris.append(((0, 0, -r), p(rings - 1, j1), p(rings - 1, j)))
    for i in range(1, rings - 1):
        a, b, c, d = p(i, j), p(i + 1, j), p(i + 1, j1), p(i, j1)
        tris.append((a, b, c))
        tris.append((a, c, d))
with open(os.path.join(sys.argv[1], "limit.stl"), "wb") as f:
    f.write(b"sphere".ljust(80, b" ") + struct.pack("<I", len(tris)))
    for t in tris:
        f.write(struct.pack("<12fH", 0, 0, 0, *t[0], *t[1], *t[2], 0))
with open(os.path.join(sys.argv[1], "over.stl"), "wb") as f:
    f.write(b"x" * 80 + struct.pack("<I", 2000000))
    f.truncate(84 + 50 * 2000000)
PY
check mesh-1M "0" "^wrote" "$bin" run --mesh "$work/limit.stl" --steps 1 -q --out "$work/mesh"
check mesh-2M "2" "holds 2000000 triangles" "$bin" run --mesh "$work/over.stl" --steps 1 -q --out "$work/mesh2"
# The largest depth-of-cure mould (--spacing 0.02 --mould-length 50: 79 million particles).
check depth-of-cure-largest "2" "7.86e\+07 particles" "$bin" material-test depth-of-cure --spacing 0.02 --mould-length 50
# report: a run folder whose summary is at the size limit (16 MB of JSON) and one over it.
cp -r "$work/run" "$work/run_big"
python3 - "$work/run_big/summary.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
d["padding"] = ["x" * 1000] * 16000
json.dump(d, open(sys.argv[1], "w"))
PY
check report-16MB-summary "0" "^wrote" "$bin" report "$work/run_big" --out "$work/big.html"
truncate -s 300M "$work/run_big/summary.json"
check report-300MB-summary "2" "300 MB, more than the 16 MB" "$bin" report "$work/run_big" --out "$work/big2.html"
# replay: a realtime session's recording replayed, and one whose haptic.csv is larger than a
# session writes (600 MB, a sparse file): refused before it is read.
check realtime-short "0" "^wrote" "$bin" run --realtime --device scripted --duration 0.5 --threads 1 -q --out "$work/rt"
check replay "0" "^wrote" "$bin" replay "$work/rt/recording" --threads 1 --out "$work/replayed"
truncate -s 600M "$work/rt/recording/haptic.csv"
check replay-600MB-recording "2" "600 MB, more than the 512 MB" "$bin" replay "$work/rt/recording" --out "$work/replayed2"
# The viewer under a virtual display, the paste drawn as its surface (OpenVDB, Mesa's software
# OpenGL): skipped, saying so, where the viewer or xvfb-run is not there.
viewer="$(dirname "$bin")/../viewer/dentsph-viewer"
if [ -x "$viewer" ] && command -v xvfb-run > /dev/null; then
  check viewer-surface "0" "^wrote" xvfb-run -a -s "-screen 0 1280x800x24" "$viewer" --frames 30 --surface \
    --threads 2 --screenshot "$work/viewer.png"
else
  echo "viewer-surface           skipped: no $viewer or no xvfb-run"
fi
# The virtual handling tests (docs/model.md, "Handling tests"): each rig is of one size (the paste at
# 0.3 mm in a mould or between plates), so each runs as a user runs it; the depth-of-cure mould at
# its finest spacing is refused above, and one at its default spacing runs here.
for t in rheometer slump packing tack condensation; do
  check "material-test-$t" "0" "published" "$bin" material-test "$t" --threads 2
done
check material-test-depth-of-cure "0" "depth of cure: " "$bin" material-test depth-of-cure
# The benchmark's short sweep.
check bench-quick "0" "steps/s" "$bin" bench --quick --repeats 1

echo "memory check under ulimit -v ${limit_mb} MB: ${failed} failed"
[ "$failed" -eq 0 ]
