#!/usr/bin/env bash
# The benchmark table of the README: installs, fetches the libcgal-demo scans
# when the Debian archive is reachable (the bench runs without them), builds
# Release and runs the encoder per stage, the decoder per level and the
# comparison against full-vertex DSS and Draco on the example set.
# Extra arguments go to codec_bench (e.g. --levels 4, or point files).
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install-deps.sh
bash scripts/fetch-test-data.sh || echo "bench: libcgal-demo data unavailable; benchmarking the shipped example only" >&2
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build --target codec_bench
build/bin/codec_bench "$@"
