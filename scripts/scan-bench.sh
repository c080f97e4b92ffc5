#!/usr/bin/env bash
# The real-scan regression table (issue 13): installs, fetches the
# libcgal-demo scans when the Debian archive is reachable (without them the
# bench runs on its hand-made defective shapes only), builds Release and
# runs scan_bench: per input, what came out, the clamped share, the
# points->surface distance, the encode time and the self-check's warnings.
# Extra arguments go to scan_bench (e.g. --levels 3, --surface closed,
# --keep-outliers, or parts of input names to run only those).
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install-deps.sh
bash scripts/fetch-test-data.sh || echo "scan-bench: libcgal-demo data unavailable; defective shapes only" >&2
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build --target scan_bench
build/bin/scan_bench "$@"
