#!/usr/bin/env bash
# Installs the Debian 12 packages dentsph builds, tests and benchmarks with.
set -euo pipefail
packages=(
  cmake ninja-build ccache g++ pkg-config git
  nlohmann-json3-dev libcli11-dev libspdlog-dev libfmt-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libassimp-dev libstb-dev
  # the paste's surface: OpenVDB's level sets and meshes (src/surface; its headers need Boost's)
  libopenvdb-dev libboost-dev libtbb-dev
  # the spectrum of the force a realtime run renders (src/haptics/force_spectrum.cpp)
  libfftw3-dev
  # the tutor's report: the plotting library bundled into report.html, the session store (SQLite,
  # and PostgreSQL's client library), the browser its tests render the report in, and the
  # PostgreSQL server its store tests start
  libjs-chart.js libsqlite3-dev libpq-dev chromium postgresql
  # dentsph-viewer, and its tests under a virtual display with Mesa's software OpenGL
  libglfw3-dev libepoxy-dev libimgui-dev libglm-dev xvfb xauth libgl1-mesa-dri libglx-mesa0
  # the benchmark scripts (bench/*.sh) read the runs' JSON
  python3
)
# --sanitizers: also clang 14, its runtimes (libFuzzer, the sanitizers) and LLVM's OpenMP, for the
# tsan preset (Archer makes OpenMP visible to ThreadSanitizer) and the fuzz preset (scripts/fuzz.sh).
if [ "${1:-}" = "--sanitizers" ]; then
  packages+=(clang-14 libomp-14-dev libclang-rt-14-dev)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
echo "install-deps: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
