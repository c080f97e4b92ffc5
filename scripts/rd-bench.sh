#!/usr/bin/env bash
# Rate-distortion of dbss against advancing front + Draco and Poisson +
# Draco, errors against the true meshes (bench/rd_bench.cpp): installs the
# dependencies (CGAL for the peers), fetches the libcgal-demo meshes, builds
# rd_bench, prints a table per shape and writes build/rd/rd.csv and, when
# matplotlib is there (apt-get install python3-matplotlib), one PNG per
# shape in build/rd/.  Arguments go to rd_bench (e.g. --points 10000
# --levels 4, or mesh files); rerun it after an encoder change to compare.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/fetch-test-data.sh || echo "rd-bench: test data could not be fetched; only meshes already present run" >&2
build=${BUILD_DIR:-build}
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j"${JOBS:-2}" --target rd_bench
mkdir -p "$build/rd"
"$build/bin/rd_bench" --csv "$build/rd/rd.csv" "$@"
# Debian's matplotlib is for Debian's python, whatever python3 comes first on PATH.
python=/usr/bin/python3
[ -x "$python" ] || python=python3
if "$python" -c "import matplotlib" 2>/dev/null; then
  "$python" scripts/plot-rd.py "$build/rd/rd.csv" "$build/rd"
else
  echo "rd-bench: no matplotlib (apt-get install python3-matplotlib): no plots" >&2
fi
