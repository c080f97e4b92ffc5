#!/usr/bin/env bash
# The decoder-only build (issue 14): format, decoder, io and a dbss command
# with `info`, `decode` and `export`, configured with -DDBSS_BUILD_ENCODER=OFF on a
# compiler that cannot see Eigen or nanoflann: find_package for either is
# disabled, and a directory of poisoned headers (#error) comes first on the
# include path, so reaching an Eigen or nanoflann include fails the build.
# Then the install is used by a separate project through
# find_package(dbss COMPONENTS decoder), and the command decodes the golden
# files to their recorded hashes.  Called by scripts/test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
work=${1:-build-decoder-only}
case $work in /*) ;; *) work="$PWD/$work" ;; esac  # absolute: the install prefix below needs one
rm -rf "$work"
mkdir -p "$work/poison/Eigen"
for h in Eigen/Core Eigen/Dense Eigen/Sparse Eigen/Eigenvalues nanoflann.hpp; do
  echo "#error \"decoder-only build reached <$h>\"" > "$work/poison/$h"
done
# The poison works: a file including Eigen must fail to compile.
echo '#include <Eigen/Dense>' > "$work/poison-check.cpp"
if c++ -I"$work/poison" -isystem /usr/include/eigen3 -fsyntax-only "$work/poison-check.cpp" 2>/dev/null; then
  echo "decoder-only: the poisoned Eigen header did not stop a compile" >&2
  exit 1
fi

cmake -S . -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DDBSS_BUILD_ENCODER=OFF \
  -DDBSS_BUILD_BENCH=OFF -DDBSS_WERROR=ON -DCMAKE_INSTALL_PREFIX="$work/prefix" \
  -DCMAKE_DISABLE_FIND_PACKAGE_Eigen3=ON -DCMAKE_DISABLE_FIND_PACKAGE_nanoflann=ON \
  -DCMAKE_CXX_FLAGS="-I$work/poison" >/dev/null
cmake --build "$work/build" -j "$jobs"
cmake --install "$work/build" >/dev/null
for lib in dbss_encoder dbss_measure; do
  if ls "$work/prefix"/lib*/lib$lib.* "$work/build/lib/lib$lib".* >/dev/null 2>&1; then
    echo "decoder-only: $lib was built" >&2
    exit 1
  fi
done

dbss="$work/build/bin/dbss"
# encode and compare say they are missing; info and decode work.
if "$dbss" encode examples/double-torus.xyz -o "$work/x.dbss" 2>"$work/encode.err"; then
  echo "decoder-only: dbss encode succeeded without an encoder" >&2
  exit 1
fi
grep -q "built without the encoder" "$work/encode.err"
# Every golden level decodes to its recorded hash (spec/decoding.md section 8).
for f in tests/golden/v1/*.dbss; do
  "$dbss" info --hashes "$f" | awk '{print $NF}' | cmp -s - "${f%.dbss}.hashes" || {
    echo "decoder-only: $f does not decode to ${f%.dbss}.hashes" >&2
    exit 1
  }
  "$dbss" decode "$f" -o "$work/out.ply" >/dev/null
  "$dbss" export "$f" -o "$work/out.glb" >/dev/null
done

cmake -S tests/install/consumer -B "$work/consumer" -G Ninja -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/consumer" >/dev/null
"$work/consumer/consumer" tests/golden/v1/torus-4-levels.dbss | grep -q "decoder-only consumer ok"
echo "decoder-only: built without Eigen and nanoflann; info, decode, export and a find_package(dbss COMPONENTS decoder) consumer work"
