#!/usr/bin/env bash
# Installs dbss's build and test dependencies from Debian 12 packages.
# Runs apt-get only when something is missing, so repeated runs are quick.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config   # toolchain
  clang libclang-rt-14-dev                       # second compiler, sanitizers, libFuzzer
  libdraco-dev libzstd-dev                       # container payloads (decoder)
  libtinygltf-dev nlohmann-json3-dev             # glTF reading and writing (io); header-only
  libnanoflann-dev libeigen3-dev                 # KD-tree queries, quadrics (encoder)
  libopenmesh-dev                                # QEM decimation (encoder); differential tests
  catch2                                         # tests (Catch2 v2)
  libcgal-dev                                    # rd_bench's peers only (reconstruction); header-only
  libmeshoptimizer-dev                           # lod_bench only: the LOD chain it compares against
  pybind11-dev python3-dev python3-numpy         # the Python module (python/, DBSS_BUILD_PYTHON) for /usr/bin/python3
  python3-pytest python3-dask python3-distributed  # its tests; dbss.batch's engine
)
# Optional, for scripts/plot-rd.py's plots: apt-get install python3-matplotlib

# `install-deps.sh web`: the WebAssembly build and the browser tests
# (scripts/web-build.sh) also need emscripten (with its prebuilt system
# libraries), Debian's Chromium, dpkg-dev for `apt-get source`, and Draco's
# command-line tools for the browser benchmark.  Node.js
# with npm is taken from PATH when present (Debian's npm package conflicts
# with a NodeSource node); otherwise Debian's.
if [ "${1:-}" = web ]; then
  packages=(emscripten chromium dpkg-dev xz-utils draco)  # draco: draco_encoder for web/bench/
  command -v node >/dev/null && command -v npm >/dev/null || packages+=(nodejs npm)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo="sudo"
fi
echo "install-deps: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
