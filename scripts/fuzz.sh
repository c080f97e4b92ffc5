#!/usr/bin/env bash
# Builds the libFuzzer targets with clang and runs each for FUZZ_SECONDS
# (default 60) on a copy of its corpus.  Fails on any crash, leak, timeout or
# out-of-memory; the input that failed is left in build-fuzz/crashes/ to be
# added to fuzz/corpus/<target>/ with its fix.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${FUZZ_SECONDS:-60}
jobs=$(nproc 2>/dev/null || echo 2)

cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DDBSS_BUILD_FUZZ=ON -DDBSS_BUILD_TESTS=OFF -DDBSS_BUILD_BENCH=OFF -DDBSS_BUILD_TOOLS=OFF >/dev/null
cmake --build build-fuzz -j "$jobs" --target container_fuzzer decode_fuzzer gltf_fuzzer

mkdir -p build-fuzz/crashes
status=0
for target in container decode gltf; do
  work=$(mktemp -d)
  cp -r "fuzz/corpus/$target/." "$work/"
  echo "== fuzz: $target for ${seconds}s =="
  set +e
  build-fuzz/bin/${target}_fuzzer "$work" -max_total_time="$seconds" -max_len=65536 -timeout=10 \
    -rss_limit_mb=2048 -artifact_prefix="build-fuzz/crashes/${target}-" -print_final_stats=1 > "$work.log" 2>&1
  rc=$?
  set -e
  grep -E "^(stat::|SUMMARY|Done|==[0-9]+==ERROR)" "$work.log" || true
  if [ $rc -ne 0 ] || ls build-fuzz/crashes/${target}-* >/dev/null 2>&1; then
    tail -n 40 "$work.log"
    echo "fuzz: $target found a failing input:" build-fuzz/crashes/${target}-*
    status=1
  fi
  rm -rf "$work" "$work.log"
done
exit $status
