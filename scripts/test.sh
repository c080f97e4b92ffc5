#!/usr/bin/env bash
# Every test: install, build with gcc and run the suite, then build with
# clang under ASan+UBSan and run it again.  README command (b); .ci/run.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install-deps.sh
# Real scans for the scan tests.  Under CI=true a failed fetch stops the run
# (and the scan tests fail on missing data, tests/test_data.h); without it,
# offline, the scan tests skip.
if ! bash scripts/fetch-test-data.sh; then
  if [ "${CI:-}" = true ]; then
    echo "test: libcgal-demo data unavailable and CI=true: failing (offline, run without CI=true to skip the scan tests)" >&2
    exit 1
  fi
  echo "test: libcgal-demo data unavailable; the scan tests skip" >&2
fi
jobs=$(nproc 2>/dev/null || echo 2)
# Each stage says when it starts, so a slow CI run shows where its time went.
stage() { echo "== $* == (${SECONDS} s so far)"; }

stage "gcc, Release"
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=g++ -DDBSS_WERROR=ON -DDBSS_BUILD_PYTHON=ON
cmake --build build -j "$jobs"
rm -rf build/tests/gltf-out  # only this run's glTF files reach the validator below
ctest --test-dir build --output-on-failure -j "$jobs" | tee build/ctest.log

# The Python module (built above into build/python) against the command
# line it was built with, and dbss.batch on a two-worker Dask cluster.
stage "python"
PYTHONPATH="$PWD/build/python" /usr/bin/python3 -m pytest -q python/tests

# The decoder compiled to WebAssembly from the same sources, its JavaScript
# API, and the viewer in headless Chromium (web/, issue 17): every level
# must hash as build/bin/dbss's does.
stage "web"
bash scripts/web-build.sh build-web
DBSS_BIN="$PWD/build/bin/dbss" bash web/test/run.sh

# The glTF files the gcc suite just wrote (`dbss decode` and `dbss export`
# in tests/cli, io_tests in tests/gltf-out) through the Khronos validator,
# pinned in tests/gltf/package-lock.json: any error fails.  About 3 s.
# Offline, as with the scan data above, the step is skipped unless CI=true.
stage "glTF validator"
if (cd tests/gltf && npm ci --no-audit --no-fund --loglevel=error); then
  node tests/gltf/validate.mjs build/tests/cli build/tests/gltf-out
elif [ "${CI:-}" = true ]; then
  echo "test: npm ci in tests/gltf failed and CI=true: failing" >&2
  exit 1
else
  echo "test: the glTF validator could not be installed (offline?); its step is skipped" >&2
fi

# Format, decoder and io alone, where Eigen and nanoflann cannot be reached.
stage "decoder-only build"
bash scripts/decoder-only.sh build-decoder-only

stage "clang, ASan + UBSan"
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DDBSS_SANITIZE=address,undefined -DDBSS_BUILD_BENCH=OFF -DDBSS_WERROR=ON
cmake --build build-asan -j "$jobs"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build-asan --output-on-failure -j "$jobs" | tee build-asan/ctest.log

# The decoder's helper threads synchronise by hand (decoder/src/parallel.h):
# its tests once more under ThreadSanitizer.
stage "clang, TSan: decoder tests"
cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DDBSS_SANITIZE=thread -DDBSS_BUILD_BENCH=OFF -DDBSS_WERROR=ON >/dev/null
cmake --build build-tsan -j "$jobs" --target codec_tests
TSAN_OPTIONS=halt_on_error=1 build-tsan/bin/codec_tests

# The decoder's output is part of the format: the golden-file test must give
# the same bits with optimisation off (gcc -O0) and with clang -O3 too.
for cfg in "g++ Debug" "clang++ Release"; do
  set -- $cfg
  dir="build-determinism-${1%++}-$2"
  stage "determinism: $1 $2"
  cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE="$2" -DCMAKE_CXX_COMPILER="$1" -DDBSS_BUILD_BENCH=OFF >/dev/null
  cmake --build "$dir" -j "$jobs" --target codec_tests
  "$dir/bin/codec_tests" "golden files decode to the recorded bits at every level" --warn NoTests
done

# Fuzzing: each libFuzzer target for about a minute (scripts/fuzz.sh).
stage "fuzz"
bash scripts/fuzz.sh

# One closing line for both suites (set -e and pipefail stopped us on any
# failure before here).
passed=0
for log in build/ctest.log build-asan/ctest.log; do
  n=$(sed -n 's/^100% tests passed, 0 tests failed out of \([0-9]*\)$/\1/p' "$log")
  passed=$((passed + ${n:-0}))
done
echo "test.sh: gcc and clang+sanitizer suites, the Python tests, the web build and its browser tests, the glTF validator, the decoder-only build, golden files at -O0 and clang -O3, fuzzing: all clean"
echo "${passed} passed, 0 failed (${SECONDS} s)"
